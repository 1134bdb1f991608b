// SPDX-License-Identifier: GPL-3.0-or-later
// Clean interruption (issue 11; SIGHUP, SIGQUIT and SIGPIPE since issue 23): a signal during the writing stage of a
// real run removes every temporary file, leaves no output at all (no partial set), prints one line on stderr and exits
// with 130 / 143. The run (the seed's reference run, every format, an 8000-pixel-wide preview) writes for about a
// second after 0.3 s of work; the test waits until the first temporary
// `.NAME.ext.tmpPID` appears and then sends the signal.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_interrupt_cli_test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

struct Interrupted {
  int exit_code = -1;
  bool saw_temporary = false;
  std::string err;
  std::vector<std::string> left;  // every file left in the output folder
};

// Starts `aquatoria mesh <args>` with stderr to `err`, stdout to /dev/null, the signals at their
// defaults (aquatoria keeps a signal that was ignored when it started, nohup) and `env` set.
pid_t spawn_mesh(const fs::path& err, const std::vector<std::string>& args,
                 const std::vector<std::pair<const char*, const char*>>& env = {}) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  if (std::freopen(err.c_str(), "w", stderr) == nullptr || std::freopen("/dev/null", "w", stdout) == nullptr)
    ::_exit(99);
  for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE}) std::signal(s, SIG_DFL);
  for (const auto& [name, value] : env) ::setenv(name, value, 1);
  std::vector<char*> argv{const_cast<char*>(AQ_BINARY), const_cast<char*>("mesh")};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(AQ_BINARY, argv.data());
  ::_exit(98);
}

Interrupted interrupt_run(int sig) {
  aq::testing::TempDir dir;
  const fs::path out = dir / "out", err = dir / "stderr.txt";
  const pid_t pid = spawn_mesh(err, {"--set", "output.png_width=8000", "-o", out.string()});
  Interrupted r;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline && !r.saw_temporary) {
    if (::waitpid(pid, &status, WNOHANG) == pid) break;  // finished before writing: the test fails
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(out, ec))
      r.saw_temporary = r.saw_temporary || e.path().filename().string().find(".tmp") != std::string::npos;
    if (!r.saw_temporary) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (r.saw_temporary) {
    ::kill(pid, sig);
    ::waitpid(pid, &status, 0);
  } else if (::waitpid(pid, &status, WNOHANG) == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  r.err = aq::test::slurp(err);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out, ec)) r.left.push_back(e.path().filename().string());
  return r;
}

void expect_clean(const Interrupted& r, int code, const char* name) {
  ASSERT_TRUE(r.saw_temporary) << "the run ended before its writing stage: " << r.err;
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_THAT(r.left, ::testing::IsEmpty());
  // One line, the last one on stderr, saying how many temporaries it removed (at least the one seen).
  const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
  EXPECT_THAT(last, ::testing::MatchesRegex(std::string("aquatoria: interrupted by ") + name +
                                            "; [1-9][0-9]* temporary file\\(s\\) removed\n"));
  EXPECT_EQ(r.err.find("interrupted"), r.err.rfind("interrupted"));
}

TEST(CliInterrupt, SigtermWhileWritingLeavesNothingAndExits143) {
  expect_clean(interrupt_run(SIGTERM), 143, "SIGTERM");
}

TEST(CliInterrupt, SigintWhileWritingLeavesNothingAndExits130) { expect_clean(interrupt_run(SIGINT), 130, "SIGINT"); }

// Issue 23: a closed terminal (SIGHUP), Ctrl-\ (SIGQUIT) and a reader of stderr that has quit
// (SIGPIPE, e.g. `2>&1 | grep -m1`) left the temporaries behind: they are handled the same way.
TEST(CliInterrupt, SighupWhileWritingLeavesNothingAndExits129) { expect_clean(interrupt_run(SIGHUP), 129, "SIGHUP"); }
TEST(CliInterrupt, SigquitWhileWritingLeavesNothingAndExits131) {
  expect_clean(interrupt_run(SIGQUIT), 131, "SIGQUIT");
}
TEST(CliInterrupt, SigpipeWhileWritingLeavesNothingAndExits141) {
  expect_clean(interrupt_run(SIGPIPE), 141, "SIGPIPE");
}

// Issue 33: a signal that arrived while the process was still starting (the shared libraries'
// constructors, before main) killed it without a word. The handlers are installed before those
// constructors run: a preloaded library whose constructor sleeps holds the process there while
// SIGTERM arrives, and the run ends with the handler's line and 143, having written nothing.
TEST(CliInterrupt, SigtermWhileStartingIsHandled) {
  aq::testing::TempDir dir;
  const fs::path out = dir / "out", err = dir / "stderr.txt";
  // ASAN_OPTIONS: in the sanitizer build the preloaded library comes before ASan's runtime.
  const pid_t pid = spawn_mesh(
      err, {"-o", out.string()},
      {{"LD_PRELOAD", AQ_SLOW_START_LIB}, {"AQ_SLOW_START_MS", "5000"}, {"ASAN_OPTIONS", "verify_asan_link_order=0"}});
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));  // inside the 5 s constructor
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string e = aq::test::slurp(err);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << " without the handler: " << e;
  EXPECT_EQ(WEXITSTATUS(status), 143) << e;
  EXPECT_EQ(e, "aquatoria: interrupted by SIGTERM; 0 temporary file(s) removed\n");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace

}  // namespace cli_interrupt_cli_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23, output side: a commit is all-or-nothing (a rename that fails midway puts the old
// files back), temporaries of dead processes are removed by the next run in the folder, long
// names get temporary names within 255 bytes, paths that are not regular files are named, and
// error messages keep their NUL bytes visible.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/output_files.hpp"
#include "core/temp_registry.hpp"
#include "support/temp_dir.hpp"

namespace unit_core_output_commit_test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// A pid that no process has: a child that has exited and been reaped.
long dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return static_cast<long>(pid);
}

}  // namespace

// The last final name cannot be replaced (it is a non-empty directory): the two files renamed
// before it must go back to their old contents, the third old file stays, and nothing else is
// left in the folder. Before issue 23 the first two kept the new contents (a mixed set).
TEST(OutputCommit, AFailedLastRenameRestoresTheOldFiles) {
  aq::testing::TempDir dir;
  std::ofstream(dir / "a.txt") << "old a";
  std::ofstream(dir / "b.txt") << "old b";
  fs::create_directories(dir / "c.txt" / "inside");
  const int before = aq::TempRegistry::in_use();
  {
    aq::OutputSet out(dir.path());
    std::ofstream(out.temp_path("a.txt")) << "new a";
    std::ofstream(out.temp_path("b.txt")) << "new b";
    std::ofstream(out.temp_path("new.txt")) << "new file";
    std::ofstream(out.temp_path("c.txt")) << "new c";
    try {
      out.commit();
      ADD_FAILURE() << "the commit should fail at c.txt";
    } catch (const aq::OutputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("c.txt: cannot rename into place"));
      EXPECT_THAT(e.what(), HasSubstr("none of the 4 new files was kept"));
    }
  }
  EXPECT_EQ(read(dir / "a.txt"), "old a");
  EXPECT_EQ(read(dir / "b.txt"), "old b");
  EXPECT_FALSE(fs::exists(dir / "new.txt"));
  EXPECT_TRUE(fs::is_directory(dir / "c.txt" / "inside"));
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"a.txt", "b.txt", "c.txt"}));
  EXPECT_EQ(aq::TempRegistry::in_use(), before);
}

// A successful commit replaces the old files and leaves no backups.
TEST(OutputCommit, ASuccessfulCommitLeavesOnlyTheNewFiles) {
  aq::testing::TempDir dir;
  std::ofstream(dir / "a.txt") << "old a";
  aq::OutputSet out(dir.path());
  std::ofstream(out.temp_path("a.txt")) << "new a";
  std::ofstream(out.temp_path("b.txt")) << "new b";
  out.commit();
  EXPECT_EQ(read(dir / "a.txt"), "new a");
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"a.txt", "b.txt"}));
}

// An interrupt during a commit (the handler's path) also puts the old file back.
TEST(OutputCommit, TheInterruptHandlerRestoresABackedUpFile) {
  aq::testing::TempDir dir;
  std::ofstream(dir / "a") << "old";
  std::ofstream(dir / "tmp_a") << "new";
  ASSERT_EQ(::link((dir / "a").c_str(), (dir / "bak_a").c_str()), 0);
  const int a = aq::TempRegistry::add(dir / "tmp_a", dir / "a", dir / "bak_a");
  aq::TempRegistry::backed_up(a, false);
  aq::TempRegistry::renaming(a);
  fs::rename(dir / "tmp_a", dir / "a");
  aq::TempRegistry::renamed(a);
  EXPECT_EQ(aq::TempRegistry::remove_registered_temporaries(), 1);
  aq::TempRegistry::release(a);
  EXPECT_EQ(read(dir / "a"), "old");
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"a"}));
}

// A run killed with SIGKILL leaves .NAME.tmpPID files; the next OutputSet in the folder removes
// those of processes that no longer exist, and only those.
TEST(OutputCommit, TemporariesOfDeadProcessesAreRemoved) {
  aq::testing::TempDir dir;
  const long dead = dead_pid();
  const std::string stale = ".mesh.msh.tmp" + std::to_string(dead), stale_bak = ".mesh.nc.bak" + std::to_string(dead);
  const std::string alive = ".mesh.vtu.tmp" + std::to_string(static_cast<long>(::getppid()));
  for (const std::string& n : {stale, stale_bak, alive, std::string(".hidden.tmpfoo"), std::string("keep.tmp12")})
    std::ofstream(dir / n) << "x";
  std::vector<std::string> lines;
  aq::Logger log([&lines](aq::LogLevel, std::string_view m) { lines.emplace_back(m); });
  aq::OutputSet out(dir.path(), log);
  ASSERT_EQ(out.stale_removed().size(), 2u);
  std::vector<std::string> kept{alive, ".hidden.tmpfoo", "keep.tmp12"};
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(names_in(dir.path()), kept);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0] + lines[1], HasSubstr(stale));
  EXPECT_THAT(lines[0], HasSubstr("that no longer runs"));
}

TEST(OutputCommit, TemporaryNamesArePidTagged) {
  EXPECT_EQ(aq::output_temporary_pid(".a.msh.tmp123"), 123);
  EXPECT_EQ(aq::output_temporary_pid(".a.msh.bak9"), 9);
  EXPECT_EQ(aq::output_temporary_pid("a.msh.tmp123"), -1);
  EXPECT_EQ(aq::output_temporary_pid(".a.msh.tmp"), -1);
  EXPECT_EQ(aq::output_temporary_pid(".a.msh.old123"), -1);
}

// A 240-byte name: the final names fit (255 bytes), the temporary ".NAME.tmpPID" would not; it
// is shortened and the commit works. Before issue 23 the temporary failed with ENAMETOOLONG.
TEST(OutputCommit, LongNamesGetShortTemporaries) {
  aq::testing::TempDir dir;
  const std::string name = std::string(240, 'n') + ".msh";
  aq::OutputSet out(dir.path());
  const fs::path tmp = out.temp_path(name);
  EXPECT_LE(tmp.filename().native().size(), 255u);
  std::ofstream(tmp) << "mesh";
  ASSERT_TRUE(fs::exists(tmp));
  out.commit();
  EXPECT_EQ(read(dir / name), "mesh");
  EXPECT_THROW(out.temp_path(std::string(256, 'x')), aq::OutputError);
}

TEST(InputFiles, SpecialFilesAreNamed) {
  aq::testing::TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  std::ofstream(dir / "file") << "text";
  EXPECT_EQ(aq::input_file_problem(dir / "file"), "");
  EXPECT_EQ(aq::input_file_problem(dir / "fifo"), "is a FIFO (named pipe), not a regular file");
  EXPECT_EQ(aq::input_file_problem("/dev/zero"), "is a character device, not a regular file");
  EXPECT_EQ(aq::input_file_problem(dir.path()), "is a directory, not a regular file");
  EXPECT_EQ(aq::input_file_problem(dir / "missing"), "no such file");
  EXPECT_THAT(aq::input_file_problem(dir / "file", 2), HasSubstr("is 4 bytes, more than the 2"));
  EXPECT_EQ(aq::input_file_problem(std::string("a\0b", 3)), "contains a NUL byte");
  EXPECT_EQ(aq::special_file_problem(dir / "missing"), "");
  EXPECT_EQ(aq::output_dir_problem(dir / "file"), "is a regular file, not a directory");
  EXPECT_EQ(aq::output_dir_problem(dir.path()), "");
}

// A message with a NUL byte (from a value or a file) is printed whole: the NUL shows as \0.
TEST(Errors, NulBytesInMessagesAreShownNotCut) {
  const aq::ConfigError e(std::string("key = a\0b: bad", 14));
  EXPECT_STREQ(e.what(), "key = a\\0b: bad");
  EXPECT_EQ(e.exit_code(), 2);
}

}  // namespace unit_core_output_commit_test

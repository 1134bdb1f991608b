// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: run a shell command, capture stdout and stderr separately, return the exit code.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace aq::test {

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `command` through /bin/sh; stdout and stderr are captured into temporary files.
inline CommandResult run_command(const std::string& command) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path() / "aq_cmd";
  std::filesystem::create_directories(dir);
  const auto base = dir / (std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string o = base.string() + ".out", e = base.string() + ".err";
  const std::string full = command + " >" + o + " 2>" + e + " </dev/null";
  const int status = std::system(full.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(o);
  r.err = slurp(e);
  std::filesystem::remove(o);
  std::filesystem::remove(e);
  return r;
}

/// The aquatoria binary under test, with arguments.
inline CommandResult run_aquatoria(const std::string& args) { return run_command(std::string(AQ_BINARY) + " " + args); }

}  // namespace aq::test

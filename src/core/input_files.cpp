// SPDX-License-Identifier: GPL-3.0-or-later
// Input path checks: one stat(2) each, never an open(2) (opening a FIFO blocks).
#include "core/input_files.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

namespace aq {
namespace {

const char* kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO (named pipe)";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

// 0 and the stat of `path`, or errno; NUL bytes are refused before the system call would cut the
// name at the first one.
int stat_of(const std::filesystem::path& path, struct stat& st) {
  if (path.native().find('\0') != std::string::npos) return EINVAL;
  return ::stat(path.c_str(), &st) == 0 ? 0 : errno;
}

}  // namespace

std::string input_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  if (path.native().find('\0') != std::string::npos) return "contains a NUL byte";
  if (path.empty()) return "is empty";
  struct stat st {};
  if (const int err = stat_of(path, st); err != 0)
    return err == ENOENT ? std::string("no such file") : fmt::format("cannot be read: {}", std::strerror(err));
  if (!S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) return "is a directory, not a regular file";
    return fmt::format("is {}, not a regular file", kind_of(st.st_mode));
  }
  if (max_bytes > 0 && static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    return fmt::format("is {} bytes, more than the {} read for a text file", static_cast<std::uintmax_t>(st.st_size),
                       max_bytes);
  return {};
}

std::string special_file_problem(const std::filesystem::path& path) {
  if (path.native().find('\0') != std::string::npos) return "contains a NUL byte";
  struct stat st {};
  if (stat_of(path, st) != 0) return {};
  return S_ISREG(st.st_mode) ? std::string() : input_file_problem(path);
}

std::string output_dir_problem(const std::filesystem::path& path) {
  if (path.native().find('\0') != std::string::npos) return "contains a NUL byte";
  struct stat st {};
  if (stat_of(path, st) != 0 || S_ISDIR(st.st_mode)) return {};
  return fmt::format("is {}, not a directory", S_ISREG(st.st_mode) ? "a regular file" : kind_of(st.st_mode));
}

}  // namespace aq

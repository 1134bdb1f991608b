// SPDX-License-Identifier: GPL-3.0-or-later
// What an input path must be before anything opens it (issue 23): a regular file (after
// symbolic links), not a FIFO that blocks the reader forever, a device such as /dev/zero that
// never ends, a directory or a socket. Text inputs (configs, contours) are also bounded in size,
// so every read of a user's file is finite. The callers add the key or option that named the path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace aq {

/// The largest configuration or contour text file read (64 MiB: real ones are a few kB).
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{64} << 20;

/// "" when `path` names an existing regular file (of at most `max_bytes` when that is not 0);
/// otherwise what it is instead, for a message: "no such file", "is a directory, not a regular
/// file", "is a FIFO (named pipe), not a regular file", "is a character device, not a regular
/// file", "is 70000000 bytes, more than the 67108864 read for a text file", "contains a NUL
/// byte", ... Never opens the file.
std::string input_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes = 0);

/// "" when `path` does not exist or names a regular file; otherwise as input_file_problem (for
/// configuration checks that leave a missing file to the reader, which names it).
std::string special_file_problem(const std::filesystem::path& path);

/// "" when `path` does not exist or is a directory; otherwise what it is (an output folder).
std::string output_dir_problem(const std::filesystem::path& path);

}  // namespace aq

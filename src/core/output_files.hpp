// SPDX-License-Identifier: GPL-3.0-or-later
// All-or-nothing output (ARCHITECTURE §4.8, §9): every file is written under a temporary name
// in the destination folder and renamed only when the whole run succeeded. If the run fails
// (an exception unwinds past the OutputSet), the temporaries are removed: no partial outputs.
// The commit itself is all-or-nothing too: the files it replaces are first hard-linked to backup
// names, and when a rename fails midway the files already renamed are put back (the old file
// where there was one, none where there was none), so the folder holds either the whole new set
// or what it held before. Every temporary is also in the TempRegistry (core/temp_registry.hpp),
// so that an interrupt handler can do the same.
//
// Names in the folder (PID: the writing process):
//   .NAME.tmpPID   a file being written         .NAME.bakPID   the old NAME during a commit
// NAME is shortened to its first 200 bytes and a hash when the temporary name would be over
// 255 bytes. A run removes such files of processes that no longer exist (killed with SIGKILL,
// or a power cut) from its folder when it starts, and says so in the log.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/log.hpp"

namespace aq {

/// The process id in a temporary or backup name of an OutputSet (".NAME.tmpPID" or
/// ".NAME.bakPID"), or -1 when `file_name` is not one.
long output_temporary_pid(const std::string& file_name);

/// XXH64 (seed 0) of a file's bytes, as 16 hex digits: what `xxhsum -H1 FILE` prints. Throws
/// InputError if unreadable. Reports list it under kChecksumKey.
std::string file_checksum(const std::filesystem::path& path);
/// The report key of an output file's checksum (file_checksum).
inline constexpr const char* kChecksumKey = "checksum_xxh64";
/// 64-bit FNV-1a over a byte range, continuing from `hash` (start with kFnvOffset).
inline constexpr std::uint64_t kFnvOffset = 1469598103934665603ULL;
std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t hash = kFnvOffset);

class OutputSet {
 public:
  /// Creates `dir` if needed and checks it is writable; throws OutputError naming it otherwise.
  /// Removes the temporaries and backups of dead processes from it (logged at info level).
  explicit OutputSet(std::filesystem::path dir, const Logger& log = Logger::null());
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Reserves `name` in the folder; returns the temporary path a writer should write to.
  std::filesystem::path temp_path(const std::string& name);
  /// Renames every temporary to its final name. Returns the final paths in reservation order.
  /// When a rename fails, undoes the ones before it (old files restored), removes the
  /// temporaries and throws OutputError naming the file and the reason.
  std::vector<std::filesystem::path> commit();
  /// The files of dead processes the constructor removed.
  [[nodiscard]] const std::vector<std::filesystem::path>& stale_removed() const { return stale_; }
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }
  /// Temporary path of a reserved name (where its writer wrote it, before commit); throws
  /// InternalError if `name` was not reserved.
  [[nodiscard]] std::filesystem::path pending_path(const std::string& name) const;
  /// Final path of a reserved name (valid before and after commit).
  [[nodiscard]] std::filesystem::path final_path(const std::string& name) const { return dir_ / name; }

 private:
  std::filesystem::path dir_;
  struct Pending {
    std::filesystem::path tmp, fin, bak;
    int slot;  // in the TempRegistry
  };
  std::vector<Pending> files_;
  std::vector<std::filesystem::path> stale_;
  bool committed_ = false;
};

}  // namespace aq

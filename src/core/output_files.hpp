// All-or-nothing output (ARCHITECTURE §4.8, §9): every file is written under a temporary name
// in the destination folder and renamed only when the whole run succeeded. If the run fails
// (an exception unwinds past the OutputSet), the temporaries are removed: no partial outputs.
// Every temporary is also in the TempRegistry (core/temp_registry.hpp), so that an interrupt
// handler can remove them (and the renamed files of an unfinished commit) too.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace aq {

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
  explicit OutputSet(std::filesystem::path dir);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Reserves `name` in the folder; returns the temporary path a writer should write to.
  std::filesystem::path temp_path(const std::string& name);
  /// Renames every temporary to its final name. Returns the final paths in reservation order.
  std::vector<std::filesystem::path> commit();
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }
  /// Temporary path of a reserved name (where its writer wrote it, before commit); throws
  /// InternalError if `name` was not reserved.
  [[nodiscard]] std::filesystem::path pending_path(const std::string& name) const;
  /// Final path of a reserved name (valid before and after commit).
  [[nodiscard]] std::filesystem::path final_path(const std::string& name) const { return dir_ / name; }

 private:
  std::filesystem::path dir_;
  struct Pending {
    std::filesystem::path tmp, fin;
    int slot;  // in the TempRegistry
  };
  std::vector<Pending> files_;
  bool committed_ = false;
};

}  // namespace aq

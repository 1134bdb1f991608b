// SPDX-License-Identifier: GPL-3.0-or-later
// A process-wide registry of the temporary files of unfinished outputs, readable from a signal
// handler (ARCHITECTURE §4.8, §9: an interrupted run leaves no temporaries and no partial
// outputs). OutputSet registers every temporary it hands out and the final name it will be
// renamed to; an interrupt handler installed by src/app calls remove_registered_temporaries(),
// which touches only lock-free atomics, fixed char buffers and unlink(2): it is
// async-signal-safe and never allocates.
//
// Slot states (one atomic int per slot):
//
//   kFree --acquire--> kFilling --paths copied--> kTemp --commit--> kRenaming --rename--> kRenamed
//     ^                                             |                                        |
//     +------------------ release (after the commit or the removal) -------------------------+
//
//   remove_registered_temporaries() unlinks: kTemp -> the temporary; kRenaming -> the temporary
//   and the final name (the rename may have happened); kRenamed -> the final name (its output set
//   was not completely renamed yet, so the run's outputs would be partial). A final name that
//   held an older file when the commit began has a backup (a hard link made before the renames,
//   `backed_up`): instead of being unlinked, the final name gets the backup back (rename(2)),
//   so an interrupted commit leaves the old files as they were.
//
// Files are created and renamed by the thread that reserved them; the handler must run on that
// thread (src/app forwards the signal to the main thread) so no file can appear after the
// removal. Slots live in chunks that are allocated on demand and never freed.
#pragma once

#include <cstddef>
#include <filesystem>

namespace aq {

class TempRegistry {
 public:
  /// Registers a temporary `tmp` that will be renamed to `fin`; returns its slot. Throws
  /// OutputError naming the path when a path is longer than kPathMax - 1 bytes or every slot is
  /// in use (kMaxSlots).
  static int add(const std::filesystem::path& tmp, const std::filesystem::path& fin,
                 const std::filesystem::path& bak = {});
  /// The old final file of `slot` is now also at its backup name (given to add()): a hard link
  /// (`moved` false) or moved there (`moved` true, where hard links fail).
  static void backed_up(int slot, bool moved) noexcept;
  /// The temporary of `slot` is about to be renamed to its final name.
  static void renaming(int slot) noexcept;
  /// The rename of `slot` is done (its output set may still be partial).
  static void renamed(int slot) noexcept;
  /// Forgets `slot` (the set was committed completely, or its temporary was removed).
  static void release(int slot) noexcept;
  /// Unlinks every registered temporary, and the final files of an output set whose renaming
  /// was interrupted. Async-signal-safe; returns the number of files removed.
  static int remove_registered_temporaries() noexcept;
  /// Slots in use (for tests).
  static int in_use() noexcept;

  static constexpr std::size_t kPathMax = 4096;
  static constexpr int kSlotsPerChunk = 32;
  static constexpr int kMaxChunks = 512;
  static constexpr int kMaxSlots = kSlotsPerChunk * kMaxChunks;
};

}  // namespace aq

// SPDX-License-Identifier: GPL-3.0-or-later
// netCDF-4 chunks compressed ahead on the OpenMP team: the same bytes as HDF5's deflate filter,
// in a fraction of the time on the writing thread.
//
// A compressed netCDF-4 variable (nc_def_var_deflate, with shuffle) is written chunk by chunk
// through HDF5's filter pipeline: shuffle, then zlib's compress2 at the variable's level, one
// chunk after another on the thread that writes (8 of the 12 s the 15" run's 0.37 GB UGRID file
// took, on one core). HDF5 refuses to replace its predefined filters, and its file layout
// depends on the order in which its chunk cache flushes the chunks, so the chunks cannot be
// written any other way without changing the file's bytes. What can change is who computes
// compress2's answer:
//
//   writer:  prepare(slab) ─────────────> nc_put_vara(slab) ... HDF5 flushes a chunk: shuffle,
//              │                                                 compress2(chunk, level)
//   team:    shuffle + compress2 each whole chunk ──> cache ──> hit: the cached bytes (a copy)
//                                                           └──> miss: zlib's compress2
//
// The program defines compress2 itself (the `aquatoria` executable exports it, so HDF5's calls
// reach it): while a DeflateAhead is alive it answers a call whose input (level, length and
// 128-bit XXH3 hash) was prepared with the bytes zlib gave for it, and otherwise, as always,
// calls zlib's compress2. The file's bytes are those of zlib's compress2 whatever the cache
// holds: a chunk prepared wrongly (a partial last chunk's padding) costs time, not bytes. Where
// HDF5's calls do not reach the program's compress2 (the tests and the Python module link the
// library without exporting it) or OpenMP is off, active() is false and prepare() does nothing.
#pragma once

#include <cstddef>
#include <cstdint>

namespace aq::io {

class DeflateAhead {
 public:
  /// Turns the cache on (when active()); one DeflateAhead at a time per process (a second one
  /// waits for the first to go).
  DeflateAhead();
  /// Turns it off and frees what was prepared and not asked for.
  ~DeflateAhead();
  DeflateAhead(const DeflateAhead&) = delete;
  DeflateAhead& operator=(const DeflateAhead&) = delete;

  /// Whether prepare() compresses anything: HDF5's calls of compress2 reach the program's, and
  /// there is a team to share the work.
  [[nodiscard]] bool active() const { return active_; }

  /// Compresses at `level` (1..9) the `bytes` bytes at `data` in chunks of `chunk_bytes`, as
  /// HDF5 will hand them to compress2: the values in the variable's file type (elements of
  /// `element_bytes`), shuffled when `shuffle`; a last chunk shorter than chunk_bytes padded
  /// with zero bytes. `data` must start at a chunk boundary of the variable. Fewer than 4
  /// chunks are left to zlib (too little to share).
  void prepare(const void* data, std::size_t bytes, std::size_t chunk_bytes, std::size_t element_bytes, bool shuffle,
               int level);

  /// Tests: false makes every later DeflateAhead inactive (the writers then run as without one).
  static void allow(bool allowed);

  /// compress2 calls answered from the cache, and the others, since this object was made.
  [[nodiscard]] std::int64_t hits() const;
  [[nodiscard]] std::int64_t misses() const;

 private:
  bool active_ = false;
};

}  // namespace aq::io

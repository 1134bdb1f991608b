// SPDX-License-Identifier: GPL-3.0-or-later
// Patches: the forest engine's unit of pixel work (README "The forest engine"). The lattice is cut
// into squares of P × P pixels, P = 2^min(L, 7): the level-lp squares of the quadtree, lp = L −
// log2 P (a level-0 square is one patch when L <= 7). A patch is uniform — none or all of its
// pixels in a set — or mixed, and then holds a P × P bitmap of the set. Only patches along the
// coast are mixed, so a set costs memory in proportion to the coast, not to the lattice.
//
// The patch forest is the brick's forest refined uniformly to lp, spread over the ranks in whole
// trees, with a ghost layer of face and corner neighbours: a stencil of radius r <= P around a
// patch's pixels is evaluated exactly on the 3P × 3P window of the patch and its 8 neighbours
// (assemble()), whatever rank holds them.
//
//   patch (gx, gy) = pixels [gx·P, (gx+1)·P) × [gy·P, (gy+1)·P); tree (gx >> lp, gy >> lp);
//   key = gy·npx + gx;  column gx wraps on a periodic lattice; rows beyond the poles (and columns
//   beyond a window lattice) are outside: assemble() fills them with the value the dense
//   engine's bitmaps imply there (see OutsideRule).
#pragma once

#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "config/kinds.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "forest/comm.hpp"
#include "forest/lattice_forest.hpp"

namespace aq::forest {

/// At most this many pixels per patch side (log2); the configuration's checks at load know it too.
inline constexpr int kMaxPatchLog2 = config::kForestMaxPatchLog2;

struct PatchGrid {
  Lattice lat;
  int plog = 0;           ///< log2 P
  int level = 0;          ///< lp: the quadtree level of a patch
  std::int64_t size = 1;  ///< P
  std::int64_t npx = 0, npy = 0;
  std::int64_t per_tree = 1;  ///< patches per tree side, 2^lp
  bool periodic = true;

  static PatchGrid make(const Lattice& lat);
  [[nodiscard]] std::int64_t count() const { return npx * npy; }
  [[nodiscard]] std::int64_t key(std::int64_t gx, std::int64_t gy) const { return gy * npx + gx; }
  [[nodiscard]] std::int64_t gx(std::int64_t key) const { return key % npx; }
  [[nodiscard]] std::int64_t gy(std::int64_t key) const { return key / npx; }
  /// Key of patch (gx + dx, gy + dy), the column wrapped on a periodic lattice; -1 outside.
  [[nodiscard]] std::int64_t neighbour(std::int64_t gx, std::int64_t gy, std::int64_t dx, std::int64_t dy) const;
  /// Key of patch (gx, gy) after the wrap, or -1 outside (rows: beyond the poles; columns: a window).
  [[nodiscard]] std::int64_t key_at(std::int64_t gx, std::int64_t gy) const;
  [[nodiscard]] std::int64_t tree_of(std::int64_t key) const;
};

/// A pixel set restricted to one patch.
enum class Fill : std::uint8_t { kNone = 0, kAll = 1, kMixed = 2 };
struct PatchBits {
  Fill state = Fill::kNone;
  Bitmap bits;  ///< P × P when kMixed, empty otherwise
  [[nodiscard]] bool get(std::int64_t i, std::int64_t j) const {
    return state == Fill::kAll || (state == Fill::kMixed && bits.get(i, j));
  }
  /// Makes it uniform when the bitmap is all ones or all zeros.
  void normalise();
  /// A P × P bitmap of it (ones for kAll, zeros for kNone).
  [[nodiscard]] Bitmap dense(std::int64_t p) const;
};

/// What the cells outside the lattice are in an assembled window: the dense engine's bitmaps have
/// no rows beyond the poles (their neighbours count as `row_value`) and wrap columns on a window
/// lattice onto its padding, which is never in any set (`col_value` = false).
struct OutsideRule {
  bool row_value = false;
  bool col_value = false;
};

/// The patches of this rank and the ghosts around them, with a p4est forest and ghost layer that
/// hold the distribution.
class PatchForest {
 public:
  PatchForest(const LatticeBrick& brick, const Comm& comm);

  [[nodiscard]] const PatchGrid& grid() const { return grid_; }
  [[nodiscard]] const Comm& comm() const { return comm_; }
  [[nodiscard]] const LatticeBrick& brick() const { return brick_; }
  [[nodiscard]] p4est_t* forest() const { return forest_.get(); }
  /// Local patches in p4est's order (tree, then Morton).
  [[nodiscard]] std::size_t local_count() const { return keys_.size(); }
  [[nodiscard]] std::int64_t key(std::size_t local) const { return keys_[local]; }
  /// Local index of a key, or -1 when this rank does not hold it.
  [[nodiscard]] std::int64_t local_index(std::int64_t key) const;
  /// Ghost patches (neighbours held by other ranks) in p4est's ghost order.
  [[nodiscard]] std::size_t ghost_count() const { return ghost_keys_.size(); }
  [[nodiscard]] std::int64_t ghost_key(std::size_t g) const { return ghost_keys_[g]; }
  [[nodiscard]] std::int64_t ghost_index(std::int64_t key) const;
  /// The local trees [first, last).
  [[nodiscard]] std::int64_t first_tree() const { return first_tree_; }
  [[nodiscard]] std::int64_t last_tree() const { return last_tree_; }

  /// The ghosts' copies of a per-local-patch set (`local` indexed like the local patches).
  /// Collective.
  [[nodiscard]] std::vector<PatchBits> exchange(const std::vector<PatchBits>& local) const;
  /// The ghosts' copies of fixed-size plain records, `bytes` per local patch. Collective.
  [[nodiscard]] std::vector<char> exchange_bytes(const std::vector<char>& local, std::size_t bytes) const;
  /// The same with each record written by pack(local index, out) for the patches other ranks see
  /// only (no record of every local patch is held). Collective.
  [[nodiscard]] std::vector<char> exchange_records(std::size_t bytes,
                                                   const std::function<void(std::size_t, char*)>& pack) const;

  /// The 3P × 3P window of the set around local patch `local`: patch (gx + dx, gy + dy) at pixel
  /// offset ((dx + 1)·P, (dy + 1)·P), taken from `mine` (local patches) or `ghosts` (ghost patches).
  [[nodiscard]] Bitmap assemble(std::size_t local, const std::vector<PatchBits>& mine,
                                const std::vector<PatchBits>& ghosts, const OutsideRule& outside) const;
  /// The patch (local or ghost) with `key`, or null when neither.
  [[nodiscard]] const PatchBits* find(std::int64_t key, const std::vector<PatchBits>& mine,
                                      const std::vector<PatchBits>& ghosts) const;

 private:
  const LatticeBrick& brick_;
  Comm comm_;
  PatchGrid grid_;
  ForestPtr forest_;
  GhostPtr ghost_;
  std::vector<std::int64_t> keys_;
  std::vector<std::int64_t> ghost_keys_;
  std::int64_t first_tree_ = 0, last_tree_ = 0;
  std::int64_t first_key_tree_base_ = 0;
  std::unordered_map<std::int64_t, std::int64_t> ghost_index_;
  std::vector<std::int64_t> tree_first_local_;  ///< local index of the first patch of each local tree
};

/// The whole set as one nx × ny bitmap on rank 0 (empty on the others): for tests and checks on
/// lattices small enough to hold densely. Collective.
Bitmap gather_dense(const PatchForest& pf, const std::vector<PatchBits>& set);

/// ORs the n bits src[0..n) into dst at bit offset `off` (dst has room; no wrap).
void or_bits_at(std::uint64_t* dst, std::int64_t off, const std::uint64_t* src, std::int64_t n);
/// Copies bits [off, off + n) of src into dst[0..n) (dst zeroed first).
void take_bits(const std::uint64_t* src, std::int64_t off, std::uint64_t* dst, std::int64_t n);
/// The P × P centre of a 3P × 3P window.
Bitmap centre_of(const Bitmap& window, std::int64_t p);

}  // namespace aq::forest

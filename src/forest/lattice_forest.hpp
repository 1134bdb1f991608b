// SPDX-License-Identifier: GPL-3.0-or-later
// The lattice (core/lattice.hpp) as a p4est forest (FOREST.md §1): one tree per level-0 square,
// a brick of nx0 × ny0 trees, periodic in x when the lattice spans all longitudes (the λ seam is
// a periodic face; the rows at the poles are the brick's edge). The brick numbers its trees along
// a space-filling curve; they are permuted so that tree t = b0·nx0 + a0, and p4est's global
// order of quadrants — tree, then Morton inside it — is the dense engine's leaf order (level-0
// square row-major, then Morton of the SW pixel; quadtree/leaves.hpp).
//
//   quadrant of level l at (x, y) of tree (a0, b0)  <->  lattice square (l, a, b):
//     a = a0·2^l + x / 2^(30 - l),   b = b0·2^l + y / 2^(30 - l)       (p4est: x, y < 2^30)
//   child id = x-bit | y-bit << 1  =  SW 0, SE 1, NW 2, NE 3 (quadtree/leaves.hpp's order)
#pragma once

#include <p4est.h>
#include <p4est_extended.h>
#include <p4est_ghost.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/lattice.hpp"
#include "forest/comm.hpp"

namespace aq::forest {

struct ConnectivityDeleter {
  void operator()(p4est_connectivity_t* c) const { p4est_connectivity_destroy(c); }
};
struct ForestDeleter {
  void operator()(p4est_t* p) const { p4est_destroy(p); }
};
struct GhostDeleter {
  void operator()(p4est_ghost_t* g) const { p4est_ghost_destroy(g); }
};
using ConnectivityPtr = std::unique_ptr<p4est_connectivity_t, ConnectivityDeleter>;
using ForestPtr = std::unique_ptr<p4est_t, ForestDeleter>;
using GhostPtr = std::unique_ptr<p4est_ghost_t, GhostDeleter>;

/// A lattice square (level, a, b) with a, b in the lattice's own columns and rows of that level.
struct Square {
  int level = 0;
  std::int64_t a = 0, b = 0;
};

/// The brick of a lattice's level-0 squares.
class LatticeBrick {
 public:
  /// The brick of `lat` (its level-0 squares; periodic in x when lat.periodic()).
  explicit LatticeBrick(const Lattice& lat);

  [[nodiscard]] p4est_connectivity_t* connectivity() const { return conn_.get(); }
  [[nodiscard]] const Lattice& lattice() const { return lat_; }
  [[nodiscard]] std::int64_t nx0() const { return nx0_; }
  [[nodiscard]] std::int64_t ny0() const { return ny0_; }
  [[nodiscard]] std::int64_t trees() const { return nx0_ * ny0_; }
  [[nodiscard]] bool periodic() const { return periodic_; }
  /// Tree of level-0 square (a0, b0): b0·nx0 + a0.
  [[nodiscard]] std::int64_t tree(std::int64_t a0, std::int64_t b0) const { return b0 * nx0_ + a0; }
  [[nodiscard]] std::int64_t tree_a0(std::int64_t t) const { return t % nx0_; }
  [[nodiscard]] std::int64_t tree_b0(std::int64_t t) const { return t / nx0_; }

  /// The lattice square of quadrant q of tree t.
  [[nodiscard]] Square square(std::int64_t t, const p4est_quadrant_t& q) const;
  /// The quadrant (level, x, y) of lattice square s, and its tree.
  void quadrant(const Square& s, std::int64_t& tree, p4est_quadrant_t& q) const;

 private:
  Lattice lat_;
  std::int64_t nx0_ = 0, ny0_ = 0;
  bool periodic_ = false;
  ConnectivityPtr conn_;
};

/// A forest of the brick on `comm`: every tree refined uniformly to `level`, no user data. The
/// trees are then spread over the ranks in contiguous ranges of whole trees (partition_by_trees).
ForestPtr uniform_forest(const LatticeBrick& brick, const Comm& comm, int level);

/// Moves whole trees between ranks: rank r gets the trees whose cumulative weight (in tree order)
/// starts in [r·W/size, (r+1)·W/size), W the total weight. `tree_weight` (one per tree, the same
/// on every rank; empty = all 1) and `tree_quadrants` (the forest's quadrants per tree, the same
/// on every rank) decide the counts given to p4est_partition_given. Collective.
void partition_by_trees(p4est_t* forest, const std::vector<double>& tree_weight,
                        const std::vector<std::int64_t>& tree_quadrants);

/// Quadrants per tree over all ranks (the same vector on every rank). Collective.
std::vector<std::int64_t> quadrants_per_tree(p4est_t* forest, const Comm& comm);

/// The first and one-past-last tree this rank holds any quadrant of (first >= last when none).
void local_tree_range(const p4est_t* forest, std::int64_t& first, std::int64_t& last);

}  // namespace aq::forest

// SPDX-License-Identifier: GPL-3.0-or-later
// The quadtree's leaves as a p4est forest (FOREST.md §2): refined from the level pyramid
// (forest/pyramid.hpp: a square is split while it holds a filled pixel and is not inside a leaf of
// its level), every leaf flagged filled (a leaf of Ω_L) or land, then 2:1-balanced.
//
// Balance. The dense engine balances the filled leaves among themselves (land is no leaf there);
// p4est_balance balances every leaf, land included. The two agree when every filled leaf that
// touches land (by a face or a corner) is a level-L pixel, which cannot split: then a land leaf
// never forces a filled one to split, and between filled leaves the rules are the same (FACE =
// "face", FULL = "corner"). That holds when the coastal band (quadtree.coast_band >= 1, and no
// quadtree.coast_size_km in its place) splits every such leaf to level L. Otherwise (coast_band
// = 0, or coast_size_km > 0) the forest runs the dense rule itself: rounds in which every filled
// leaf that has a filled neighbour (face, or also corner) two or more levels finer is split once,
// over the ghost layer, until no rank splits one — the unique coarsest balanced refinement, the
// dense engine's. Either way a checker counts the violations left (it must find none).
#pragma once

#include <cstdint>
#include <vector>

#include "forest/lattice_forest.hpp"
#include "forest/pyramid.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/leaves.hpp"
#include "quadtree/nodes.hpp"

namespace aq::forest {

class MeshForest {
 public:
  /// The forest of the pyramid's leaves, on the patch forest's trees (the pyramid's fine levels
  /// are read where they are held). Collective.
  MeshForest(const LatticeBrick& brick, const Comm& comm, const ForestPyramid& pyramid);

  /// What the balance did.
  struct BalanceResult {
    bool used_p4est = false;         ///< p4est_balance, else the dense rule's rounds
    std::int64_t forced_splits = 0;  ///< leaves split (the rounds: filled leaves)
    int rounds = 0;
  };
  /// The 2:1 balance (see the file comment); `p4est_equivalent` selects p4est_balance. Collective.
  BalanceResult balance(quadtree::BalanceMode mode, bool p4est_equivalent);
  /// Pairs (filled leaf, direction) whose neighbour square lies inside a filled leaf two or more
  /// levels coarser, over all ranks (quadtree::count_balance_violations). Collective.
  [[nodiscard]] std::int64_t count_violations(quadtree::BalanceMode mode) const;

  /// The filled leaves of this rank, in order (the concatenation over the ranks is the dense order).
  [[nodiscard]] std::vector<quadtree::Leaf> local_leaves() const;
  /// The neighbourhoods of local_leaves() (quadtree/nodes.hpp), found over the ghost layer.
  /// Collective (the ghost layer).
  [[nodiscard]] std::vector<quadtree::LeafNeighbourhood> local_neighbourhoods() const;
  /// Filled leaves per level over all ranks. Collective.
  [[nodiscard]] std::vector<std::int64_t> leaves_per_level() const;
  /// All leaves (filled and land) over all ranks, and p4est's memory (bytes, this rank).
  [[nodiscard]] std::int64_t quadrants() const;
  [[nodiscard]] std::int64_t memory_bytes() const;
  [[nodiscard]] p4est_t* forest() const { return forest_.get(); }

 private:
  // Filled leaves that must split under the dense rule (local ones marked here; remote ones are
  // sent to their owner): returns the violations seen from this rank's filled leaves.
  std::int64_t violations(quadtree::BalanceMode mode, bool mark, std::vector<char>* marks) const;

  const LatticeBrick& brick_;
  Comm comm_;
  ForestPtr forest_;
};

}  // namespace aq::forest

// SPDX-License-Identifier: GPL-3.0-or-later
// Smoothing of the quadtree: 2:1 balance (seed 002: "итерационное сглаживание сетки с контролем
// максимальности уровней вложенности граничных квадратов", Fig. 1б; ARCHITECTURE §4.4).
// Neighbouring leaves — sharing a piece of side ("face"), or also only a corner ("corner") —
// must differ by at most one level. The coarser leaf is split, never merged; leaves of level L
// are never touched. Columns are periodic (the λ seam); rows end at the poles.
//
// Algorithm (level by level on the bitmap pyramid of leaves.hpp, fine to coarse). For a leaf B of
// level k and a direction d, let N be the level-k square next to B in direction d:
//
//     face:   . N .        corner:  N N N        B violates the invariant with the leaf holding
//             N B N                 N B N        N exactly when N lies inside a leaf of level
//             . N .                 N N N        <= k-2, i.e. omega[k-2] is set on N's grandparent.
//
// For k = L, L-1, ..., 2: dilate the level-k leaves by the stencil, OR-reduce twice to level
// k-2 and clear those bits of omega[k-2] (the leaf holding N is split until N's parent is a
// leaf of level k-1); then restore monotonicity on the coarser levels. Splits made at step k
// create leaves of levels <= k-1 only, and leaves of level k are final when step k runs, so one
// pass is enough and the result is the unique coarsest balanced refinement. Cost: O(N / 64)
// word operations, parallel over rows.
//
// The checker `count_balance_violations` counts the pairs (leaf B, direction d) above on a
// pyramid rebuilt from the leaf list; the stage calls it at the end and throws InternalError when
// it is not zero.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "config/kinds.hpp"
#include "core/lattice.hpp"
#include "quadtree/leaves.hpp"

namespace aq::quadtree {

/// quadtree.balance (config/kinds.hpp): face neighbours, or faces and corners.
using config::BalanceMode;

struct BalanceStats {
  std::int64_t forced_splits = 0;  ///< squares cleared from omega by the stencil (before coarser propagation)
  int levels_changed = 0;          ///< steps k that split anything
};

/// Balances the pyramid in place (see the file comment).
BalanceStats balance(LevelMasks& masks, BalanceMode mode);

/// Number of (leaf, direction) pairs whose neighbour square lies inside a leaf two or more levels
/// coarser; 0 exactly when the leaves are balanced. O(directions · N / 64), parallel.
std::int64_t count_balance_violations(const LevelMasks& masks, BalanceMode mode);
/// The same for a leaf list (sorted or not; throws InternalError when the leaves overlap).
std::int64_t count_balance_violations(const std::vector<Leaf>& leaves, const Lattice& lat, BalanceMode mode);

/// The balanced refinement of a leaf set, in the deterministic order.
std::vector<Leaf> balance_leaves(const std::vector<Leaf>& leaves, const Lattice& lat, BalanceMode mode);

}  // namespace aq::quadtree

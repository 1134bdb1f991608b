// SPDX-License-Identifier: GPL-3.0-or-later
// Automatic choice of the best initial grid (seed 004 Sec. 5; digest orthogonal_bvp_and_elliptic.md
// B.6). Each candidate carries its criteria f(k) (worst cell) and f(k)_o (average), k = 1..4, and
// its validity flags; the procedure:
//
//   if some candidate has f(1) > 0 (all cells convex):
//       C ← {f(1) > 0}
//       for k = 2, 3, 4:  S ← argmax_C f(k);  C ← {S} ∪ {g ∈ C : f(k)_o(g) > f(k)_o(S)}
//       if |C| > 1: the lexicographic max of (f(2), f(3), f(4))
//   elif C' = {no self-intersecting cell and no interior line crossing the boundary} ≠ ∅:
//       C ← C';  S ← argmax f(1);  C ← {S} ∪ {f(1)_o > f(1)_o(S)};  then k = 2, 3, 4 as above
//   else: the lexicographic max of (f(1)_o, f(2)_o, f(3)_o, f(4)_o)
//
// Ties (argmax) go to the earlier candidate, so the choice is deterministic.
#pragma once

#include <string>
#include <vector>

#include "curvilinear/elliptic/elliptic_grids.hpp"

namespace aq::curvilinear {

struct Candidate {
  std::string name;
  Criteria criteria;
  int self_intersecting_cells = 0;  ///< cells with signed area ≤ 0 or crossed edges (f1 = −∞ in check_grid)
  int boundary_crossings = 0;       ///< interior-line segments crossing the boundary (initial_grids.hpp)
};

struct Selection {
  int chosen = -1;                 ///< index into the candidates
  std::vector<std::string> steps;  ///< the filtering steps, one line each, for the log and report
};

/// Runs the procedure above on ≥ 1 candidates.
Selection select_best_grid(const std::vector<Candidate>& candidates);

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Two blocks of the orthogonal-family method sharing one interface side (seed 003 Sec. 4 end,
// multi-block; digest orthogonal_bvp_and_elliptic.md A.9): block A's east side Γ3 (θ^A = 1) is
// block B's west side Γ1 (θ^B = 0), the same curve, traversed south -> north in both.
//
//        block A             block B
//   +----------------+-----------------+
//   |  θ^A: 0 -> 1   |Y_q  θ^B: 0 -> 1 |      η-lines cross the interface; it is a θ-isoline
//   |                |                 |      of both blocks, so both meet it at 90°:
//   +----------------+-----------------+      the η-lines are C1 across it, not only C0.
//
// The equations are solved in each block independently; the interface nodes Y_q are fixed by A
// (η^A = η^A_q on it), and B's η-levels are η^B_q := η^B(Y_q), interpolated along B's reference
// interface, so that the q-th η-line of B starts where A's ends. B's interface column is then set
// to A's (C0 to round-off). Each outer iteration re-solves both blocks on their new grids.
#pragma once

#include "curvilinear/bvp/orthogonal_bvp.hpp"

namespace aq::curvilinear {

struct TwoBlockResult {
  SurfaceGrid a, b;                  ///< the grids; a's column P = b's column 0
  std::vector<double> eta_levels_b;  ///< B's derived η levels (last iteration)
  std::vector<double> f_max, f_avg;  ///< over both blocks (f_avg area-weighted), k = 0..iterations
  int iterations = 0;                ///< outer iterations run
  /// Largest angle (radians) between an η-line's last segment in A and its first in B, over
  /// the interior interface nodes: the kink across the interface (0 for C1 lines).
  double max_kink = 0.0;
};

/// `a_options` gives A's θ and η levels and the common iteration settings (its `project` is
/// applied to A, `b_project` to B); `b_theta_levels` are B's θ levels. B's η levels are derived.
/// Runs outer iterations until f_max and f_avg over both blocks level off as in orthogonal_bvp()
/// (relative change ≤ level_off after min_iterations; digest A.8) or max_iterations, and returns
/// the last (C0 across the interface holds for every iterate, the best-f_avg pick of one block
/// would not keep it for a pair).
/// The reference grids must share the interface curve (A's column nx−1, B's column 0) and its
/// end points. Throws as orthogonal_bvp().
TwoBlockResult orthogonal_bvp_two_blocks(const SurfaceGrid& a_initial, const SurfaceGrid& b_initial,
                                         const BvpOptions& a_options, const std::vector<double>& b_theta_levels,
                                         const std::function<void(SurfaceGrid&)>& b_project = {});

}  // namespace aq::curvilinear

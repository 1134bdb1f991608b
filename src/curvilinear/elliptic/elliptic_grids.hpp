// SPDX-License-Identifier: GPL-3.0-or-later
// Final grids of seed 004 Sec. 3 (digest orthogonal_bvp_and_elliptic.md B.4): the node coordinates
// solve, on the unit-step index grid with the boundary nodes fixed (Dirichlet),
//
//   ED2 (3.1): ∂/∂q1 (w g22 ∂x/∂q1) + ∂/∂q2 (w g11 ∂x/∂q2) = 0,   g11 = |x_q1|², g22 = |x_q2|²
//   RL  (3.2): ∂/∂q1 (λ ∂x/∂q1) + ∂/∂q2 (λ⁻¹ ∂x/∂q2) = 0,         λ = |x_q2| / |x_q1|
//
// (ED2 = the Ryskin–Leal orthogonality equations plus w·J = const: large w, small cells.) Discretised
// with face coefficients (digest B.4 [DEV]):
//
//   a_{i+½,j} = w(½(x_ij + x_i+1,j)) |¼(x_i,j+1 + x_i+1,j+1 − x_i,j−1 − x_i+1,j−1)|²     (w g22)
//   b_{i,j+½} = w(½(x_ij + x_i,j+1)) |¼(x_i+1,j + x_i+1,j+1 − x_i−1,j − x_i−1,j+1)|²     (w g11)
//   a₊(x_i+1,j − x_ij) − a₋(x_ij − x_i−1,j) + b₊(x_i,j+1 − x_ij) − b₋(x_ij − x_i,j−1) = 0
//
// Solver: Picard iteration with the coefficients lagged; each step solves the (symmetric positive
// definite) linear system for x and y by conjugate gradients with an incomplete-Cholesky IC(0)
// preconditioner, truncated (relative residual 0.2 or 6 iterations), and under-relaxes
// x ← (1 − ω)x + ω x*. Faster than the paper's line Gauss–Seidel; the discrete maximum principle
// still holds for the exact solution of each step. Serial sums in a fixed order: the result does
// not depend on the thread count.
//
// Stop (seed 004: "compute the criteria at every iteration and stop when they stop changing"),
// checking f(k), f(k)_o (k = 1..4, grid_checks.hpp) every check_every iterations, at the first of
//   - nodes settled: the largest node move is below tolerance·diam(Ω) and no f(k), f(k)_o changed by
//     criteria_tolerance or more since the previous check (the digest's B.4 rule, looser numbers);
//   - averages settled (stop_when_averages_settle): no f(k)_o changed by criteria_tolerance or more
//     at two consecutive checks. The worst-cell values f(k) are left out on purpose: on domains with
//     thin corner cells (the Black Sea at 131 × 101) Picard does not reach a fixed point; a few
//     nodes creep by 1e-5..2e-4 of the diameter per iteration for thousands of iterations while the
//     averages stay put and f(k) wanders by ±0.01..0.05;
//   - max_iterations (then converged = false).
// last_move reports the largest node move of the last iteration either way.
#pragma once

#include <array>
#include <vector>

#include "core/log.hpp"
#include "curvilinear/common/grid2d.hpp"
#include "grid_params/control_function.hpp"

namespace aq::curvilinear {

enum class EllipticMethod { kEd2, kRyskinLeal };

struct EllipticOptions {
  EllipticMethod method = EllipticMethod::kEd2;
  /// ω of the Picard update, (0, 1].
  double relaxation = 0.7;
  /// Node-move tolerance relative to the domain's diameter, > 0.
  double tolerance = 1e-4;
  /// Change of f(k) and f(k)_o between checks below which the criteria count as settled, > 0.
  double criteria_tolerance = 1e-3;
  /// Picard iterations at most, ≥ 1.
  int max_iterations = 200;
  /// Criteria every this many iterations, ≥ 1.
  int check_every = 5;
  /// Inner CG: stop at this relative residual, (0, 1), or after inner_iterations, ≥ 1. The
  /// coefficients are lagged, so a more exact inner solve buys little: on the Black Sea (131 × 101)
  /// 0.2/6 takes 120 Picard and 1221 CG iterations to settle, 0.1/10 190 and 3270. RL is sensitive to
  /// λ: the regional pipeline gives it 0.1/10 (with 0.2/6 its Black Sea orthogonality error doubles).
  double inner_tolerance = 0.2;
  int inner_iterations = 6;
  /// Also stop when the averages f(k)_o have settled (see the rules above).
  bool stop_when_averages_settle = true;
  /// Progress of the iterations (fraction of max_iterations, with the last move); may be empty.
  ProgressFn progress = {};
};

enum class EllipticStop { kIterationCap, kNodesSettled, kAveragesSettled };

/// "iteration cap", "nodes and criteria settled", "averages settled".
const char* elliptic_stop_name(EllipticStop s);

/// f(1..4) worst and average of one grid (the seed-004 criteria of check_grid, w at cell centroids).
struct Criteria {
  std::array<double, 4> worst{};
  std::array<double, 4> average{};
};

/// The criteria of `grid` for the control function w (check_grid with cells_only).
Criteria grid_criteria(const Grid2D& grid, const ControlFunction& w);

struct EllipticResult {
  int iterations = 0;
  int cg_iterations = 0;   ///< inner CG iterations, summed
  double last_move = 0.0;  ///< largest node move of the last iteration / diam(Ω)
  bool converged = false;  ///< stopped by a rule, not by max_iterations
  EllipticStop stop = EllipticStop::kIterationCap;
  std::vector<Criteria> history;  ///< criteria at every check, the initial grid first
};

/// Smooths the interior of `grid` (boundary nodes kept) by ED2 or RL. Needs ≥ 3 × 3 points.
/// InternalError for bad options (validated at load); InputError when w is not positive and finite at a face midpoint.
EllipticResult elliptic_smooth(Grid2D& grid, const ControlFunction& w, const EllipticOptions& options = {});

/// "ed2" or "rl".
const char* elliptic_method_name(EllipticMethod m);

}  // namespace aq::curvilinear

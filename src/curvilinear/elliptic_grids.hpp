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
// preconditioner, truncated (relative residual 0.1 or 10 iterations), and
// under-relaxes x ← (1 − ω)x + ω x*. Faster than the paper's line Gauss–Seidel; the discrete
// maximum principle still holds for the exact solution of each step. Stop when the largest node
// move is below tolerance·diam(Ω) and f(k), f(k)_o (k = 1..4, grid_checks.hpp) change by less than
// criteria_tolerance between checks, or after max_iterations (then converged = false). Serial sums
// in a fixed order: the result does not depend on the thread count.
#pragma once

#include <array>
#include <vector>

#include "curvilinear/grid2d.hpp"
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
  /// Inner CG: stop at this relative residual, (0, 1), or after inner_iterations, ≥ 1.
  double inner_tolerance = 0.1;
  int inner_iterations = 10;
};

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
  bool converged = false;
  std::vector<Criteria> history;  ///< criteria at every check, the initial grid first
};

/// Smooths the interior of `grid` (boundary nodes kept) by ED2 or RL. Needs ≥ 3 × 3 points.
/// ConfigError for bad options; InputError when w is not positive and finite at a face midpoint.
EllipticResult elliptic_smooth(Grid2D& grid, const ControlFunction& w, const EllipticOptions& options = {});

/// "ed2" or "rl".
const char* elliptic_method_name(EllipticMethod m);

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Dirichlet fill of a grid's interior: x(ξ,η) and y(ξ,η) harmonic with the boundary nodes fixed
// (izogrid mode 4, seed 000 Sec. 2.5; digest izogrid.md §8).
//
// Operator: the compact 4th-order "mehrstellen" 9-point Laplacian for Δξ ≠ Δη, eqs. (32)–(35),
// in the normalised weights of digest §8.1 (ρ = Δξ/Δη, everything multiplied by 6Δξ²):
//
//     | γ  β  γ |      α = 6 − 2ρ,  β = 6ρ² − 2ρ,  γ = ρ,  δ = −(12 + 12ρ² − 4ρ)
//     | α  δ  α |      (i±1 = ξ neighbours, j±1 = η neighbours; at ρ = 1: 4, 4, 1, −20)
//     | γ  β  γ |
//
// For a harmonic q its truncation error is −(Δξ−Δη)²/12 · q_ξξηη: 4th order when Δξ−Δη = O(h²)
// (the automatic nx keeps ρ − 1 = O(1/nx)), 2nd order with a small constant otherwise; harmonic
// polynomials of degree ≤ 3 are reproduced exactly for any ρ, of degree ≤ 5 for ρ = 1.
//
// Solvers: the paper's 4-colour Gauss–Seidel SOR with the monotone Chebyshev ω of (42)–(43), and
// (default) a direct solver: the interior operator is diagonalised by the 2-D DST-I (FFTW
// RODFT00) with eigenvalues 2α(cos a_p−1) + 2β(cos b_q−1) + 4γ(cos a_p cos b_q−1). Both agree to
// round-off; the DST one is O(N log N) and needs no tolerance.
#pragma once

#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/laplace_stencil.hpp"
#include "grid_params/grid_kinds.hpp"

namespace aq::curvilinear {

struct LaplaceOptions {
  using Solver = LaplaceSolver;
  Solver solver = Solver::kDst;
  /// SOR only: stop when the largest update of one iteration, max |Δq|, is below
  /// tolerance × extent (extent = larger side of the boundary's bounding box). Dimensionless;
  /// 1e-14 leaves the solution within about 1e-12·extent of the exact discrete one up to
  /// ~2000×1000 points.
  double tolerance = 1e-14;
  /// SOR only: iterations (4 colour sweeps each) before giving up with NumericalError.
  int max_iterations = 200000;
  /// The 2nd-order 5-point operator instead of the 9-point one (for comparisons only).
  bool five_point = false;
};

struct LaplaceResult {
  int iterations = 0;     ///< SOR iterations; 1 for the direct solver
  double residual = 0.0;  ///< final max |L q|/|δ| over interior nodes and x, y, divided by extent
  double seconds = 0.0;   ///< wall time of the solve
  /// SOR: max |Δq|/extent of each iteration; direct solver: the single final residual.
  std::vector<double> residual_history;
};

/// Fills the interior nodes of `grid` (1 ≤ i ≤ nx_pts−2, 1 ≤ j ≤ ny_pts−2) from its boundary
/// nodes; boundary nodes are not changed (bit for bit). `dxi`, `deta` > 0 are the steps of the
/// uniform computational grid (e.g. W/(nx_pts−1), H/(ny_pts−1) of the conformal rectangle; only
/// their ratio matters). Grids with fewer than 3 points in a direction have no interior and are
/// returned unchanged. SOR results are bit-identical for any number of OpenMP threads.
/// Throws NumericalError for non-positive or non-finite steps, a non-finite boundary node, or
/// when SOR does not converge (the message names the residual and the iteration count);
/// InternalError if x, y do not have nx_pts·ny_pts entries.
LaplaceResult laplace_fill(Grid2D& grid, double dxi, double deta, const LaplaceOptions& options = {});

}  // namespace aq::curvilinear

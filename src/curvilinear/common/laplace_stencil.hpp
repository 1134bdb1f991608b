// SPDX-License-Identifier: GPL-3.0-or-later
// The compact 4th-order "mehrstellen" 9-point Laplacian of the izogrid Laplace fill (seed 000
// eqs. (32)–(35); digest izogrid.md §8; the weights are explained in conformal/laplace_fill.hpp):
// its weights and its residual, shared by the fill (conformal/) and the grid checks (common/).
#pragma once

#include <cstddef>
#include <vector>

#include "curvilinear/common/grid2d.hpp"

namespace aq::curvilinear {

/// Normalised stencil weights (see the top of this file); `alpha` acts on ξ neighbours, `beta` on
/// η neighbours, `gamma` on the four diagonals, `delta` on the centre (negative).
struct StencilWeights {
  double alpha = 0.0, beta = 0.0, gamma = 0.0, delta = 0.0;
};

/// Weights for the step ratio ρ = Δξ/Δη > 0. The 5-point operator is α = 1, β = ρ², γ = 0.
/// All weights are positive (an M-matrix) for 1/3 < ρ < 3; the 9-point operator stays negative
/// definite for every ρ > 0.
StencilWeights laplace_weights(double dxi_over_deta, bool five_point = false);

/// The operator at flat index p of a field with row stride nx (the node must be interior).
inline double apply_stencil(const double* q, std::size_t p, std::size_t nx, const StencilWeights& w) {
  const double ortho = w.alpha * (q[p - 1] + q[p + 1]) + w.beta * (q[p - nx] + q[p + nx]);
  const double diag = q[p - nx - 1] + q[p - nx + 1] + q[p + nx - 1] + q[p + nx + 1];
  return ortho + w.gamma * diag + w.delta * q[p];
}

/// InternalError unless x and y have nx_pts·ny_pts entries; `who` names the caller.
void check_laplace_shape(const Grid2D& g, const char* who);

/// Residual of the operator at every node, divided by |δ| (i.e. the Jacobi correction, in the
/// units of x, y): `rx`, `ry` get nx_pts·ny_pts values, 0 on the boundary.
void laplace_residual(const Grid2D& grid, double dxi_over_deta, bool five_point, std::vector<double>& rx,
                      std::vector<double>& ry);

}  // namespace aq::curvilinear

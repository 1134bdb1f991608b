// SPDX-License-Identifier: GPL-3.0-or-later
// The θ- and η-equations of the orthogonal-family method (seed 003 eqs. (13), (19) in the plane,
// (32), (33) on a surface; digest orthogonal_bvp_and_elliptic.md A.3–A.5), discretised by Q1
// finite elements ("variational-difference", digest A.5 option 1) on a reference grid:
//
//   ∂α[(l_β² T_α − l_α l_β cos φ T_β)/J] + ∂β[(l_α² T_β − l_α l_β cos φ T_α)/J] = 0,
//   J = |r_α × r_β|   (the planar Jacobian when z = 0)
//
//   θ = 0 on Γ1 (i = 0),  θ = 1 on Γ3 (i = nx−1),  ∂θ/∂n = 0 on Γ2, Γ4 (natural)
//   η = 0 on Γ2 (j = 0),  η = 1 on Γ4 (j = ny−1),  ∂η/∂n = 0 on Γ1, Γ3 (natural)
//
// Per reference cell the bilinear map r(ξ,ζ) gives the element stiffness
// K_ab = ∫∫ ∇N_a · [[G22, −G12], [−G12, G11]]/√g · ∇N_b (2×2 Gauss), summed into one 9-point
// stencil per node. The operator is the Laplace–Beltrami operator in reference coordinates, so
// θ + i·M·η is the conformal map of the quadrilateral onto [0,1] × [0,M] (M its conformal
// modulus); the discrete energies are upper bounds: E(θ) ≥ M, E(η) ≥ 1/M, E(θ)·E(η) ≥ 1.
// Each problem is solved by preconditioned conjugate gradients (symmetric Gauss–Seidel); each
// solve is serial, the two run side by side on two threads: bit-identical for any thread count.
#pragma once

#include <vector>

#include "curvilinear/bvp/surface_grid.hpp"

namespace aq::curvilinear {

struct ThetaEtaOptions {
  /// Stop CG when ||r||₂ ≤ tolerance · ||b||₂ (b: the Dirichlet data moved to the right side).
  double tolerance = 1e-10;
  /// CG iterations per problem before NumericalError.
  int max_iterations = 20000;
};

struct ThetaEta {
  std::vector<double> theta;  ///< nodal θ, nx_pts·ny_pts values (grid order)
  std::vector<double> eta;    ///< nodal η
  double energy_theta = 0.0;  ///< discrete ∫|∇θ|² dA (≥ M)
  double energy_eta = 0.0;    ///< discrete ∫|∇η|² dA (≥ 1/M)
  int iterations_theta = 0;   ///< CG iterations used
  int iterations_eta = 0;
  /// W/H of the conformal rectangle, width along ξ over height along η: sqrt(E(η)/E(θ)).
  [[nodiscard]] double aspect_ratio() const;
};

/// Solves both problems on `reference` (≥ 2 × 2 points, every cell with |r_ξ × r_ζ| > 0 at its
/// Gauss points). `guess_theta`, `guess_eta` (nx_pts·ny_pts values or empty = i/(nx−1), j/(ny−1))
/// start CG; their boundary values are replaced by the Dirichlet data. Throws NumericalError for
/// a degenerate cell (naming it) or when CG does not converge.
ThetaEta solve_theta_eta(const SurfaceGrid& reference, const ThetaEtaOptions& options = {},
                         const std::vector<double>& guess_theta = {}, const std::vector<double>& guess_eta = {});

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Orthogonality of a grid in the plane or on a surface, seed 003 Sec. 5.1 (digest
// orthogonal_bvp_and_elliptic.md A.10): per cell the cosine between the mean directions of its
// two pairs of opposite edges, n_a ∝ a_0 + a_1 and n_b ∝ b_0 + b_1 (the direction of (46) in
// grid_checks.hpp), both first projected onto the cell's tangent plane (normal ∝ d1 × d2 of the
// diagonals), so that on the sphere the angle is the one between great-circle directions;
//
//   f_max = max |cos φ_ij|,   f_avg = sqrt( Σ S_ij cos² φ_ij / Σ S_ij ),   S_ij = ½ |d1 × d2|.
//
// In the plane f_max equals check_grid()'s ortho_err_46 worst value.
#pragma once

#include "curvilinear/bvp/surface_grid.hpp"

namespace aq::curvilinear {

struct SurfaceOrthogonality {
  double f_max = 0.0;  ///< worst |cos φ| over cells
  double f_avg = 0.0;  ///< area-weighted L2 mean of cos φ
};

/// Needs ≥ 2 × 2 points; degenerate cells (zero area or zero mean edge) are skipped.
SurfaceOrthogonality surface_orthogonality(const SurfaceGrid& grid);

}  // namespace aq::curvilinear

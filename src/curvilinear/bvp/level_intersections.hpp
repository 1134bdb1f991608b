// SPDX-License-Identifier: GPL-3.0-or-later
// Nodes of the orthogonal grid as intersections of the level lines θ = θ_p and η = η_q of the
// nodal solutions on the reference grid (seed 003 Sec. 4; digest orthogonal_bvp_and_elliptic.md
// A.6, A.7):
//
//   1. trace θ = θ_p from the south side (j = 0) to the north side as the polyline of its
//      crossings with reference-grid edges, η interpolated along each crossed edge;
//   2. on it, the point where η = η_q: X^θ_pq (linear, or natural cubic splines in the polyline
//      index for x, y, z and η, root taken inside the bracketing segment);
//   3. the same with θ and η swapped (η = η_q traced west -> east): X^η_pq;
//   4. X_pq = ½ (X^θ_pq + X^η_pq).
//
// The boundary levels θ_0 = 0, θ_P = 1 (η_0 = 0, η_Q = 1) are the boundary polylines themselves,
// so boundary nodes are where the other function's levels cut the reference boundary; corners are
// the reference corners. Deterministic tie-breaking instead of the paper's random noise: a value
// equal to the level counts as above it; a saddle cell (four crossed edges) is resolved by the
// asymptotic decider (the bilinear saddle value).
#pragma once

#include <vector>

#include "curvilinear/bvp/surface_grid.hpp"
#include "grid_params/grid_kinds.hpp"

namespace aq::curvilinear {

/// The (P+1) × (Q+1) grid of level-line intersections, P+1 = theta_levels.size(),
/// Q+1 = eta_levels.size(). Levels must increase strictly from exactly 0 to exactly 1. theta and
/// eta are nodal values on `reference` (as from solve_theta_eta: θ = 0, 1 on i = 0, nx−1 and
/// η = 0, 1 on j = 0, ny−1). Throws NumericalError when a level line cannot be traced across
/// (it leaves through the side it started from: θ or η not monotone along a boundary), naming the
/// level; InternalError for levels that do not increase from 0 to 1.
SurfaceGrid level_intersections(const SurfaceGrid& reference, const std::vector<double>& theta,
                                const std::vector<double>& eta, const std::vector<double>& theta_levels,
                                const std::vector<double>& eta_levels, LevelInterpolation interpolation);

/// Uniform levels k/n, k = 0..n, or levels whose steps grow geometrically so that the last step is
/// `ratio` times the first (ratio > 0; 1 = uniform; < 1 clusters toward level 1). n ≥ 1.
std::vector<double> graded_levels(int n, double ratio = 1.0);

}  // namespace aq::curvilinear

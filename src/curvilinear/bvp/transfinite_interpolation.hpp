// SPDX-License-Identifier: GPL-3.0-or-later
// Classic transfinite interpolation (Coons patch) of a logically rectangular grid from its four
// boundary polylines: the reference grid of iteration 0 of the orthogonal-family method (seed 003
// Sec. 4; digest orthogonal_bvp_and_elliptic.md A.1, A.8). Bilinear blending in the index
// parameters ξ = i/(nx−1), η = j/(ny−1):
//
//   X(ξ,η) = (1−η) S(ξ) + η N(ξ) + (1−ξ) W(η) + ξ E(η)
//            − [(1−ξ)(1−η) SW + ξ(1−η) SE + ξη NE + (1−ξ)η NW]
#pragma once

#include <vector>

#include "curvilinear/bvp/surface_grid.hpp"

namespace aq::curvilinear {

/// The TFI grid of nx = south.size() by ny = west.size() points. south and north run west -> east
/// (i = 0..nx−1), west and east south -> north (j = 0..ny−1); shared corners must agree (the south
/// side's are used). Boundary points are reproduced exactly. Throws InternalError if nx, ny < 2 or
/// the opposite sides differ in length.
SurfaceGrid transfinite_interpolation(const std::vector<Vec3>& south, const std::vector<Vec3>& east,
                                      const std::vector<Vec3>& north, const std::vector<Vec3>& west);

}  // namespace aq::curvilinear

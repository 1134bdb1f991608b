// SPDX-License-Identifier: GPL-3.0-or-later
// The bvp method of `aquatoria regional` (regional.method = "bvp"; seed 003, digest
// orthogonal_bvp_and_elliptic.md A): from the contour and its uniform boundary nodes to the same
// (2nx+1) × (2ny+1) supergrid the Laplace fill gives, so every downstream file and check works.
//
//   uniform boundary nodes --TFI--> reference grid 0 --orthogonal_bvp (θ, η; level lines)--> grid
//
// surface = plane: everything in the projection plane (z = 0).
// surface = sphere: the reference grid's nodes are mapped to the unit sphere by the inverse
//   projection and the equations are solved there with the |r_α × r_β| metric (seed 003 Sec. 3.2);
//   no map projection enters the solution. Nodes are put back onto the sphere (normalised) after
//   every iteration. The returned Grid2D holds the sphere grid's nodes mapped forward into the
//   projection plane (that is what _xygrid.nc stores; _grd.nc maps them back to the sphere).
// In both, boundary nodes are moved back onto the spline contour (closest point on their side,
// found in the plane) after every iteration; corners stay the contour's corners.
//
// Grid size: ny is kept; with auto_nx (or nx = 0) nx = round(ny · W/H), W/H = sqrt(E(η)/E(θ)) of a
// first θ, η solve on the TFI grid (the conformal modulus), so cells are square for uniform levels.
#pragma once

#include "curvilinear/common/boundary_nodes.hpp"
#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/bvp/orthogonal_bvp.hpp"
#include "curvilinear/common/projection.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "grid_params/regional_params.hpp"

namespace aq::curvilinear {

struct RegionalBvp {
  Grid2D grid;                  ///< the supergrid in the projection plane
  BoundaryNodes nodes;          ///< its boundary nodes as contour parameters
  BvpResult bvp;                ///< outer-iteration history (f_max, f_avg on the plane or the sphere)
  double aspect_ratio = 0.0;    ///< W/H from the first solve (the conformal modulus, inverted)
  int nx = 0;                   ///< cells along ξ of the final (ρ) grid
  double interface_kink = 0.0;  ///< two blocks: largest angle (rad) of an η-line at the interface
};

/// Builds the grid. `uniform` are the uniform boundary nodes of a (2nx0+1) × (2ny+1) supergrid
/// (stage 2; they define the reference grid 0). Throws NumericalError from the solver or the
/// level-line tracing, InputError when a node falls where the projection is singular.
/// With `contour2` and `uniform2` (a second block whose west side is the first one's east side,
/// bvp_two_blocks.hpp) the two grids (same ny) are merged into one supergrid of
/// (2nx_A + 2nx_B + 1) × (2ny+1) points; `nodes` are then the first block's.
RegionalBvp regional_bvp(const SplineContour& contour, const BoundaryNodes& uniform, const Projection& projection,
                         const RegionalParams& params, const SplineContour* contour2 = nullptr,
                         const BoundaryNodes* uniform2 = nullptr);

}  // namespace aq::curvilinear

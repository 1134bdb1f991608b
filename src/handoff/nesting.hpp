// SPDX-License-Identifier: GPL-3.0-or-later
// Nesting data of a regional grid in the global mesh (ARCHITECTURE §6): for every open-boundary
// ρ, u and v point of the regional C-grid, the global triangle holding it and its barycentric
// weights, and the refinement ratio there. The C-grid staggering is curvilinear/cgrid.hpp's
// (ρ(i, j) = G[2i][2j] on the contour, u(k, j) = G[2k+1][2j], v(i, l) = G[2i][2l+1]), so the
// boundary points are, per ROMS boundary (a corner point belongs to both of its boundaries):
//
//   west  (1):  ρ(0, j), j = 0..M     u(0, j), j = 0..M       v(0, l), l = 0..M-1
//   south (2):  ρ(i, 0), i = 0..L     u(k, 0), k = 0..L-1     v(i, 0), i = 0..L
//   east  (3):  ρ(L, j)               u(L-1, j)               v(L, l)
//   north (4):  ρ(i, M)               u(k, M)                 v(i, M-1)
//
// — the outermost row/column of each of ρ, u and v, where ROMS reads boundary values (u(0, j) is
// ROMS's u(1, j) on the western boundary, v(i, 0) its v(i, 1) on the southern one).
//
// Location: handoff/mesh_locator.hpp (O(L) per point), on either lattice: the weights are those of
// the lattice plane (λ', φ' or λ' and the Mercator ordinate). Refinement ratio = global element
// size / regional cell size, with the element's leg length ℓ = √(2·area) in pixels times Δ_L in
// radians times R·Lattice::size_scale at the point (R = the C-grid's earth radius; the scale is
// √(cos φ'), the geometric mean of the metres per radian along λ' and φ', on the lon-lat lattice
// and cos φ' on the Mercator one), and the regional cell size √(1/(pm·pn)) at ρ points (the mean of the
// two neighbouring ρ points for u and v). Points outside the global wet mesh get element −1,
// weights 0 and ratio NaN and are counted.
#pragma once

#include <cstdint>

#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/grid2d.hpp"
#include "grid_files/nesting_netcdf.hpp"
#include "handoff/mesh_locator.hpp"
#include "mesh/mesh.hpp"

namespace aq::handoff {

enum class CPointType : std::int8_t { kRho = 0, kU = 1, kV = 2 };
/// ROMS's boundary numbering (iwest = 1, isouth = 2, ieast = 3, inorth = 4).
enum class RomsBoundary : std::int8_t { kWest = 1, kSouth = 2, kEast = 3, kNorth = 4 };

struct BoundaryPoint {
  CPointType type = CPointType::kRho;
  RomsBoundary boundary = RomsBoundary::kWest;
  int xi = 0, eta = 0;  ///< 0-based index into the type's ROMS array (cgrid.hpp file index)
  int si = 0, sj = 0;   ///< the supergrid point it is
};

/// Supergrid index (I, J) of point (xi, eta) of a type (see the file comment).
std::array<int, 2> supergrid_index(CPointType type, int xi, int eta);

/// The boundary points of a C-grid with L × M ρ cells (L, M >= 1), in the order west, south,
/// east, north; within a boundary ρ, u, v; along it by increasing index.
std::vector<BoundaryPoint> boundary_points(int L, int M);

struct NestingSummary {
  std::int64_t points = 0;
  std::int64_t outside = 0;   ///< points outside the global wet mesh
  double ratio_median = 0.0;  ///< refinement ratio over the points inside (NaN if none)
  double ratio_min = 0.0, ratio_max = 0.0;
};

/// Nesting data of the regional grid (`supergrid` in the plane of `cgrid`'s projection; `cgrid`
/// built from it by curvilinear::build_cgrid) in `mesh`. Fills every per-point array of the
/// result and the attributes points_total, points_outside, refinement_ratio (median),
/// refinement_ratio_min/max, global_mesh_nodes/triangles, lattice_kind, lattice_step0_deg,
/// lattice_levels, lattice_lon0_deg, lattice_y0_deg (Mercator), pole_lon/lat_deg (with rotation)
/// and staggering. Throws InternalError when
/// the supergrid and the C-grid disagree in size, and what MeshLocator throws.
io::NestingFile global_nesting(const curvilinear::Grid2D& supergrid, const curvilinear::CGrid& cgrid,
                               const mesh::Mesh& mesh, NestingSummary* summary = nullptr);

}  // namespace aq::handoff

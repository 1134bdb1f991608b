// SPDX-License-Identifier: GPL-3.0-or-later
// Back to the sphere: the Arakawa C-grid of a ROMS grid file from the izogrid supergrid (seed 000
// Sec. 2.5 end, digest izogrid.md §9 [S]; ROMS Data/ROMS/CDL/grd_spherical.cdl). The planar
// (2L+1) × (2M+1) supergrid G is mapped to longitude/latitude by the inverse projection and split
// into ρ, u, v and ψ points; metrics and angles come from distances and directions on the sphere.
//
// Index convention. ρ points are the even supergrid points *including the contour*; ROMS's
// boundary ρ row/column (i = 0, L and j = 0, M, "ghost" points outside the physical domain) lies
// on the contour, the physical boundary (u(1), u(L), v(1), v(M), the ψ points) half a cell inside:
//
//   supergrid I →    0     1     2     3     4   ...  2L-1   2L
//   J = 2M           ρ     u     ρ     u     ρ          u     ρ     ← ρ row j = M (north contour)
//   J = 2M-1         v     ψ     v     ψ     v          ψ     v     ← v, ψ row M-1 (file index)
//     ...
//   J = 2            ρ     u     ρ     u     ρ          u     ρ     ← ρ row j = 1
//   J = 1            v     ψ     v     ψ     v          ψ     v     ← v, ψ row 0 (file index)
//   J = 0            ρ     u     ρ     u     ρ          u     ρ     ← ρ row j = 0 (south contour)
//
//   ρ(i, j)   = G[2i  ][2j  ]   i = 0..L,   j = 0..M     dims (eta_rho = M+1, xi_rho = L+1)
//   u(k, j)   = G[2k+1][2j  ]   k = 0..L-1, j = 0..M     dims (eta_u = M+1,   xi_u = L)
//   v(i, l)   = G[2i  ][2l+1]   i = 0..L,   l = 0..M-1   dims (eta_v = M,     xi_v = L+1)
//   ψ(k, l)   = G[2k+1][2l+1]   k = 0..L-1, l = 0..M-1   dims (eta_psi = M,   xi_psi = L)
//
// File index k is ROMS's Fortran index k+1 for u and ψ (ROMS u(i) sits between ρ(i-1) and ρ(i)),
// so u file index k lies between ρ k and k+1, v file index l between ρ rows l and l+1, and ψ (k, l)
// is the corner shared by ρ (k, l), (k+1, l), (k, l+1), (k+1, l+1). All arrays are row-major with
// ξ fastest: value (i, j) at j·ni + i, as netCDF stores (eta, xi).
//
// Metrics (at ρ):
//   1/pm(i,j) = |G[2i-1][2j] G[2i][2j]| + |G[2i][2j] G[2i+1][2j]|  (u(i-1) → ρ → u(i), two
//               supergrid half steps along the ξ line, measured on the Earth); at i = 0 and
//               i = L (on the contour) the outer half step is extrapolated linearly from the two
//               inner ones h1 (next to the contour) and h2: 1/pm = max(3·h1 − h2, 1.5·h1);
//   1/pn      likewise along η;
//   angle     = direction of the ξ line at ρ, radians counter-clockwise from east (ROMS: u_east =
//               u·cos(angle) − v·sin(angle)): the tangent from Earth-centred positions, centred
//               X(G[2i+1]) − X(G[2i−1]) inside and one-sided second order −3X(G[0]) + 4X(G[1]) −
//               X(G[2]) (mirrored at i = L) on the boundary, resolved into local east and north;
//   dndx      = ∂(1/pn)/∂ξ, dmde = ∂(1/pm)/∂η: centred differences of ρ neighbours, one-sided on
//               the boundary (metres per grid step);
//   f         = 2Ω sin φ with Ω = kEarthOmega = 7.2921e-5 s⁻¹.
// Distances are great circles on a sphere of radius `earth_radius_m` (atan2 form without
// cancellation, accurate at every distance) or, with DistanceModel::kWgs84, geodesics on the
// WGS84 ellipsoid (GeographicLib Geodesic::WGS84(), ~15 nm accuracy) taking the latitudes as
// geodetic; `angle` then uses WGS84 Earth-centred positions (GeographicLib Geocentric).
//
// x_*, y_* (metres) are the plane coordinates times the projection's true scale at its centre
// (metres_per_unit(0, 0), rescaled to earth_radius_m): metres along the plane axes, exact
// distances only near the centre. ROMS uses them only when spherical = F.
// xl, el: the lengths of the ρ lines between the contour's opposite sides (sum of supergrid
// half steps along ξ, resp. η), averaged over the lines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/projection.hpp"

namespace aq::curvilinear {

/// Earth's rotation rate used for f, s⁻¹ (sidereal, 7.2921e-5 rounded as in most ROMS tools).
inline constexpr double kEarthOmega = 7.2921e-5;

struct CGridOptions {
  /// Sphere radius, metres, > 0: pm, pn, xl, el with kSphere; x_*, y_* always.
  double earth_radius_m = 6371000.0;
  DistanceModel distances = DistanceModel::kSphere;
};

/// One staggered family of points (ρ, u, v or ψ): ni × nj points, value (i, j) at j·ni + i.
struct StaggeredPoints {
  int ni = 0, nj = 0;
  std::vector<double> lon_deg, lat_deg;  ///< geographic, degrees (longitude continuous near rlon)
  std::vector<double> x_m, y_m;          ///< plane coordinates in metres (see file comment)
  [[nodiscard]] std::size_t at(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  }
  [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj); }
};

/// The C-grid of a ROMS grid file: L = xi_rho − 1, M = eta_rho − 1.
struct CGrid {
  int L = 0, M = 0;
  StaggeredPoints rho, u, v, psi;
  /// At ρ points (rho.size() values each).
  std::vector<double> pm, pn;       ///< 1/m
  std::vector<double> dndx, dmde;   ///< m
  std::vector<double> angle;        ///< radians, counter-clockwise from east to the ξ axis
  std::vector<double> f;            ///< s⁻¹
  double xl_m = 0.0, el_m = 0.0;    ///< domain lengths in ξ and η, metres
  double xy_metres_per_unit = 0.0;  ///< scale applied to plane coordinates for x_*, y_*
  CGridOptions options;             ///< as used
};

/// Summary figures of a C-grid (over all ρ points unless said).
struct CGridStats {
  double pm_min = 0, pm_max = 0, pn_min = 0, pn_max = 0;  ///< 1/m
  double dx_min_m = 0, dx_max_m = 0;                      ///< 1/pm, 1/pn extremes together
  double isotropy_max = 0;                                ///< max |pm/pn − 1| over all ρ points
  double isotropy_max_interior = 0;                       ///< the same without the boundary rows/columns
  int isotropy_worst_i = 0, isotropy_worst_j = 0;         ///< where isotropy_max is reached
  double angle_min = 0, angle_max = 0;                    ///< radians
};

/// Builds the C-grid of `supergrid` (plane coordinates of `projection`). Preconditions:
/// nx_pts and ny_pts odd and ≥ 5 (L, M ≥ 2), coordinates finite. Throws InputError naming the
/// size for an even or too small supergrid, InputError for points where the inverse projection is
/// not finite, InternalError for a non-positive or non-finite earth_radius_m, NumericalError when
/// two neighbouring supergrid points coincide on the Earth (pm or pn would be infinite).
/// Parallel over rows with OpenMP; results do not depend on the thread count.
CGrid build_cgrid(const Grid2D& supergrid, const Projection& projection, const CGridOptions& options = {});

/// The corners of the ρ cells of `g`: (L+2) × (M+2) points (value (a, b) at b·(L+2) + a, the
/// layout of mask/cell_elevation.hpp), corner (a, b) = ψ(a−1, b−1) for the ψ points that exist
/// and, for the boundary ρ cells (i = 0, L or j = 0, M, centred on the contour), extrapolated
/// linearly in longitude/latitude from the two nearest ψ columns, then rows (latitudes clamped to
/// ±90°). Cell (i, j) of that layout is the ρ cell (i, j).
void rho_cell_corners(const CGrid& g, std::vector<double>& lon_deg, std::vector<double>& lat_deg);

/// pm/pn ranges, isotropy and angle range of `g`.
CGridStats cgrid_stats(const CGrid& g);

/// The largest area ratio of two neighbouring interior ρ cells (area 1/(pm·pn); i and j from 1 to
/// L−1, M−1) and the first cell (row by row) where it is reached; 1 with no pair.
struct AreaJump {
  double ratio = 1.0;
  int i = 0, j = 0;
};
AreaJump max_area_jump(const CGrid& g);

/// Interior ρ cells finer than a raster of `dlon_deg` × `dlat_deg` pixels in both directions (the
/// pixel's size on a sphere of `radius_m` above both 1/pm and 1/pn): their depths are interpolated
/// between raster points, not measured. `worst_k` is the ρ index with the most cells per raster spacing.
struct FinerThanRaster {
  std::int64_t finer = 0, interior = 0;
  double worst = 0.0;  ///< the most cells per raster spacing (0 when none is finer)
  std::size_t worst_k = 0;
};
FinerThanRaster finer_than_raster(const CGrid& g, double dlon_deg, double dlat_deg, double radius_m);

/// Great-circle distance between two points on a sphere of `radius_m`, metres (atan2 form).
double great_circle_m(double lon1_deg, double lat1_deg, double lon2_deg, double lat2_deg, double radius_m);

}  // namespace aq::curvilinear

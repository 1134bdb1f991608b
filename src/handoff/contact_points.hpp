// ROMS contact points of a regional grid (receiver, "child") nested inside another regional ROMS
// grid (donor, "parent"): refinement-style nesting in the sense of ROMS's nesting.cdl
// (io/contact_netcdf.hpp for the file). For every perimeter ρ, u and v point of the child
// C-grid (ρ: i = 0, L or j = 0, M; u: ROMS i = 1, L or j = 0, M; v: i = 0, L or ROMS j = 1, M;
// each point once, on_boundary = the first of west, south, east, north it lies on):
//   Idg, Jdg   the parent cell of the same point type containing the point, as ROMS indices of its
//              lower-left corner (ρ: file index; u: ROMS I = file k + 1; v: ROMS J = file l + 1);
//   Lweight    bilinear weights of the cell corners (Idg,Jdg), (Idg+1,Jdg), (Idg+1,Jdg+1),
//              (Idg,Jdg+1) in longitude/latitude: Σ w_k (lon_k, lat_k) reproduces the point;
//   Qweight    biquadratic Lagrange weights on the 3 × 3 donor points (Idg-1..Idg+1) ×
//              (Jdg-1..Jdg+1) (the stencil shifted inward at the parent's edges), in the donor's
//              fractional index space given by the bilinear cell map, i fastest; they sum to 1;
//   Irg, Jrg   the point's ROMS indices in the child;  Xrg, Yrg its longitude, latitude;
//   h, f, pm, pn, dndx, dmde, angle: the parent ρ fields interpolated bilinearly at the point
//   (angle through its sine and cosine); mask: the parent mask of the point's type at the donor
//   corner with the largest weight.
// Location: a coarse scan finds the nearest parent point, the bilinear map of the 4 cells around
// it is inverted by Newton's method, then the search walks cell to cell towards the point, and as
// a last resort tries every cell. A point in no cell is outside the parent: ConfigError.
#pragma once

#include <string>

#include "curvilinear/cgrid.hpp"
#include "io/contact_netcdf.hpp"

namespace aq::handoff {

struct ContactSummary {
  std::size_t points = 0, rho = 0, u = 0, v = 0;
  double ratio_median = 0.0, ratio_min = 0.0, ratio_max = 0.0;  ///< parent / child grid step at ρ points
  std::size_t wet_points = 0;                                   ///< mask = 1
};

/// Contact points of `child` in `parent`. `context` (e.g. "configs/child.toml: nesting.parent =
/// x_grd.nc") starts the error message when a child point lies outside the parent grid.
io::ContactFile contact_points(const io::RomsGridFields& parent, const curvilinear::CGrid& child,
                               const std::string& context, ContactSummary* summary = nullptr);

}  // namespace aq::handoff

// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS contact points of a refinement grid (receiver of region 1, "fine") and its parent (donor of
// region 1, "coarse"), as ROMS's contact.m sets them for refinement and ROMS's nesting.F uses them
// (io/contact_netcdf.hpp for the file). The fine grid is the parent's ψ box I_left..I_right ×
// J_bottom..J_top (Io..Ie × Jo..Je) split r × r (curvilinear/refine.hpp), with L = r(Ie−Io) + 1,
// Lm = L − 1, likewise M, Mm. ROMS indices: ρ 0..L, u 1..L (ξ), v 1..M (η), ψ 1..L; in the
// parent's fractional index space ψ(I) is at ξ = I, ρ(i) at i + ½, fine ρ(i) at Io + (i − ½)/r.
//
// Region 1 (coarse → fine): the fine points of the band around the fine interior that ROMS fills
// from the coarse grid,
//   ρ  i = −3..L+2, j = −3..M+2 except i = 1..Lm ∧ j = 1..Mm;
//   u  i = −2..L+2, j = −3..M+2 except i = 2..Lm ∧ j = 1..Mm (the boundary u points included);
//   v  i = −3..L+2, j = −2..M+2 except i = 1..Lm ∧ j = 2..Mm.
// Idg, Jdg: the lower-left coarse point of the same type of the coarse cell holding the point
// (ρ: Io + ⌊(i − (r+1)/2)/r⌋, u: Io + ⌊(i − 1)/r⌋, v: ρ's rule in ξ, u's in η), computed in exact
// integer arithmetic; Lweight: bilinear in the coarse fractional index space, corners (Idg,Jdg),
// (Idg+1,Jdg), (Idg+1,Jdg+1), (Idg,Jdg+1); Qweight: 3 × 3 around (Idg,Jdg), i fastest, quadratic
// Lagrange plus ROMS's cell-average term α = ((1/r)² − 1)/24. on_boundary: 1 (west) for u at
// i = 1, 3 (east) at i = L, 2 (south) for v at j = 1, 4 (north) at j = M, along the interior rows
// and columns; 0 elsewhere. ρ slots carry h, f, angle interpolated bilinearly from the coarse grid
// (angle through sine and cosine) and pm, pn, dndx, dmde of the fine grid (from `fine`, which
// extends `pad` fine cells past the grid); u and v slots carry kContactFill. mask: the coarse ρ mask
// at the coarse ρ cell holding the point, u and v as products of the two adjacent such ρ masks.
// With the fine grid file's values (ReceiverValues), the points inside the fine grid (the ρ ring
// i = 0, L or j = 0, M; u and v on it or across it) take its h and masks instead, which ROMS then
// copies onto themselves (handoff/nested_bathymetry.hpp makes the ring's mask the coarse cell's).
// Xrg, Yrg: the fine point; Xdg, Ydg: the donor point (Idg, Jdg).
//
// Region 2 (fine → coarse): the coarse points inside the fine grid, which ROMS replaces by the
// average of the r × r fine points around the fine point (Idg, Jdg) at their centre:
//   ρ  i = Io..Ie−1, j = Jo..Je−1:  Idg = (r+1)/2 + (i−Io)·r, Jdg likewise;
//   u  i = Io+1..Ie−1, j = Jo..Je−1: Idg = 1 + (i−Io)·r,       Jdg as ρ;
//   v  i = Io..Ie−1, j = Jo+1..Je−1: Idg as ρ,                 Jdg = 1 + (j−Jo)·r;
// weights 0, on_boundary 0, fields and mask the coarse grid's own values (ROMS copies them into the
// coarse grid, so `parent` must be the parent grid file ROMS runs with), Xrg, Yrg the coarse point,
// Xdg, Ydg the fine point.
// Within each region and type the points run j outer, i inner.
#pragma once

#include <string>

#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/refine.hpp"
#include "grid_files/contact_netcdf.hpp"

namespace aq::handoff {

struct ContactSummary {
  std::size_t points = 0;
  std::array<std::size_t, 3> coarse_to_fine{};  ///< ρ, u, v points of region 1
  std::array<std::size_t, 3> fine_to_coarse{};  ///< ρ, u, v points of region 2
  std::size_t wet_points = 0;                   ///< mask = 1
  double ratio_median = 0.0;                    ///< coarse / fine ρ step over region 1's ρ points
};

/// The parent ψ range a refinement box must keep inside so that every region-1 point has a whole
/// coarse donor cell: I_left ≥ 2, J_bottom ≥ 2, I_right ≤ Lp − 1, J_top ≤ Mp − 1 (Lp = parent
/// xi_rho − 1). "" when `box` fits, else the reason, naming the indices and the parent's range.
std::string refinement_box_problem(const curvilinear::RefineBox& box, int parent_L, int parent_M);

/// The refinement grid file's own h and masks (ρ (L+1) × (M+1), u L × (M+1), v (L+1) × M, file
/// layout). ROMS overwrites the refinement grid's values at its region-1 points with the contact
/// file's; given these, region-1 points inside the grid (the outer ρ ring, the boundary u and v
/// points) carry them, so the two files agree there.
struct ReceiverValues {
  std::vector<double> h;
  std::vector<std::uint8_t> mask_rho, mask_u, mask_v;
};

/// Both contact regions of the refinement `box` of `parent`. `fine` is the C-grid of the fine grid
/// padded by `pad` ≥ 4 cells on every side (refine_supergrid(..., pad) → build_cgrid); `receiver`
/// (optional) the fine grid file's h and masks. Throws ConfigError (from refinement_box_problem)
/// for a box too close to the parent's edge, InternalError when `fine` or `receiver` does not have
/// the box's size.
io::ContactFile refinement_contact(const io::RomsGridFields& parent, const curvilinear::RefineBox& box,
                                   const curvilinear::CGrid& fine, int pad, ContactSummary* summary = nullptr,
                                   const ReceiverValues* receiver = nullptr);

/// A parent ρ field (e.g. h) at the refinement grid's ρ points 0..L × 0..M (value (i, j) at
/// j·(L+1) + i), bilinear in the parent's fractional index space: the interpolation region 1 of
/// refinement_contact uses, so on the fine grid's outer ρ ring it equals the contact file's value
/// there (which ROMS copies into the fine grid). Throws ConfigError as refinement_contact does.
std::vector<double> parent_rho_on_fine(const io::RomsGridFields& parent, const std::vector<double>& field,
                                       const curvilinear::RefineBox& box);

/// The same for a parent ρ field of (parent_L + 1) × (parent_M + 1) values.
std::vector<double> parent_rho_on_fine(const std::vector<double>& field, int parent_L, int parent_M,
                                       const curvilinear::RefineBox& box);

}  // namespace aq::handoff

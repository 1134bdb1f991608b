// SPDX-License-Identifier: GPL-3.0-or-later
// The land mask of a regional (ROMS) grid from the global run's ocean (ARCHITECTURE §5 stage 5,
// §6: "the regional land mask agrees with the global Ω_L"; field.md D3; roms-tools #66), so the
// regional ocean is exactly the globally connected ocean: a lake or an unconnected sea inside the
// regional block stays land however deep it is.
//
// Rule for a ρ point at geographic (λ, φ) with sampled elevation d (metres, negative below sea
// level) and the global threshold h (mask.min_depth_m):
//
//     wet  ⇔  pixel(λ, φ) ∈ Ω_L  and  d ≤ −h
//
// where pixel(λ, φ) is the lattice pixel containing the point after the global run's pole
// rotation: (λ', φ') = rotated(λ, φ), i = floor((λ' − lon0)/Δ_L) mod nx, j = floor((φ' + 90)/Δ_L)
// (φ' = 90 goes to the top row; on the Mercator lattice j = floor(row_of_lat(φ')), and a point
// beyond its rows lies in the dry cap, in no pixel of Ω_L). A point on a pixel edge belongs to the
// pixel east / north of it.
// The depth test removes islands smaller than a pixel; it never adds water outside Ω_L.
//
// Then, as ROMS expects (ROMS's boundary ρ points are ghost points outside the physical domain):
//   boundary copy  mask_rho(0, j) = mask_rho(1, j), mask_rho(L, j) = mask_rho(L−1, j) for the
//                  interior rows, then rows 0 and M copy rows 1 and M−1 (so corners copy the
//                  diagonal interior point);
//   mask_u(k, j)   = mask_rho(k, j)·mask_rho(k+1, j)                 (u between ρ k and k+1)
//   mask_v(i, l)   = mask_rho(i, l)·mask_rho(i, l+1)
//   mask_psi(k, l) = mask_rho(k, l)·mask_rho(k+1, l)·mask_rho(k, l+1)·mask_rho(k+1, l+1)
// with the file indices of curvilinear/cgrid.hpp. Every *interior* wet ρ point is therefore in
// Ω_L; a boundary ρ point is wet exactly when its interior neighbour is.
// Arrays are row-major with ξ fastest: value (i, j) at j·ni + i; masks hold 0 (land) or 1 (water).
#pragma once

#include <cstdint>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "mask/lattice_coords.hpp"
#include "raster/bathymetry.hpp"

namespace aq::mask {

/// Counts describing how the ρ mask came about.
struct RegionalMaskStats {
  std::int64_t rho_points = 0;
  std::int64_t in_filled = 0;          ///< ρ points whose pixel is in Ω_L
  std::int64_t deep_enough = 0;        ///< ρ points with d ≤ −h
  std::int64_t lake_points = 0;        ///< deep enough, outside Ω_L, in a wet pixel (lakes, unconnected seas): land
  std::int64_t coastal_points = 0;     ///< deep enough, outside Ω_L, in a pixel with a dry vertex: land
  std::int64_t shallow_in_filled = 0;  ///< in Ω_L but d > −h (sub-pixel islands, shoals): land
  std::int64_t boundary_changed = 0;   ///< boundary ρ points the copy from the interior changed
  std::int64_t wet_rho = 0, wet_u = 0, wet_v = 0, wet_psi = 0;  ///< final counts
  std::int64_t wet_rho_interior = 0;                            ///< wet ρ points off the boundary rows/columns
};

/// The four masks of a ROMS grid: rho is ni × nj, u (ni−1) × nj, v ni × (nj−1), psi (ni−1) × (nj−1).
struct RomsMasks {
  int ni = 0, nj = 0;  ///< ρ points: ni = L+1, nj = M+1
  std::vector<std::uint8_t> rho, u, v, psi;
  RegionalMaskStats stats;
};

/// The lattice pixel containing geographic point (lon, lat), by the rule above (the nearest row's
/// pixel for a point beyond the Mercator rows; `on_rows`, when given, says whether it was on them).
[[nodiscard]] PixelIJ pixel_of_point(const Lattice& lattice, const PoleRotation& rot, double lon_deg, double lat_deg,
                                     bool* on_rows = nullptr);

/// Elevations (m, negative below sea level) of n points sampled with the raster's own sampling
/// (as the global mesh samples it). Throws InputError naming the raster when any point has no
/// data: the regional grid leaves the raster's coverage (count and the first such point given).
std::vector<double> sample_elevations(const raster::Bathymetry& bathy, const double* lon_deg, const double* lat_deg,
                                      std::size_t n);

/// The raw ρ mask: 1 where the point's pixel is in `filled` (Ω_L, lattice.nx × lattice.ny) and,
/// when `elevation_m` is given, elevation ≤ −threshold_m. Fills the in_filled, deep_enough,
/// lake_points, coastal_points and shallow_in_filled counts of `stats` (if given); the deep points
/// outside Ω_L count as lake points unless `wet_pixels` (the global run's wet pixels) says their
/// pixel is not wet (coastal points). InternalError when a bitmap does not match the lattice.
std::vector<std::uint8_t> rho_mask_from_filled(const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot,
                                               const double* lon_deg, const double* lat_deg, const double* elevation_m,
                                               double threshold_m, std::size_t n, RegionalMaskStats* stats = nullptr,
                                               const Bitmap* wet_pixels = nullptr);

/// Makes the boundary rows/columns equal their nearest interior point (ni, nj ≥ 3); returns the
/// number of points changed. InternalError for sizes that do not match or ni, nj < 3.
std::int64_t copy_boundary_from_interior(std::vector<std::uint8_t>& mask_rho, int ni, int nj);

/// mask_u, mask_v, mask_psi from mask_rho by the ROMS rules above.
void derive_staggered_masks(const std::vector<std::uint8_t>& mask_rho, int ni, int nj,
                            std::vector<std::uint8_t>& mask_u, std::vector<std::uint8_t>& mask_v,
                            std::vector<std::uint8_t>& mask_psi);

/// All steps: raw ρ mask, boundary copy, u/v/ψ masks and the counts. `lon_deg`, `lat_deg`,
/// `elevation_m` are ρ arrays of ni × nj (elevation may be null: pixel rule only); `wet_pixels`
/// only refines the counts.
RomsMasks build_roms_masks(const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot, const double* lon_deg,
                           const double* lat_deg, const double* elevation_m, double threshold_m, int ni, int nj,
                           const Bitmap* wet_pixels = nullptr);

}  // namespace aq::mask

// SPDX-License-Identifier: GPL-3.0-or-later
// The physical terms of the size field (ARCHITECTURE §4.10), each a function of grid values so
// that it can be tested on a synthetic grid with a known answer. Sizes are in km, depths H in
// metres (positive down), +inf means "no constraint". The formulas are the peers' (OceanMesh2D
// `edgefx`, oceanmesh sizing functions; the floodplain terms those of surge meshes, OCSMesh's
// `Hfun` by elevation and the inland distance of OceanMesh2D's `dis` on land):
//   coast       h = h0 + α·d                    d: distance (km) to the nearest coast cell
//   inland      h = h0 + α·d                    d: distance (km) inland from the nearest cell holding sea
//   elevation   h = h0 + k·z                    z: elevation (m) above the datum, on the floodplain
//   feature     h = 2·(d_MA + d)/R              d_MA: distance (km) to the water's medial axis
//   wavelength  h = T·√(g·H)/wl
//   slope       h = (2π/slp)·H̄/|∇H̄|             H̄: H low-pass filtered over a box of half-width
//                                               filter·√(g·H)/|f| (Rossby radius), f = 2Ω·sin φ
//   CFL         h >= (√(g·H) + u)·Δt/Cr_max     (applied after the gradient limit)
#pragma once

#include <cstdint>
#include <vector>

#include "core/bitmap.hpp"
#include "mask/coast.hpp"
#include "size/field_grid.hpp"

namespace aq::size {

inline constexpr double kGravity = 9.81;            ///< m/s²
inline constexpr double kEarthOmega = 7.2921159e-5;  ///< rad/s

/// Coast cells: cells with at least one pixel outside the filled set (count < pixels per cell²).
std::vector<std::uint8_t> coast_cells(const FieldGrid& grid, const std::vector<std::int32_t>& filled_count);

/// Coast cells with coast sources (mask/coast.hpp): cells holding a pixel that is neither in
/// `coast.sea` (or `filled` without a sea) nor in `coast.open`: the shoreline at the datum and
/// the land, not the open water beyond a regional domain's edge.
std::vector<std::uint8_t> shore_cells(const FieldGrid& grid, const Bitmap& filled, const mask::CoastSources& coast);

/// h0 + α·d per cell, d the distance (km) to the nearest coast cell; +inf without coast cells.
std::vector<double> coast_term(const FieldGrid& grid, const std::vector<std::uint8_t>& coast, double h0_km,
                               double alpha);

/// The same from the distances d (km) to the coast (distance_to), shared with the feature term.
std::vector<double> coast_term(std::vector<double> d, double h0_km, double alpha);

/// Medial-axis cells of the water: neighbours (row or column) whose nearest coast cells lie
/// farther apart than max(2 cells, 0.8·(d_a + d_b)), i.e. on opposite banks.
std::vector<std::uint8_t> medial_axis(const FieldGrid& grid, const std::vector<double>& d,
                                      const std::vector<std::int32_t>& nearest, const std::vector<std::uint8_t>& water);

/// 2·(d_MA + d)/R per cell (R > 0): in a channel of width W this is W/R everywhere across it.
/// +inf where there is no medial axis or no coast.
std::vector<double> feature_term(const FieldGrid& grid, const std::vector<std::uint8_t>& coast,
                                 const std::vector<std::uint8_t>& water, double r);

/// The same from the distances d (km) to the coast and each cell's nearest coast cell (distance_to).
std::vector<double> feature_term(const FieldGrid& grid, const std::vector<double>& d,
                                 const std::vector<std::int32_t>& nearest, const std::vector<std::uint8_t>& water,
                                 double r);

/// T·√(g·H)/wl (km), T in hours, H (m) per cell (NaN/<= 0: +inf).
std::vector<double> wavelength_term(const std::vector<double>& depth_m, double period_h, double wl);

/// H low-pass filtered by a box mean of half-width min(filter·√(g·H)/|2Ω sin φ_geo|, max_km)
/// (km) around every cell (columns wrap, rows clip). `geo_lat_deg` is each cell's geographic
/// latitude (the Coriolis parameter is geographic); filter = 0 returns H unchanged.
std::vector<double> rossby_filter(const FieldGrid& grid, const std::vector<double>& depth_m,
                                  const std::vector<double>& geo_lat_deg, double filter, double max_km);

/// The box mean of `v` with half-widths radius_km per cell (the filter's kernel; exposed for tests).
std::vector<double> box_mean(const FieldGrid& grid, const std::vector<double>& v, const std::vector<double>& radius_km);

/// (2π/slp)·H/|∇H| (km) from central differences of `depth_m` (already filtered); +inf where
/// the gradient is 0 or a neighbour has no depth.
std::vector<double> slope_term(const FieldGrid& grid, const std::vector<double>& depth_m, double slp);

/// The CFL lower bound (√(g·H) + u)·Δt/Cr_max (km) per cell (H >= min_depth).
std::vector<double> cfl_bound(const std::vector<double>& depth_m, double dt_s, double courant_max, double u_ms);

}  // namespace aq::size

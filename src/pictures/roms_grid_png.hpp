// SPDX-License-Identifier: GPL-3.0-or-later
// Picture of a ROMS grid (<name>_roms.png): every ρ control volume filled in the projection plane,
// land tan, water blue shaded by the model depth h on a logarithmic scale, with the 0 m coastline,
// every k-th grid line (ψ lines), the contour and a depth legend. Drawn with Cairo; the bytes
// depend only on the inputs.
//
// The control volume of ρ (i, j) is the supergrid quadrilateral with corners at supergrid points
// (2i±1, 2j±1), clamped to the contour for the boundary ρ points (half and quarter cells there).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/plane_point.hpp"
#include "curvilinear/common/projection.hpp"
#include "raster/bathymetry.hpp"

namespace aq::io {

struct RomsPictureOptions {
  int width_px = 1400;      ///< image width, 200..20000; the height follows the grid's extent
  int max_grid_lines = 80;  ///< at most this many ψ lines per direction are drawn (every k-th), ≥ 2
  std::string title;        ///< drawn at the top
  /// Coastline polylines already in the plane (non-finite points cut a line).
  std::vector<std::vector<curvilinear::PlanePoint>> coastlines;
  /// Closed outlines drawn in red over everything (e.g. a refinement grid nested in this one).
  std::vector<std::vector<curvilinear::PlanePoint>> outlines;
};

/// The coastline of a grid's picture: the `level_m` contour of `bathy` (raster::contour_lines) over
/// the lon/lat box of the `n` points (`lon_deg`, `lat_deg`: the ρ points) widened by 0.5° on each
/// side (latitudes within ±90°), each point mapped into the plane by `projection` (for
/// RomsPictureOptions::coastlines).
std::vector<std::vector<curvilinear::PlanePoint>> grid_coastlines(const raster::Bathymetry& bathy, double level_m,
                                                                  const double* lon_deg, const double* lat_deg,
                                                                  std::size_t n,
                                                                  const curvilinear::Projection& projection);

/// Draws the grid of `supergrid` ((2L+1) × (2M+1) points) with `mask_rho` and `h` (ρ arrays of
/// (L+1) × (M+1), value (i, j) at j·(L+1) + i) into a PNG at `path` (OutputSet::temp_path).
/// Throws InternalError for sizes that do not match, OutputError naming the path when Cairo
/// cannot write it.
void write_roms_png(const std::filesystem::path& path, const curvilinear::Grid2D& supergrid,
                    const std::vector<std::uint8_t>& mask_rho, const std::vector<double>& h,
                    const RomsPictureOptions& options = {});

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// PNG pictures of the regional izogrid stages (seed 000 Figs. 2, 3, 10, 11: the pictures izogrid
// draws after each mode with NCAR Graphics), drawn with Cairo in the projection plane:
//   map        graticule (every latlongrid degrees) and coastline in the projection, the
//              projection's axes (dash-dot: its "equator" and central meridian), control points;
//   contour    "graph paper" in plane units, coastline, control points (corners marked), the spline
//              (quintic solid, cubic dashed when spline_type = 4) and the two tangents at each corner;
//   uniform    contour and the mode-2 boundary nodes;
//   conformal  contour and the mode-3 boundary nodes (the mode-2 ones faint);
//   grid       every grid line of the supergrid, or every k-th for big grids, and the contour.
// The picture depends only on the inputs (no time stamps).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "curvilinear/common/projection.hpp"
#include "curvilinear/regional.hpp"

namespace aq::io {

struct RegionalPictureOptions {
  /// Image width in pixels, 200..20000; the height follows the drawn extent (at most 20000).
  int width_px = 1400;
  /// Line-width multiplier (the seed's lwidth), > 0.
  double line_width = 1.0;
  /// Grid stage: at most this many grid lines per direction are drawn (every k-th line, k ≥ 1,
  /// the boundary always); ≥ 2.
  int max_grid_lines = 160;
  /// Coastline polylines in longitude/latitude degrees (e.g. the bathymetry's 0 m contour),
  /// drawn on every stage; pieces crossing a projection singularity are cut.
  std::vector<std::vector<curvilinear::GeoPoint>> coastlines;
  /// Title drawn at the top; empty = "<source>: <stage>".
  std::string title;
};

/// Draws `stage` of `result` (stage ≤ result.completed, else InternalError) into a PNG at
/// `path` (callers pass OutputSet::temp_path). Throws OutputError naming the path and Cairo's
/// message when the file cannot be written.
void write_regional_png(const std::filesystem::path& path, const curvilinear::RegionalResult& result,
                        curvilinear::Stage stage, const RegionalPictureOptions& options = {});

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// PNG heat map of a per-cell grid quality field (e.g. the orthogonality error (50) of seed 000's
// checkort): the cells drawn in the projection plane, coloured by log10 |value|, thin grid lines,
// a colour bar and a title. Cairo image surface; the picture depends only on the inputs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "curvilinear/common/grid2d.hpp"

namespace aq::io {

struct QualityPngOptions {
  int width_px = 1200;  ///< image width in pixels (200..20000); the height follows the grid
  std::string title;    ///< drawn above the map
  std::string value_label = "log10 |orthogonality error|";  ///< colour bar caption
  /// Colour range in decades: [max(floor(log10 min), ceil(log10 max) − decades), ceil(log10 max)].
  int decades = 10;
  int max_lines = 60;  ///< at most this many grid lines per direction (every k-th line)
};

/// Writes the heat map of `cell_values` ((nx_pts−1)·(ny_pts−1) values, cell (i, j) at
/// j·(nx_pts−1) + i; NaN cells grey) to `path` (callers pass OutputSet::temp_path). Cells much
/// smaller than a pixel are drawn in blocks of k×k coloured by their largest |value|.
/// Throws OutputError naming the path and Cairo's message; InternalError on size mismatch.
void write_quality_png(const std::filesystem::path& path, const curvilinear::Grid2D& grid,
                       const std::vector<double>& cell_values, const QualityPngOptions& options = {});

}  // namespace aq::io

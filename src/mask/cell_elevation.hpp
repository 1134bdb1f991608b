// SPDX-License-Identifier: GPL-3.0-or-later
// The elevation of a grid cell from a raster finer than the cell (issue 9, regional depth from a
// fine raster): a statistic over the raster sample points that fall inside the cell's polygon,
// instead of one interpolated sample at the cell centre.
//
// A cell is the quadrilateral of its four corners in longitude/latitude (degrees, longitude
// continuous over the grid), corners (i, j), (i+1, j), (i+1, j+1), (i, j+1) for cell (i, j):
//
//   corner (i, j+1) ---- (i+1, j+1)
//        |     cell (i, j)     |        corners: (ni+1) × (nj+1), value (i, j) at j·(ni+1) + i
//   corner (i, j)   ---- (i+1, j)       cells:   ni × nj,         value (i, j) at j·ni + i
//
// A raster sample point (λ_c, φ_r) of raster/bathymetry.hpp's normalised layout belongs to the
// cell whose polygon contains it (crossing-number test with half-open edges, so a point on an
// edge shared by two cells counts in exactly one). No-data points are skipped. Statistics:
//   point   the interpolated sample at the cell centre (the global run's sampling; no area rule)
//   mean    arithmetic mean of the points inside (each raster point stands for an equal area
//           of a lon/lat raster cell at that latitude; over a ROMS cell the cos φ change is
//           negligible, so the plain mean is the cell-area average)
//   median  middle value (the mean of the two middle values for an even count)
//   min     the smallest elevation (the deepest point: depth = max of depths)
//   auto    mean when the raster is finer than the cells (the median number of raster points per
//           cell is at least 4, i.e. about 2 × 2 points), point otherwise
// A cell containing no valid raster point (a cell smaller than the raster spacing) keeps the point
// sample; such cells are counted.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "config/kinds.hpp"
#include "raster/bathymetry.hpp"

namespace aq::mask {

/// roms.depth_statistic (config/kinds.hpp).
using config::CellStatistic;

struct CellElevations {
  std::vector<double> elevation_m;             ///< per cell, metres (negative below sea level)
  CellStatistic used = CellStatistic::kPoint;  ///< the statistic applied (auto resolved)
  double median_points_per_cell = 0.0;         ///< raster points per cell, median over cells
  std::int64_t point_cells = 0;                ///< cells with no raster point inside (kept the point sample)
};

/// Elevation of each of the ni × nj cells. `point_elevation_m` (ni·nj values) is the interpolated
/// sample at each cell's centre, used by `point` and for cells with no raster point inside.
/// Preconditions: ni, nj >= 1; corners finite. Parallel over cell rows (OpenMP); the result
/// does not depend on the thread count.
CellElevations cell_elevations(const raster::Bathymetry& bathy, const double* corner_lon_deg,
                               const double* corner_lat_deg, int ni, int nj, const double* point_elevation_m,
                               CellStatistic statistic);

}  // namespace aq::mask

// SPDX-License-Identifier: GPL-3.0-or-later
// Cell statistics of a fine raster (see cell_elevation.hpp).
#include "mask/cell_elevation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::mask {

namespace {

// Crossing-number test (W. R. Franklin's PNPOLY): edges are half-open in φ, so a point on an
// edge shared by two cells is inside exactly one of them.
bool inside_quad(const std::array<double, 4>& x, const std::array<double, 4>& y, double px, double py) {
  bool in = false;
  for (int k = 0, l = 3; k < 4; l = k++) {
    if ((y[k] > py) != (y[l] > py) && px < (x[l] - x[k]) * (py - y[k]) / (y[l] - y[k]) + x[k]) in = !in;
  }
  return in;
}

double statistic_of(std::vector<double>& v, CellStatistic s) {
  if (s == CellStatistic::kMin) return *std::min_element(v.begin(), v.end());
  if (s == CellStatistic::kMedian) {
    const std::size_t h = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h), v.end());
    const double upper = v[h];
    if (v.size() % 2 == 1) return upper;
    return 0.5 * (*std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h)) + upper);
  }
  double sum = 0.0;  // in point order: deterministic
  for (const double e : v) sum += e;
  return sum / static_cast<double>(v.size());
}

}  // namespace

CellElevations cell_elevations(const raster::Bathymetry& bathy, const double* corner_lon_deg,
                               const double* corner_lat_deg, int ni, int nj, const double* point_elevation_m,
                               CellStatistic statistic) {
  if (ni < 1 || nj < 1) throw InternalError(fmt::format("cell_elevations: {} x {} cells", ni, nj));
  const auto ncell = static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj);
  CellElevations out;
  out.elevation_m.assign(point_elevation_m, point_elevation_m + ncell);
  out.used = statistic;
  if (statistic == CellStatistic::kPoint) return out;
  const CellStatistic applied = statistic == CellStatistic::kAuto ? CellStatistic::kMean : statistic;

  const auto& ri = bathy.info();
  const std::size_t nci = static_cast<std::size_t>(ni) + 1;
  std::vector<std::int64_t> count(ncell, 0);
  std::vector<double> area(ncell, std::numeric_limits<double>::quiet_NaN());
  const double* clon = corner_lon_deg;
  const double* clat = corner_lat_deg;
  double* res = area.data();
  std::int64_t* cnt = count.data();
#pragma omp parallel default(none) shared(bathy, ri, clon, clat, res, cnt, ni, nj, nci, applied)
  {
    std::vector<double> values;
#pragma omp for schedule(static)
    for (int j = 0; j < nj; ++j) {
      for (int i = 0; i < ni; ++i) {
        std::array<double, 4> x{}, y{};
        const std::size_t at[4] = {static_cast<std::size_t>(j) * nci + static_cast<std::size_t>(i),
                                   static_cast<std::size_t>(j) * nci + static_cast<std::size_t>(i) + 1,
                                   static_cast<std::size_t>(j + 1) * nci + static_cast<std::size_t>(i) + 1,
                                   static_cast<std::size_t>(j + 1) * nci + static_cast<std::size_t>(i)};
        for (int k = 0; k < 4; ++k) {
          x[static_cast<std::size_t>(k)] = clon[at[k]];
          y[static_cast<std::size_t>(k)] = clat[at[k]];
        }
        const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
        const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
        const auto c0 = static_cast<std::int64_t>(std::ceil((*xmin - ri.lon_first) / ri.dlon));
        const auto c1 = static_cast<std::int64_t>(std::floor((*xmax - ri.lon_first) / ri.dlon));
        const auto r0 = static_cast<std::int64_t>(std::ceil((*ymin - ri.lat_first) / ri.dlat));
        const auto r1 = static_cast<std::int64_t>(std::floor((*ymax - ri.lat_first) / ri.dlat));
        values.clear();
        for (std::int64_t r = r0; r <= r1; ++r) {
          const double py = ri.lat_first + static_cast<double>(r) * ri.dlat;
          for (std::int64_t c = c0; c <= c1; ++c) {
            const double px = ri.lon_first + static_cast<double>(c) * ri.dlon;
            if (!inside_quad(x, y, px, py)) continue;
            const float v = bathy.value(c, r);
            if (!std::isnan(v)) values.push_back(static_cast<double>(v));
          }
        }
        const std::size_t cell =
            static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
        cnt[cell] = static_cast<std::int64_t>(values.size());
        if (!values.empty()) res[cell] = statistic_of(values, applied);
      }
    }
  }

  std::vector<std::int64_t> sorted = count;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(ncell / 2), sorted.end());
  out.median_points_per_cell = static_cast<double>(sorted[ncell / 2]);
  if (statistic == CellStatistic::kAuto && out.median_points_per_cell < 4.0) {
    out.used = CellStatistic::kPoint;
    return out;
  }
  out.used = applied;
  for (std::size_t k = 0; k < ncell; ++k) {
    if (count[k] > 0) {
      out.elevation_m[k] = area[k];
    } else {
      ++out.point_cells;
    }
  }
  return out;
}

}  // namespace aq::mask

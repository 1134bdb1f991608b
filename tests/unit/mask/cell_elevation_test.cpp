// SPDX-License-Identifier: GPL-3.0-or-later
// Cell statistics of a fine raster (mask/cell_elevation.hpp) on synthetic rasters whose answers
// are known: a linear field (mean = value at the centre), a checkerboard (mean, median, min), the
// half-open edge rule (each raster point in exactly one cell) and the auto rule.
#include "mask/cell_elevation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"

namespace aq::mask::unit_mask_cell_elevation_test {
namespace {

// A raster of n × n points at (c·d, r·d) with values f(c, r).
template <class F>
raster::Bathymetry make_raster(int n, double d, F f) {
  std::vector<float> v(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) v[static_cast<std::size_t>(r) * n + c] = static_cast<float>(f(c, r));
  return raster::Bathymetry::from_grid(std::move(v), n, n, 0.0, 0.0, d, d);
}

// ni × nj axis-aligned cells of side `side` from (x0, y0).
struct Cells {
  int ni, nj;
  std::vector<double> lon, lat, point;
};
Cells make_cells(int ni, int nj, double x0, double y0, double side) {
  Cells c{ni, nj, {}, {}, std::vector<double>(static_cast<std::size_t>(ni) * nj, 12345.0)};
  for (int b = 0; b <= nj; ++b)
    for (int a = 0; a <= ni; ++a) {
      c.lon.push_back(x0 + a * side);
      c.lat.push_back(y0 + b * side);
    }
  return c;
}

CellElevations run(const raster::Bathymetry& r, const Cells& c, CellStatistic s) {
  return cell_elevations(r, c.lon.data(), c.lat.data(), c.ni, c.nj, c.point.data(), s);
}

TEST(CellElevation, LinearFieldMeanIsTheCentreValue) {
  const double d = 1.0 / 64.0;
  const auto field = [](double lon, double lat) { return -1000.0 + 37.0 * lon - 21.0 * lat; };
  const auto r = make_raster(200, d, [&](int c, int rr) { return field(c * d, rr * d); });
  // Cells of 10 raster spacings whose edges fall half-way between raster points: 10 × 10 points
  // symmetric about the centre.
  const Cells cells = make_cells(5, 4, 0.5 * d + 7 * d, 0.5 * d + 3 * d, 10 * d);
  const auto e = run(r, cells, CellStatistic::kMean);
  EXPECT_EQ(e.used, CellStatistic::kMean);
  EXPECT_EQ(e.median_points_per_cell, 100.0);
  EXPECT_EQ(e.point_cells, 0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) {
      const double cx = 7.5 * d + (i + 0.5) * 10 * d, cy = 3.5 * d + (j + 0.5) * 10 * d;
      EXPECT_NEAR(e.elevation_m[static_cast<std::size_t>(j * 5 + i)], field(cx, cy), 1e-3) << i << "," << j;
    }
}

TEST(CellElevation, CheckerboardMeanMedianMin) {
  const double d = 1.0 / 64.0;
  const auto r = make_raster(100, d, [](int c, int rr) { return (c + rr) % 2 == 0 ? -200.0 : -100.0; });
  const Cells cells = make_cells(3, 3, 10.5 * d, 20.5 * d, 6 * d);  // 36 points: 18 of each
  const auto mean = run(r, cells, CellStatistic::kMean);
  const auto median = run(r, cells, CellStatistic::kMedian);
  const auto min = run(r, cells, CellStatistic::kMin);
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_DOUBLE_EQ(mean.elevation_m[k], -150.0);
    EXPECT_DOUBLE_EQ(median.elevation_m[k], -150.0);  // mean of the two middle values
    EXPECT_DOUBLE_EQ(min.elevation_m[k], -200.0);
  }
  // An odd count (5 × 5 = 25 points, 13 of one colour): the median is the majority colour.
  const Cells odd = make_cells(1, 1, 10.5 * d, 20.5 * d, 5 * d);
  const auto m5 = run(r, odd, CellStatistic::kMedian);
  EXPECT_DOUBLE_EQ(m5.elevation_m[0], (11 + 21) % 2 == 0 ? -200.0 : -100.0);
  EXPECT_NEAR(run(r, odd, CellStatistic::kMean).elevation_m[0], (13 * -200.0 + 12 * -100.0) / 25.0, 1e-9);
}

TEST(CellElevation, PointsOnSharedEdgesCountOnce) {
  // Corners exactly on raster points (spacing 1/64, cell side 1/8): every point is in one cell.
  const double d = 1.0 / 64.0;
  const auto r = make_raster(100, d, [](int c, int rr) { return -(c + 100.0 * rr); });
  const Cells cells = make_cells(4, 4, 8 * d, 8 * d, 8 * d);
  const auto e = run(r, cells, CellStatistic::kMean);
  EXPECT_EQ(e.median_points_per_cell, 64.0);  // 8 × 8, not 9 × 9
  // The mean of cell (0, 0) is that of its half-open 8 × 8 block of points.
  double sum = 0.0;
  for (int rr = 0; rr < 8; ++rr)
    for (int c = 0; c < 8; ++c) sum += -((8 + c) + 100.0 * (8 + rr));
  EXPECT_NEAR(e.elevation_m[0], sum / 64.0, 1e-9);
}

TEST(CellElevation, AutoIsMeanOnlyWhenTheRasterIsFiner) {
  const double d = 1.0 / 64.0;
  const auto r = make_raster(100, d, [](int c, int) { return -10.0 * c; });
  const Cells fine = make_cells(3, 3, 10.5 * d, 10.5 * d, 4 * d);    // 16 points per cell
  const Cells coarse = make_cells(3, 3, 10.5 * d, 10.5 * d, 1 * d);  // 1 point per cell
  const auto a = run(r, fine, CellStatistic::kAuto);
  EXPECT_EQ(a.used, CellStatistic::kMean);
  EXPECT_NE(a.elevation_m[0], 12345.0);
  const auto b = run(r, coarse, CellStatistic::kAuto);
  EXPECT_EQ(b.used, CellStatistic::kPoint);
  EXPECT_EQ(b.elevation_m, coarse.point);
  const auto p = run(r, fine, CellStatistic::kPoint);
  EXPECT_EQ(p.elevation_m, fine.point);
  // A cell smaller than the raster spacing with an explicit statistic keeps the point sample.
  const Cells tiny = make_cells(1, 1, 10.2 * d, 10.2 * d, 0.5 * d);
  const auto t = run(r, tiny, CellStatistic::kMean);
  EXPECT_EQ(t.point_cells, 1);
  EXPECT_EQ(t.elevation_m[0], 12345.0);
}

}  // namespace
}  // namespace aq::mask::unit_mask_cell_elevation_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Value bounds of a raster under a geographic box: every bilinear sample in the box lies within
// them, a box that may sample no-data says so, and the threshold decision follows.
#include "raster/value_bounds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace aq::raster::unit_raster_value_bounds_test {
namespace {

// A 1° global grid-registered raster: λ = -180 + c, φ = -90 + r; a no-data patch at 10..12°E,
// 40..42°N.
Bathymetry global_1deg(Interpolation interp = Interpolation::kBilinear) {
  const std::int64_t nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c) {
      const double lon = -180.0 + static_cast<double>(c), lat = -90.0 + static_cast<double>(r);
      float x = static_cast<float>(3000.0 * std::sin(0.05 * lon) * std::cos(0.07 * lat) - 100.0 * std::cos(0.3 * lon));
      if (interp == Interpolation::kBilinear && lon >= 10.0 && lon <= 12.0 && lat >= 40.0 && lat <= 42.0)
        x = std::nanf("");
      v[static_cast<std::size_t>(r * nc + c)] = x;
    }
  return Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, 1.0, 1.0, interp);
}

TEST(ValueBounds, HoldEverySampleInTheBoxAndFlagNoData) {
  const Bathymetry b = global_1deg();
  for (const std::int64_t block : {1, 4, 32}) {
    const ValueBounds vb(b, block);
    ASSERT_TRUE(vb.available());
    std::mt19937_64 rng(7);
    // Small boxes read the finest blocks, large ones (up to 80°) the coarser levels of the pyramid.
    std::uniform_real_distribution<double> ulon(-400.0, 400.0), ulat(-95.0, 95.0), usize(0.0, 6.0), ularge(0.0, 80.0);
    for (int k = 0; k < 600; ++k) {
      const bool large = k % 3 == 2;
      const double lon0 = ulon(rng), lat0 = ulat(rng), w = large ? ularge(rng) : usize(rng),
                   h = large ? ularge(rng) : usize(rng);
      const ValueRange r = vb.in_box(lon0, lon0 + w, lat0, lat0 + h);
      bool saw_nan = false;
      const int steps = large ? 80 : 12;
      for (int a = 0; a <= steps; ++a)
        for (int c = 0; c <= steps; ++c) {
          const double x = b.sample(lon0 + w * a / steps, std::clamp(lat0 + h * c / steps, -90.0, 90.0));
          if (std::isnan(x)) {
            saw_nan = true;
            continue;
          }
          ASSERT_TRUE(r.any_finite);
          EXPECT_GE(x, r.lo - 1e-9) << lon0 << " " << lat0;
          EXPECT_LE(x, r.hi + 1e-9) << lon0 << " " << lat0;
        }
      if (saw_nan) {
        EXPECT_TRUE(r.nan) << lon0 << " " << lat0;
      }
    }
  }
  // A box over the no-data patch, one across the seam, and one well inside.
  const ValueBounds vb(b, 8);
  EXPECT_TRUE(vb.in_box(10.5, 11.5, 40.5, 41.5).nan);
  const ValueRange seam = vb.in_box(179.2, 180.8, 0.0, 1.0);  // λ 179.2..-179.2
  EXPECT_LE(seam.lo, b.sample(-179.5, 0.5));
  EXPECT_GE(seam.hi, b.sample(179.5, 0.5));
  // Tight: within the values of the blocks around the box (8-cell blocks, one cell of margin),
  // not the whole raster's range.
  const ValueRange inner = vb.in_box(-60.0, -59.0, 10.0, 11.0);
  EXPECT_FALSE(inner.nan);
  double lo = 1e30, hi = -1e30;
  for (std::int64_t r = 96; r < 112; ++r)       // φ 6..21: rows of the blocks 96..103, 104..111
    for (std::int64_t c = 112; c < 128; ++c) {  // λ -68..-53: columns of the blocks 112..119, 120..127
      lo = std::min(lo, static_cast<double>(b.value(c, r)));
      hi = std::max(hi, static_cast<double>(b.value(c, r)));
    }
  EXPECT_GE(inner.lo, lo);
  EXPECT_LE(inner.hi, hi);
  EXPECT_LT(inner.hi - inner.lo, 0.5 * (b.info().max_m - b.info().min_m));
}

// The pyramid: a small box is bounded by the finest blocks around it, a large one by coarser
// blocks (fewer than kMaxBlocksPerQuery reads), still holding every value under it.
TEST(ValueBounds, SmallBoxesUseTheFinestBlocks) {
  const Bathymetry b = global_1deg();
  const ValueBounds vb(b, 2);
  EXPECT_GT(vb.bytes(), 0);
  // Box λ -60..-59.5, φ 10..10.5: cells c 120..121, r 100..100, one more before and two after:
  // c 119..123, r 99..102; with 2-cell blocks that is c 118..123, r 98..103.
  const ValueRange small = vb.in_box(-60.0, -59.5, 10.0, 10.5);
  double lo = 1e30, hi = -1e30;
  for (std::int64_t r = 98; r <= 103; ++r)
    for (std::int64_t c = 118; c <= 123; ++c) {
      lo = std::min(lo, static_cast<double>(b.value(c, r)));
      hi = std::max(hi, static_cast<double>(b.value(c, r)));
    }
  EXPECT_DOUBLE_EQ(small.lo, lo);
  EXPECT_DOUBLE_EQ(small.hi, hi);
  // A 40° box: conservative over its own cells.
  const ValueRange large = vb.in_box(-100.0, -60.0, -20.0, 20.0);
  for (std::int64_t r = 70; r <= 110; ++r)
    for (std::int64_t c = 80; c <= 120; ++c) {
      EXPECT_LE(large.lo, b.value(c, r));
      EXPECT_GE(large.hi, b.value(c, r));
    }
}

TEST(ValueBounds, SideOfThreshold) {
  ValueRange r;
  r.any_finite = true;
  r.lo = -50.0;
  r.hi = -10.0;
  EXPECT_EQ(side_of_threshold(r, 0.0), 1);     // all wet
  EXPECT_EQ(side_of_threshold(r, -10.0), 0);   // a value at the threshold: undecided (margin)
  EXPECT_EQ(side_of_threshold(r, -60.0), -1);  // all dry
  r.nan = true;
  EXPECT_EQ(side_of_threshold(r, 0.0), 0);     // a NaN sample is dry: not all wet
  EXPECT_EQ(side_of_threshold(r, -60.0), -1);  // NaN or above: all dry
  r.any_finite = false;
  EXPECT_EQ(side_of_threshold(r, 0.0), -1);  // nothing but no-data
}

TEST(ValueBounds, NotAvailableForBicubicSampling) {
  const ValueBounds vb(global_1deg(Interpolation::kBicubic));
  EXPECT_FALSE(vb.available());
  EXPECT_EQ(side_of_threshold(vb.in_box(0.0, 1.0, 0.0, 1.0), 1e9), 0);
}

}  // namespace
}  // namespace aq::raster::unit_raster_value_bounds_test

// SPDX-License-Identifier: GPL-3.0-or-later
// RotatedMapSampler: on rasters whose values are their own column or row index, a sample *is*
// the raster position it was taken at, so the interpolated map can be checked against the exact
// one position by position: within kMaxError on the ground on a rotated Mercator map from pole
// to pole; the same values whichever rows a call samples; bicubic rasters sampled exactly; the
// edge of a regional raster left to the exact path.
#include "pictures/rotated_map_sampler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/lattice.hpp"
#include "core/types.hpp"

namespace aq::io::unit_pictures_rotated_map_sampler_test {
namespace {

constexpr double kStep = 1.0 / 6.0;  // raster spacing, degrees (10')
constexpr std::int64_t kCols = 2160, kRows = 1081;

// A global raster (λ from -180, φ from -90) whose value at column c, row r is value(c, r).
template <typename Fn>
raster::Bathymetry index_raster(Fn value, raster::Interpolation interp = raster::Interpolation::kBilinear) {
  std::vector<float> v(static_cast<std::size_t>(kCols * kRows));
  for (std::int64_t r = 0; r < kRows; ++r)
    for (std::int64_t c = 0; c < kCols; ++c) v[static_cast<std::size_t>(r * kCols + c)] = value(c, r);
  return raster::Bathymetry::from_grid(std::move(v), kCols, kRows, -180.0, -90.0, kStep, kStep, interp);
}

// A Mercator map of the rotated frame with its North pole in Greenland (the global_mercator run),
// rows to |φ'| = 86.5°, as the preview draws it.
// 0.3° pixels on the 10' raster (the ETOPO5 run: 0.15° on 5').
struct Map {
  int width = 1200, height = 1333;
  double y_max = std::log(std::tan(kPi / 4.0 + 86.5 * kDegToRad / 2.0)) * kRadToDeg;
  [[nodiscard]] double rlon(double x) const { return -180.0 + (x + 0.5) * 360.0 / width; }
  [[nodiscard]] double rlat(double y) const { return mercator_lat_deg(y_max - (y + 0.5) * 2.0 * y_max / height); }
};

RotatedMapSampler sampler(const raster::Bathymetry& bathy, const Map& m = Map(),
                          const PoleRotation& rotation = PoleRotation(-44.858333, 78.141667)) {
  return RotatedMapSampler(
      bathy, rotation, m.width, m.height, [m](double x) { return m.rlon(x); }, [m](double y) { return m.rlat(y); });
}

std::vector<float> all_rows(const RotatedMapSampler& s, bool exact) {
  std::vector<float> out(static_cast<std::size_t>(s.width()) * static_cast<std::size_t>(s.height()));
  exact ? s.sample_rows_exact(0, s.height(), out.data()) : s.sample_rows(0, s.height(), out.data());
  return out;
}

TEST(RotatedMapSampler, InterpolatedPositionsAreWithinTheBoundOnTheGround) {
  const auto columns = index_raster([](std::int64_t c, std::int64_t) { return static_cast<float>(c); });
  const auto rows = index_raster([](std::int64_t, std::int64_t r) { return static_cast<float>(r); });
  const auto sc = sampler(columns), sr = sampler(rows);
  const auto fc = all_rows(sc, false), ec = all_rows(sc, true), fr = all_rows(sr, false), er = all_rows(sr, true);
  const Map m;
  const PoleRotation rotation(-44.858333, 78.141667);
  double worst_col = 0.0, worst_row = 0.0;
  std::size_t interpolated = 0, near_seam = 0, near_seam_interpolated = 0;
  for (std::size_t k = 0; k < fc.size(); ++k) {
    ASSERT_TRUE(std::isfinite(ec[k]) && std::isfinite(er[k])) << k;
    // Samples are positions, except next to the seam column, where the column raster jumps
    // from its last to its first.
    double lon = 0, lat = 0;
    rotation.to_geographic(m.rlon(static_cast<double>(k % static_cast<std::size_t>(m.width))),
                           m.rlat(static_cast<double>(k / static_cast<std::size_t>(m.width))), lon, lat);
    const double col = (lon + 180.0) / kStep;
    if (col > 2.0 && col < kCols - 3.0) {
      worst_col = std::max(worst_col, std::abs(fc[k] - ec[k]) * std::cos(lat * kDegToRad));
    } else if (std::abs(lat) < 60.0) {
      ++near_seam;
      if (fr[k] != er[k]) ++near_seam_interpolated;
    }
    worst_row = std::max(worst_row, static_cast<double>(std::abs(fr[k] - er[k])));
    if (fr[k] != er[k]) ++interpolated;
  }
  // Float samples of positions up to 2160 carry 1e-4 of rounding.
  EXPECT_LE(worst_col, RotatedMapSampler::kMaxError + 2e-4);
  EXPECT_LE(worst_row, RotatedMapSampler::kMaxError + 2e-4);
  EXPECT_GT(worst_row, 0.1 * RotatedMapSampler::kMaxError);  // the check is not vacuous
  // Most of the map is interpolated (0.6 here; 0.99 on the ETOPO5 run, whose cells span half
  // the degrees, so a quarter of the curvature).
  EXPECT_GE(static_cast<double>(interpolated), 0.5 * static_cast<double>(fc.size()));
  // The raster's seam (λ = ±180°, where atan2 jumps) is no reason to leave the interpolation
  // (0.43 of the pixels there; 0.01 when the columns are not unwrapped across it).
  EXPECT_GT(near_seam, 500u);
  EXPECT_GE(static_cast<double>(near_seam_interpolated), 0.25 * static_cast<double>(near_seam));
}

TEST(RotatedMapSampler, TheSameValuesWhicheverRowsACallSamples) {
  const auto bathy = index_raster([](std::int64_t c, std::int64_t r) {
    return static_cast<float>(3000.0 * std::sin(0.05 * static_cast<double>(c)) *
                              std::cos(0.07 * static_cast<double>(r)));
  });
  const auto s = sampler(bathy);
  const auto whole = all_rows(s, false);
  std::vector<float> part(whole.size());
  // Bands of 32 rows, then of odd sizes that split tiles and cells.
  for (const int band : {32, 13, 1}) {
    for (int y0 = 0; y0 < s.height(); y0 += band) {
      const int n = std::min(band, s.height() - y0);
      s.sample_rows(y0, n, part.data() + static_cast<std::size_t>(y0) * static_cast<std::size_t>(s.width()));
    }
    EXPECT_EQ(std::memcmp(part.data(), whole.data(), whole.size() * sizeof(float)), 0) << "bands of " << band;
  }
}

TEST(RotatedMapSampler, BicubicRastersAreSampledExactly) {
  const auto bathy = index_raster(
      [](std::int64_t c, std::int64_t r) {
        return static_cast<float>(100.0 * std::sin(0.1 * static_cast<double>(c)) + static_cast<double>(r));
      },
      raster::Interpolation::kBicubic);
  ASSERT_FALSE(bathy.samples_bilinear());
  const auto s = sampler(bathy);
  const auto fast = all_rows(s, false), exact = all_rows(s, true);
  EXPECT_EQ(std::memcmp(fast.data(), exact.data(), fast.size() * sizeof(float)), 0);
}

// A regional raster (λ -60..60, φ -40..60, 0.25°): outside it both paths give NaN, and the cells whose
// block would reach past its edges are exact.
TEST(RotatedMapSampler, ARegionalRastersEdgesAreLeftToTheExactPath) {
  const std::int64_t nc = 481, nr = 401;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c) v[static_cast<std::size_t>(r * nc + c)] = static_cast<float>(r);
  const auto bathy = raster::Bathymetry::from_grid(std::move(v), nc, nr, -60.0, -40.0, 0.25, 0.25);
  ASSERT_FALSE(bathy.info().global_lon);
  const auto s = sampler(bathy, Map(), PoleRotation(20.0, 60.0));
  const auto fast = all_rows(s, false), exact = all_rows(s, true);
  std::size_t inside = 0;
  for (std::size_t k = 0; k < fast.size(); ++k) {
    ASSERT_EQ(std::isnan(fast[k]), std::isnan(exact[k])) << k;
    if (std::isnan(exact[k])) continue;
    ++inside;
    EXPECT_LE(std::abs(fast[k] - exact[k]), RotatedMapSampler::kMaxError + 1e-4) << k;
  }
  EXPECT_GT(inside, fast.size() / 10);
  EXPECT_LT(inside, fast.size() * 9 / 10);
}

}  // namespace
}  // namespace aq::io::unit_pictures_rotated_map_sampler_test

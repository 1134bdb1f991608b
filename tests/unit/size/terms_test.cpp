// SPDX-License-Identifier: GPL-3.0-or-later
// Each term of the size field against a synthetic grid with a known answer: constant depth gives
// a constant wavelength size; a linear slope gives H/|∇H|; a straight coast gives h0 + α·d; a
// straight channel of width W gives W/R across it (2·(d_MA + d)/R with d = W/2 on the axis); the
// Rossby-radius box filter gives the analytic ramp across a step; the CFL bound its formula.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/types.hpp"
#include "size/terms.hpp"

namespace aq::size::unit_size_terms_test {
namespace {

// 0.5° cells: 720 x 360 (lon-lat lattice, Δ0 = 4°, L = 3).
FieldGrid grid() { return FieldGrid(Lattice::make(4.0, 3, -180.0), 3); }

TEST(Terms, WavelengthOfConstantDepthIsConstant) {
  const std::vector<double> depth(100, 4000.0);
  const std::vector<double> h = wavelength_term(depth, 12.42, 30.0);
  const double expected = 12.42 * 3600.0 * std::sqrt(9.81 * 4000.0) / 30.0 / 1000.0;  // 295.6 km
  for (const double x : h) EXPECT_DOUBLE_EQ(x, expected);
  EXPECT_NEAR(expected, 295.2, 0.1);
  EXPECT_FALSE(std::isfinite(wavelength_term({std::nan("")}, 12.42, 30.0)[0]));
}

TEST(Terms, LinearSlopeGivesDepthOverGradient) {
  const FieldGrid g = grid();
  const double k = 0.2, factor = 2.0 * std::numbers::pi / 10.0;  // m per km
  // Northward: rows 0.5° apart, H/|∇H| exact for central differences.
  std::vector<double> north(static_cast<std::size_t>(g.cells())), east(north.size());
  const double dx_eq = g.dx_km(180);
  for (std::int64_t j = 0; j < g.ny(); ++j)
    for (std::int64_t i = 0; i < g.nx(); ++i) {
      north[static_cast<std::size_t>(g.index(i, j))] = 3000.0 + k * g.dy_km(j) * static_cast<double>(j - 180);
      east[static_cast<std::size_t>(g.index(i, j))] = 3000.0 + k * dx_eq * static_cast<double>(i - 360);
    }
  const std::vector<double> hn = slope_term(g, north, 10.0), he = slope_term(g, east, 10.0);
  for (const std::int64_t j : {100, 180, 250}) {
    for (const std::int64_t i : {300, 360, 400}) {
      const auto at = static_cast<std::size_t>(g.index(i, j));
      EXPECT_NEAR(hn[at], factor * north[at] / k, 1e-6 * hn[at]) << i << " " << j;
      // Eastward the columns are dx(j) = dx_eq·cos φ apart: |∇H| = k·dx_eq/dx(j).
      EXPECT_NEAR(he[at], factor * east[at] / (k * dx_eq / g.dx_km(j)), 1e-6 * he[at]) << i << " " << j;
    }
  }
}

TEST(Terms, CoastDistanceFromAStraightCoast) {
  const FieldGrid g = grid();
  std::vector<std::uint8_t> coast(static_cast<std::size_t>(g.cells()), 0);
  for (std::int64_t j = 0; j < 180; ++j)
    for (std::int64_t i = 0; i < g.nx(); ++i) coast[static_cast<std::size_t>(g.index(i, j))] = 1;  // land south of the equator
  const std::vector<double> h = coast_term(g, coast, 5.0, 0.15);
  const double row_km = 0.5 * kDegToRad * kEarthRadiusKm;
  for (const std::int64_t n : {1, 5, 40})
    EXPECT_NEAR(h[static_cast<std::size_t>(g.index(123, 179 + n))], 5.0 + 0.15 * row_km * static_cast<double>(n), 1e-6);
  EXPECT_DOUBLE_EQ(h[static_cast<std::size_t>(g.index(5, 10))], 5.0);
}

TEST(Terms, FeatureSizeOfAStraightChannel) {
  const FieldGrid g = grid();
  // Water in rows 170..189 (20 cells, W = 20 · 55.6 km = 1112 km between the banks' edges).
  std::vector<std::uint8_t> coast(static_cast<std::size_t>(g.cells()), 1), water(coast.size(), 0);
  for (std::int64_t j = 170; j < 190; ++j)
    for (std::int64_t i = 0; i < g.nx(); ++i) {
      coast[static_cast<std::size_t>(g.index(i, j))] = 0;
      water[static_cast<std::size_t>(g.index(i, j))] = 1;
    }
  const double cell = 0.5 * kDegToRad * kEarthRadiusKm, w = 20.0 * cell, r = 3.0;
  const std::vector<double> h = feature_term(g, coast, water, r);
  // Distances run between cell centres: d_MA + d is within a cell of W/2.
  for (const std::int64_t j : {170, 175, 179, 180, 189})
    EXPECT_NEAR(h[static_cast<std::size_t>(g.index(77, j))], w / r, 2.0 * cell / r) << j;
  // An open basin (no opposite bank within reach): no medial axis along a single coast.
  std::vector<std::uint8_t> half(coast.size(), 0), wet(coast.size(), 1);
  for (std::int64_t i = 0; i < g.nx(); ++i) half[static_cast<std::size_t>(g.index(i, 0))] = 1;
  const std::vector<double> open = feature_term(g, half, wet, r);
  EXPECT_FALSE(std::isfinite(open[static_cast<std::size_t>(g.index(10, 5))]));
}

TEST(Terms, BoxFilterOfAStepIsTheAnalyticRamp) {
  const FieldGrid g = grid();
  std::vector<double> v(static_cast<std::size_t>(g.cells()));
  for (std::int64_t j = 0; j < g.ny(); ++j)
    for (std::int64_t i = 0; i < g.nx(); ++i) v[static_cast<std::size_t>(g.index(i, j))] = i < 360 ? 1000.0 : 3000.0;
  const std::int64_t j = 180, r = 4;  // half-width 4 cells along the row at the equator
  std::vector<double> radius(v.size(), static_cast<double>(r) * g.dx_km(j));
  const std::vector<double> m = box_mean(g, v, radius);
  for (std::int64_t i = 350; i < 370; ++i) {
    const std::int64_t high = std::clamp<std::int64_t>(i + r - 359, 0, 2 * r + 1);  // cells >= 360 in [i-r, i+r]
    const double expected = (1000.0 * static_cast<double>(2 * r + 1 - high) + 3000.0 * static_cast<double>(high)) /
                            static_cast<double>(2 * r + 1);
    EXPECT_NEAR(m[static_cast<std::size_t>(g.index(i, j))], expected, 1e-9) << i;
  }
}

TEST(Terms, RossbyFilterHalfWidthFollowsTheRossbyRadius) {
  const FieldGrid g = grid();
  // A step in H; f at 30° N; half-width = 0.1 · √(gH)/f: 2 cells on the 1000 m side, 5 on the 4000 m side.
  std::vector<double> depth(static_cast<std::size_t>(g.cells())), geo(depth.size(), 30.0);
  for (std::int64_t j = 0; j < g.ny(); ++j)
    for (std::int64_t i = 0; i < g.nx(); ++i) depth[static_cast<std::size_t>(g.index(i, j))] = i < 360 ? 1000.0 : 4000.0;
  const double f = 2.0 * kEarthOmega * std::sin(30.0 * kDegToRad);
  const std::int64_t j = 180;
  const std::vector<double> m = rossby_filter(g, depth, geo, 0.1, 1e9);
  for (std::int64_t i = 345; i < 375; ++i) {
    const double h = i < 360 ? 1000.0 : 4000.0;
    const auto r = static_cast<std::int64_t>(std::floor(0.1 * std::sqrt(9.81 * h) / f / 1000.0 / g.dx_km(j) + 0.5));
    const std::int64_t high = std::clamp<std::int64_t>(i + r - 359, 0, 2 * r + 1);
    const double expected = (1000.0 * static_cast<double>(2 * r + 1 - high) + 4000.0 * static_cast<double>(high)) /
                            static_cast<double>(2 * r + 1);
    EXPECT_NEAR(m[static_cast<std::size_t>(g.index(i, j))], expected, 1e-9) << i << " r=" << r;
  }
  EXPECT_EQ(rossby_filter(g, depth, geo, 0.0, 1e9), depth);
}

TEST(Terms, CflBound) {
  const std::vector<double> h = cfl_bound({100.0, 4000.0}, 120.0, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(h[0], (std::sqrt(9.81 * 100.0) + 1.0) * 120.0 / 0.5 / 1000.0);
  EXPECT_DOUBLE_EQ(h[1], (std::sqrt(9.81 * 4000.0) + 1.0) * 120.0 / 0.5 / 1000.0);
}

}  // namespace
}  // namespace aq::size::unit_size_terms_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The Mercator lattice (issue 12): the row map round trips, a pixel is a square on the sphere to
// second order in its size, the rows end at whole level-0 squares beyond φ_max, and the lon-lat
// lattice keeps its exact row formula.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "core/error.hpp"
#include "core/lattice.hpp"
#include "core/types.hpp"

namespace unit_core_mercator_lattice_test {

namespace {

using aq::Lattice;

std::array<double, 3> unit(double lon_deg, double lat_deg) {
  const double lo = lon_deg * aq::kDegToRad, la = lat_deg * aq::kDegToRad;
  return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
}
// Great-circle angle (radians) between unit vectors.
double arc(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const std::array<double, 3> c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

TEST(MercatorLattice, RowsEndAtWholeLevel0SquaresBeyondTheLatitudeLimit) {
  const Lattice m = Lattice::make_mercator(4.0, 3, -180.0, 85.0);
  EXPECT_TRUE(m.mercator());
  EXPECT_EQ(m.nx, 720);
  EXPECT_EQ(m.ny, 720);  // y = ±180°: 45 level-0 squares per hemisphere, φ = ±85.0511°
  EXPECT_DOUBLE_EQ(m.y0_deg, -180.0);
  EXPECT_NEAR(m.lat_max_deg(), 85.0511287798, 1e-9);
  EXPECT_NEAR(m.lat_of(0), -m.lat_max_deg(), 1e-12);
  EXPECT_EQ(m.lat_of(m.ny / 2), 0.0);
  const Lattice d = Lattice::make_mercator(4.0, 3, -180.0, 86.5);
  EXPECT_GE(d.lat_max_deg(), 86.5);
  EXPECT_LT(Lattice::make_mercator(4.0, 3, -180.0, 86.5 - 1e-6).ny, d.ny + 1);
  EXPECT_EQ((d.ny >> d.levels) % 2, 0);  // whole level-0 squares, symmetric about the equator
  EXPECT_LT(aq::mercator_y_deg(d.lat_max_deg()) - aq::mercator_y_deg(86.5), d.step0_deg);
  EXPECT_THROW((void)Lattice::make_mercator(4.0, 3, -180.0, 90.0), aq::InternalError);
  EXPECT_THROW((void)Lattice::make_mercator(3.7, 3, -180.0, 80.0), aq::InternalError);
}

TEST(MercatorLattice, RowMapRoundTrips) {
  const Lattice m = Lattice::make_mercator(1.0, 4, -180.0, 86.5);
  for (double y = 0.0; y <= static_cast<double>(m.ny); y += 0.37) {
    const double lat = m.lat_of_row(y);
    ASSERT_LT(std::fabs(lat), 86.6);
    EXPECT_NEAR(m.row_of_lat(lat), y, 1e-8) << y;
    EXPECT_NEAR(aq::mercator_lat_deg(aq::mercator_y_deg(lat)), lat, 1e-12);
    EXPECT_NEAR(m.plane_y(y), aq::mercator_y_deg(lat), 1e-9);
  }
  // Rows are monotone and symmetric.
  for (std::int64_t j = 0; j < m.ny; ++j) {
    ASSERT_LT(m.lat_of(j), m.lat_of(j + 1));
    ASSERT_NEAR(m.lat_of(j), -m.lat_of(m.ny - j), 1e-12);
  }
}

// Sides and diagonals of pixel (i, j) on the unit sphere: a square has equal sides and diagonals
// √2 times a side. The Mercator pixel is square to O(Δ²) relative (its scale cos φ varies across
// it by O(Δ)·tan φ, symmetric to first order); the lon-lat pixel is cos φ : 1.
struct PixelShape {
  double side_ratio = 0.0;      ///< (E–W side at mid-row) / (N–S side)
  double diagonal_ratio = 0.0;  ///< one diagonal / the other
};
PixelShape shape(const Lattice& l, std::int64_t i, std::int64_t j) {
  const auto p = [&](double x, double y) { return unit(l.lon0_deg + x * l.pixel_deg(), l.lat_of_row(y)); };
  const double x = static_cast<double>(i), y = static_cast<double>(j);
  const double ew = arc(p(x, y + 0.5), p(x + 1, y + 0.5));
  const double ns = arc(p(x + 0.5, y), p(x + 0.5, y + 1));
  return {ew / ns, arc(p(x, y), p(x + 1, y + 1)) / arc(p(x + 1, y), p(x, y + 1))};
}

TEST(MercatorLattice, APixelIsASquareOnTheSphereToSecondOrder) {
  for (const double lat : {0.0, 30.0, 60.0, 80.0}) {
    double previous = 0.0;
    for (const int levels : {2, 3, 4, 5}) {
      const Lattice m = Lattice::make_mercator(1.0, levels, -180.0, 86.5);
      const auto j = static_cast<std::int64_t>(std::floor(m.row_of_lat(lat)));
      const PixelShape s = shape(m, 7, j);
      const double err = std::fabs(s.side_ratio - 1.0);
      const double delta = m.pixel_deg() * aq::kDegToRad;
      EXPECT_LT(err, 0.5 * delta * delta * (1.0 + std::pow(std::tan(lat * aq::kDegToRad), 2)) + 1e-12)
          << lat << " " << levels;
      EXPECT_NEAR(s.diagonal_ratio, 1.0, 1e-12);  // a pixel is symmetric about its mid-meridian
      if (levels > 2 && previous > 1e-12) {
        EXPECT_LT(err, 0.3 * previous) << lat << " " << levels;  // ~4× per halving
      }
      previous = err;
      // The same pixel of the lon-lat lattice is cos φ : 1.
      const Lattice g = Lattice::make(1.0, levels, -180.0);
      const auto gj = static_cast<std::int64_t>(std::floor(g.row_of_lat(lat)));
      EXPECT_NEAR(shape(g, 7, gj).side_ratio, std::cos(g.lat_of_row(static_cast<double>(gj) + 0.5) * aq::kDegToRad),
                  1e-3);
    }
  }
}

TEST(MercatorLattice, TheLonLatRowFormulaIsUnchanged) {
  const Lattice g = Lattice::make(0.5, 6, -180.0);
  EXPECT_FALSE(g.mercator());
  for (std::int64_t j = 0; j <= g.ny; j += 7) {
    ASSERT_EQ(g.lat_of(j), -90.0 + static_cast<double>(j) * g.pixel_deg());
    ASSERT_EQ(g.plane_y_of(j), g.lat_of(j));
    ASSERT_EQ(g.row_of_lat(g.lat_of(j)), (g.lat_of(j) + 90.0) / g.pixel_deg());
  }
  EXPECT_EQ(g.lat_of(g.ny), 90.0);
}

}  // namespace

}  // namespace unit_core_mercator_lattice_test

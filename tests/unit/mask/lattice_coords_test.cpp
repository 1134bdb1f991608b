// SPDX-License-Identifier: GPL-3.0-or-later
// Named index/coordinate conversions of the mask stage.
#include "mask/lattice_coords.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace aq::mask::unit_mask_lattice_coords_test {
namespace {

TEST(LatticeCoords, PixelAndWindowCentres) {
  const Lattice l = Lattice::make(4.0, 3, -180.0);  // 0.5° pixels
  EXPECT_EQ(pixel_index({3, 2}, l.nx), 2 * 720 + 3);
  const LonLat c = pixel_center_lattice_deg(l, {0, 0});
  EXPECT_DOUBLE_EQ(c.lon_deg, -179.75);
  EXPECT_DOUBLE_EQ(c.lat_deg, -89.75);
  const LonLat w = window_center_lattice_deg(l, {10, 20}, 2);
  EXPECT_DOUBLE_EQ(w.lon_deg, -180.0 + 11 * 0.5);
  EXPECT_DOUBLE_EQ(w.lat_deg, -90.0 + 21 * 0.5);
  double x = 0.0, y = 0.0;
  deg_to_lattice_xy(l, {180.0, 90.0}, x, y);  // λ = 180 is the seam again: x = 0
  EXPECT_DOUBLE_EQ(x, 0.0);
  EXPECT_DOUBLE_EQ(y, 360.0);
  deg_to_lattice_xy(l, {-0.25, 0.25}, x, y);
  EXPECT_DOUBLE_EQ(x, 359.5);
  EXPECT_DOUBLE_EQ(y, 180.5);
  EXPECT_NEAR(angular_distance_deg({0.0, 0.0}, {90.0, 0.0}), 90.0, 1e-12);
  EXPECT_NEAR(angular_distance_deg({10.0, 89.999}, {-170.0, 89.999}), 0.002, 1e-9);
}

TEST(LatticeCoords, RowMapperAgreesWithPoleRotation) {
  const Lattice l = Lattice::make(1.0, 2, -180.0);
  for (const PoleRotation& rot : {PoleRotation(-44.858333, 78.141667), PoleRotation(30.0, -10.0), PoleRotation()}) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> ux(0.0, static_cast<double>(l.nx)), uy(0.0, static_cast<double>(l.ny));
    std::vector<double> xs(500);
    for (double& x : xs) x = ux(rng);
    xs[0] = 0.0;
    const LatticeRowMapper m(l, rot, xs);
    ASSERT_EQ(m.size(), xs.size());
    std::vector<double> lon(xs.size()), lat(xs.size());
    double worst = 0.0;
    for (const double y : {0.0, 1.0, uy(rng), uy(rng), uy(rng), static_cast<double>(l.ny)}) {
      m.map_row(y, lon.data(), lat.data());
      for (std::size_t k = 0; k < xs.size(); ++k) {
        const LonLat ref = lattice_to_geographic(rot, lattice_xy_to_deg(l, xs[k], y));
        worst = std::max(worst, angular_distance_deg(ref, {lon[k], lat[k]}));
        ASSERT_GT(lon[k], -180.0 - 1e-9);
        ASSERT_LE(lon[k], 180.0);
      }
    }
    EXPECT_LT(worst, 1e-10);
  }
}

}  // namespace
}  // namespace aq::mask::unit_mask_lattice_coords_test

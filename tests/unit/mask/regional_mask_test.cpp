// SPDX-License-Identifier: GPL-3.0-or-later
// Regional (ROMS) masks from the global Ω_L: the pixel of a point (edges, seam, poles, rotation,
// beyond the Mercator rows), the wet rule against a drawn filled set with a lake and a sub-pixel
// island, the boundary copy, the ROMS u/v/ψ product rules, and the raster-coverage error.
#include "mask/regional_mask.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "mask_drawing.hpp"

namespace aq::mask::unit_mask_regional_mask_test {
namespace {

// A ROMS-style mask from rows drawn north first ('1' water, anything else land).
std::vector<std::uint8_t> drawn_mask(const std::vector<std::string_view>& rows) {
  const std::size_t nj = rows.size(), ni = rows[0].size();
  std::vector<std::uint8_t> m(ni * nj, 0);
  for (std::size_t r = 0; r < nj; ++r)
    for (std::size_t i = 0; i < ni; ++i) m[(nj - 1 - r) * ni + i] = rows[r][i] == '1' ? 1 : 0;
  return m;
}

TEST(RegionalMask, PixelOfAPointTakesTheEastAndNorthPixelOnEdges) {
  const Lattice lat = Lattice::make(4.0, 0, -180.0);  // 4° pixels, 90 x 45
  const PoleRotation none;
  EXPECT_EQ(pixel_of_point(lat, none, 20.0, 30.0), (PixelIJ{50, 30}));  // a vertex: pixel to its NE
  EXPECT_EQ(pixel_of_point(lat, none, 21.9, 33.9), (PixelIJ{50, 30}));
  EXPECT_EQ(pixel_of_point(lat, none, 19.99, 29.99), (PixelIJ{49, 29}));
  EXPECT_EQ(pixel_of_point(lat, none, 180.0, 0.0), (PixelIJ{0, 22}));  // the seam wraps
  EXPECT_EQ(pixel_of_point(lat, none, 540.0, 0.0), (PixelIJ{0, 22}));
  EXPECT_EQ(pixel_of_point(lat, none, 179.999, 0.0), (PixelIJ{89, 22}));
  EXPECT_EQ(pixel_of_point(lat, none, 10.0, 90.0), (PixelIJ{47, 44}));  // the pole row
  EXPECT_EQ(pixel_of_point(lat, none, 10.0, -90.0), (PixelIJ{47, 0}));
  // With the global run's pole rotation the pixel is found in rotated coordinates.
  const PoleRotation rot(-44.858333, 78.141667);
  for (const auto& [lon, la] : {std::pair{34.5, 43.75}, std::pair{-60.0, -20.0}, std::pair{150.0, 70.0}}) {
    double rl = 0.0, rp = 0.0;
    rot.to_rotated(lon, la, rl, rp);
    const PixelIJ p = pixel_of_point(lat, rot, lon, la);
    EXPECT_EQ(p.i, static_cast<std::int64_t>(std::floor((rl + 180.0) / 4.0)) % 90);
    EXPECT_EQ(p.j, static_cast<std::int64_t>(std::floor((rp + 90.0) / 4.0)));
  }
}

TEST(RegionalMask, PointsBeyondTheMercatorRowsAreInNoPixelOfTheOcean) {
  // Δ0 = 4°, L = 0, rows to ±80.2° (y = ±136°): an ocean everywhere on the rows.
  const Lattice lat = Lattice::make_mercator(4.0, 0, -180.0, 80.0);
  ASSERT_LT(lat.lat_max_deg(), 81.0);
  Bitmap filled(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) filled.set(i, j);
  const std::vector<double> lon{10.0, 10.0, 10.0, 10.0}, la{0.0, 79.0, 83.0, -88.0};
  bool on_rows = false;
  EXPECT_EQ(pixel_of_point(lat, PoleRotation(), 10.0, 83.0, &on_rows), (PixelIJ{47, lat.ny - 1}));  // the nearest row
  EXPECT_FALSE(on_rows);
  (void)pixel_of_point(lat, PoleRotation(), 10.0, 79.0, &on_rows);
  EXPECT_TRUE(on_rows);
  const auto m = rho_mask_from_filled(filled, lat, PoleRotation(), lon.data(), la.data(), nullptr, 0.0, lon.size());
  EXPECT_EQ(m, (std::vector<std::uint8_t>{1, 1, 0, 0}));  // the caps beyond the rows are dry
}

class DrawnBlock : public ::testing::Test {
 protected:
  // ρ points at the centres of the 8 x 6 pixels [50, 58) x [30, 36) of a 4° lattice.
  static constexpr int kNi = 8, kNj = 6;
  void SetUp() override {
    lattice = Lattice::make(4.0, 0, -180.0);
    filled = Bitmap(lattice.nx, lattice.ny);
    // Ω_L in the block; the two '.' inside the ring are a lake (deep, not connected).
    test::paste(filled, test::draw({"........", ".####...", ".######.", ".##..##.", ".######.", "........"}), 50, 30);
    for (int j = 0; j < kNj; ++j)
      for (int i = 0; i < kNi; ++i) {
        lon.push_back(-180.0 + 4.0 * (50 + i) + 2.0);
        lat.push_back(-90.0 + 4.0 * (30 + j) + 2.0);
        elevation.push_back(-100.0);
      }
    elevation[3 * kNi + 5] = 5.0;  // a sub-pixel island inside Ω_L at ρ (5, 3)
  }
  Lattice lattice;
  Bitmap filled;
  std::vector<double> lon, lat, elevation;
};

TEST_F(DrawnBlock, RhoMaskIsFilledAndDeepEnough) {
  RegionalMaskStats s;
  const auto m = rho_mask_from_filled(filled, lattice, PoleRotation(), lon.data(), lat.data(), elevation.data(), 0.0,
                                      lon.size(), &s);
  EXPECT_EQ(m, drawn_mask({"00000000", "01111000",
                           "01111010",  // (5, 3): island, land
                           "01100110",  // (3, 2), (4, 2): the lake stays land
                           "01111110", "00000000"}));
  EXPECT_EQ(s.rho_points, 48);
  EXPECT_EQ(s.in_filled, 20);
  EXPECT_EQ(s.deep_enough, 47);
  EXPECT_EQ(s.lake_points, 28);  // every deep point outside Ω_L, the lake's two among them
  EXPECT_EQ(s.coastal_points, 0);
  EXPECT_EQ(s.shallow_in_filled, 1);
  // Given the global wet pixels (Ω_L plus the lake), only the lake counts as unconnected water;
  // the other deep points lie in pixels with a dry vertex. The mask is the same.
  Bitmap wet = filled;
  wet.set(53, 32);
  wet.set(54, 32);
  RegionalMaskStats s2;
  EXPECT_EQ(rho_mask_from_filled(filled, lattice, PoleRotation(), lon.data(), lat.data(), elevation.data(), 0.0,
                                 lon.size(), &s2, &wet),
            m);
  EXPECT_EQ(s2.lake_points, 2);
  EXPECT_EQ(s2.coastal_points, 26);
  // Without depths only the pixel rule applies; a threshold deeper than the sea dries it.
  const auto pixels_only =
      rho_mask_from_filled(filled, lattice, PoleRotation(), lon.data(), lat.data(), nullptr, 0.0, lon.size());
  EXPECT_EQ(pixels_only[3 * kNi + 5], 1);
  const auto too_deep = rho_mask_from_filled(filled, lattice, PoleRotation(), lon.data(), lat.data(), elevation.data(),
                                             200.0, lon.size());
  for (const auto v : too_deep) EXPECT_EQ(v, 0);
}

TEST_F(DrawnBlock, BoundaryCopiesAndRomsRules) {
  const RomsMasks m =
      build_roms_masks(filled, lattice, PoleRotation(), lon.data(), lat.data(), elevation.data(), 0.0, kNi, kNj);
  EXPECT_EQ(m.rho, drawn_mask({"11111000", "11111000", "11111011", "11100111", "11111111", "11111111"}));
  EXPECT_EQ(m.u, drawn_mask({"1111000", "1111000", "1111001", "1100011", "1111111", "1111111"}));
  EXPECT_EQ(m.v, drawn_mask({"11111000", "11111000", "11100011", "11100111", "11111111"}));
  EXPECT_EQ(m.psi, drawn_mask({"1111000", "1111000", "1100001", "1100011", "1111111"}));
  EXPECT_EQ(m.stats.wet_rho, 39);
  EXPECT_EQ(m.stats.wet_rho_interior, 19);
  EXPECT_EQ(m.stats.boundary_changed, 20);
  EXPECT_EQ(m.stats.wet_u, 31);
  EXPECT_EQ(m.stats.wet_psi, 22);
  // Every interior wet ρ point is in Ω_L.
  for (int j = 1; j + 1 < kNj; ++j)
    for (int i = 1; i + 1 < kNi; ++i)
      if (m.rho[static_cast<std::size_t>(j * kNi + i)] != 0) {
        EXPECT_TRUE(filled.get(50 + i, 30 + j)) << i << "," << j;
      }
}

TEST(RegionalMask, CornersCopyTheDiagonalInteriorPoint) {
  auto m = drawn_mask({"0000", "0100", "0010", "0000"});
  EXPECT_EQ(copy_boundary_from_interior(m, 4, 4), 6);
  EXPECT_EQ(m, drawn_mask({"1100", "1100", "0011", "0011"}));
  EXPECT_THROW(copy_boundary_from_interior(m, 2, 8), InternalError);
}

TEST(RegionalMask, FilledSetMustMatchTheLattice) {
  const Lattice lat = Lattice::make(4.0, 0, -180.0);
  const double x = 0.0;
  EXPECT_THROW(rho_mask_from_filled(Bitmap(10, 10), lat, PoleRotation(), &x, &x, nullptr, 0.0, 1), InternalError);
}

TEST(RegionalMask, PointsOutsideARegionalRasterAreAClearError) {
  // A 10° x 10° raster of -200 m from 10°E, 40°N.
  std::vector<float> v(11 * 11, -200.0f);
  const auto bathy = raster::Bathymetry::from_grid(v, 11, 11, 10.0, 40.0, 1.0, 1.0);
  const std::vector<double> lon_in = {12.5, 19.0}, lat_in = {41.0, 49.5};
  const auto d = sample_elevations(bathy, lon_in.data(), lat_in.data(), 2);
  EXPECT_DOUBLE_EQ(d[0], -200.0);
  const std::vector<double> lon_out = {12.5, 21.0, 25.0}, lat_out = {41.0, 45.0, 45.0};
  try {
    (void)sample_elevations(bathy, lon_out.data(), lat_out.data(), 3);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no depth at 2 of the 3"), std::string::npos) << m;
    EXPECT_NE(m.find("lon 21.0000, lat 45.0000"), std::string::npos) << m;
    EXPECT_NE(m.find("leaves the raster's coverage"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace aq::mask::unit_mask_regional_mask_test

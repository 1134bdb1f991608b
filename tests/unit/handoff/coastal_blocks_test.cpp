// SPDX-License-Identifier: GPL-3.0-or-later
// Coastal blocks: the coastal-pixel definition on a drawn mask, exact per-square counts, the
// ranking order, suggested ny, user boxes (sampled counts), the error for a box without water, and
// Mercator-lattice squares (boxes of their Mercator rows, 2^L pixels high).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "handoff/coastal_blocks.hpp"

namespace unit_handoff_coastal_blocks_test {

namespace {

using aq::Bitmap;
using aq::Lattice;
using aq::PoleRotation;
using aq::handoff::BlockCandidate;
using ::testing::HasSubstr;

// Draws rows top (north) first: '#' filled, '.' not.
Bitmap draw(const std::vector<std::string>& rows) {
  const auto ny = static_cast<std::int64_t>(rows.size());
  const auto nx = static_cast<std::int64_t>(rows[0].size());
  Bitmap b(nx, ny);
  for (std::int64_t r = 0; r < ny; ++r)
    for (std::int64_t i = 0; i < nx; ++i)
      if (rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(i)] == '#') b.set(i, ny - 1 - r);
  return b;
}

std::vector<std::string> picture(const Bitmap& b) {
  std::vector<std::string> rows;
  for (std::int64_t j = b.ny() - 1; j >= 0; --j) {
    std::string r;
    for (std::int64_t i = 0; i < b.nx(); ++i) r += b.get(i, j) ? 'c' : '.';
    rows.push_back(r);
  }
  return rows;
}

// Δ0 = 45°, L = 2: 8 x 4 level-0 squares of 4 x 4 pixels, a 32 x 16 pixel lattice.
Lattice small_lattice() { return Lattice::make(45.0, 2, -180.0); }

}  // namespace

TEST(CoastalPixels, FilledPixelsWithANonFilledNeighbourOfEight) {
  // 8 columns wrap: column 7 is next to column 0.
  // clang-format off
  const Bitmap f = draw({"########",
                         "########",
                         "###..###",
                         "###..###",
                         "########",
                         "#######."});
  const std::vector<std::string> expect = {"........",
                                           "..cccc..",
                                           "..c..c..",
                                           "..c..c..",
                                           "c.cccccc",
                                           "c.....c."};
  // clang-format on
  EXPECT_EQ(picture(aq::handoff::coastal_pixels(f)), expect);
}

TEST(CoastalPixels, PoleRowsAreNotCoast) {
  const Bitmap f = draw({"####", "####"});
  EXPECT_EQ(aq::handoff::coastal_pixels(f).count(), 0);
}

TEST(RankBlocks, CountsPerSquareAndRanksByCoast) {
  const Lattice lat = small_lattice();
  ASSERT_EQ(lat.nx, 32);
  ASSERT_EQ(lat.ny, 16);
  Bitmap f(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) f.set(i, j);
  // Land: one pixel in square (2, 1) (pixels 8..11 x 4..7) -> 8 coastal pixels around it, all in (2, 1).
  f.clear(9, 5);
  // Land: a 2 x 2 block at pixels (21..22, 9..10), the middle of square (5, 2) (pixels 20..23 x
  // 8..11) -> its ring of 12 coastal pixels is the rest of the square.
  for (std::int64_t j = 9; j < 11; ++j)
    for (std::int64_t i = 21; i < 23; ++i) f.clear(i, j);
  // Land: pixel (15, 3) at the corner of square (3, 0): its 8 neighbours spread over squares
  // (3, 0) [3 pixels: (14,2),(14,3),(15,2)], (4, 0) [(16,2),(16,3)], (3, 1) [(14,4),(15,4)], (4, 1) [(16,4)].
  f.clear(15, 3);
  aq::config::BlocksOptions o;
  const auto r = aq::handoff::rank_blocks(f, lat, PoleRotation(), o);
  ASSERT_EQ(r.size(), 6u);
  EXPECT_EQ(r[0].square_a, 5);
  EXPECT_EQ(r[0].square_b, 2);
  EXPECT_EQ(r[0].coastal_pixels, 12);
  EXPECT_EQ(r[0].filled_pixels, 12);
  EXPECT_DOUBLE_EQ(r[0].wet_fraction, 12.0 / 16.0);
  EXPECT_EQ(r[1].square_a, 2);
  EXPECT_EQ(r[1].coastal_pixels, 8);
  EXPECT_EQ(r[1].filled_pixels, 15);
  EXPECT_EQ(r[2].coastal_pixels, 3);
  EXPECT_EQ(r[2].square_a, 3);
  EXPECT_EQ(r[2].square_b, 0);
  EXPECT_EQ(r[3].coastal_pixels, 2);
  EXPECT_EQ(r[4].coastal_pixels, 2);
  EXPECT_EQ(r[5].coastal_pixels, 1);
  EXPECT_EQ(r[5].square_a, 4);
  EXPECT_EQ(r[5].square_b, 1);
  // Squares (4, 0) [wet 1] and (3, 1) [wet 1]: equal, candidate order (row-major) decides.
  EXPECT_EQ(r[3].square_a, 4);
  EXPECT_EQ(r[3].square_b, 0);
  EXPECT_EQ(r[4].square_a, 3);
  EXPECT_EQ(r[4].square_b, 1);
  // The box of square (5, 2): λ = -180 + 5·45 .. +45, φ = -90 + 2·45 .. +45, lattice system.
  EXPECT_DOUBLE_EQ(r[0].box.lon_min_deg, 45.0);
  EXPECT_DOUBLE_EQ(r[0].box.lon_max_deg, 90.0);
  EXPECT_DOUBLE_EQ(r[0].box.lat_min_deg, 0.0);
  EXPECT_DOUBLE_EQ(r[0].box.lat_max_deg, 45.0);
  EXPECT_TRUE(r[0].box.lattice_system);
}

TEST(RankBlocks, NoCoastAnywhereIsAnInputError) {
  const Lattice lat = small_lattice();
  Bitmap f(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) f.set(i, j);
  EXPECT_THROW((void)aq::handoff::rank_blocks(f, lat, PoleRotation(), {}), aq::InputError);
}

TEST(RankBlocks, UserBoxesAreSampledAndRanked) {
  const Lattice lat = small_lattice();  // pixels of 11.25°
  Bitmap f(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) f.set(i, j);
  f.clear(16, 8);  // pixel [0, 11.25] x [0, 11.25]
  aq::config::BlocksOptions o;
  o.boxes = {{-90.0, -45.0, -45.0, 0.0}, {-22.5, 22.5, -22.5, 22.5}};
  const auto r = aq::handoff::rank_blocks(f, lat, PoleRotation(), o);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].box_index, 1);
  EXPECT_FALSE(r[0].box.lattice_system);
  // 4 x 4 samples at the pixel centres (-16.875 .. 16.875): the land pixel and 8 neighbours inside
  // [-11.25, 22.5]^2 ∩ the box: all 8 coastal neighbours are sampled once.
  EXPECT_EQ(r[0].coastal_pixels, 8);
  EXPECT_EQ(r[0].filled_pixels, 15);
  EXPECT_NEAR(r[0].wet_fraction, 15.0 / 16.0, 0.02);
  EXPECT_EQ(r[1].coastal_pixels, 0);
  EXPECT_DOUBLE_EQ(r[1].wet_fraction, 1.0);
  EXPECT_EQ(r[0].describe(), "blocks.boxes[1]");
}

TEST(RankBlocks, BoxWithoutWaterNamesTheBox) {
  const Lattice lat = small_lattice();
  Bitmap f(lat.nx, lat.ny);
  for (std::int64_t i = 0; i < lat.nx; ++i) f.set(i, 0);  // only the southernmost row is ocean
  aq::config::BlocksOptions o;
  o.boxes = {{-180.0, -170.0, -90.0, -70.0}, {10.0, 20.0, 30.0, 40.0}};
  try {
    (void)aq::handoff::rank_blocks(f, lat, PoleRotation(), o);
    FAIL() << "no error";
  } catch (const aq::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("blocks.boxes[1]"));
    EXPECT_THAT(e.what(), HasSubstr("no water"));
    EXPECT_EQ(e.exit_code(), 2);
  }
}

TEST(SuggestNy, FromRefinementOrFixed) {
  const Lattice lat = Lattice::make(4.0, 3, -180.0);  // Δ_L = 0.5°
  const aq::handoff::BlockBox b{0.0, 4.0, 40.0, 44.0, true};
  EXPECT_EQ(aq::handoff::suggest_ny(b, lat, PoleRotation(), 3, 0), 24);  // 4° / (0.5°/3)
  EXPECT_EQ(aq::handoff::suggest_ny(b, lat, PoleRotation(), 5, 0), 40);
  EXPECT_EQ(aq::handoff::suggest_ny(b, lat, PoleRotation(), 1, 0), 8);    // 8 at least
  EXPECT_EQ(aq::handoff::suggest_ny(b, lat, PoleRotation(), 3, 77), 77);  // fixed wins
  const aq::handoff::BlockBox c{0.0, 4.0, 40.0, 42.25, false};
  EXPECT_EQ(aq::handoff::suggest_ny(c, lat, PoleRotation(), 3, 0), 14);  // ceil(13.5) -> 14, even
}

TEST(RankBlocks, MercatorSquaresAreBoxesOfTheirRowsAndMeasureTheirPixels) {
  const Lattice lat = Lattice::make_mercator(4.0, 3, -180.0, 86.5);
  Bitmap f(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) f.set(i, j);
  const std::int64_t b = lat.ny / 8 / 2 + 14;  // a level-0 square row at about 50° of the lattice frame
  f.clear(10 * 8 + 3, b * 8 + 3);
  const auto r = aq::handoff::rank_blocks(f, lat, PoleRotation(), {});
  ASSERT_EQ(r.size(), 1u);
  const aq::handoff::BlockBox& box = r[0].box;
  EXPECT_TRUE(box.lattice_system);
  EXPECT_TRUE(box.mercator_rows);
  EXPECT_EQ(box.lat_min_deg, lat.lat_of(b * 8));
  EXPECT_EQ(box.lat_max_deg, lat.lat_of(b * 8 + 8));
  EXPECT_LT(box.lat_max_deg - box.lat_min_deg, 3.0);  // 4°·cos φ: shorter than wide in degrees
  EXPECT_EQ(r[0].coastal_pixels, 8);
  // 8 x 8 pixels, so ny = 8 · refinement, as for a lon-lat square (which φ-degrees would not give).
  const auto px = aq::handoff::box_extent_px(box, lat, PoleRotation());
  EXPECT_NEAR(px[0], 8.0, 1e-9);
  EXPECT_NEAR(px[1], 8.0, 1e-9);
  EXPECT_EQ(r[0].suggested_ny, 24);
  // A geographic box: about as many pixels as the rows and columns it covers (centre scale).
  const aq::handoff::BlockBox g{0.0, 4.0, 60.0, 62.0, false};
  const auto gp = aq::handoff::box_extent_px(g, lat, PoleRotation());
  EXPECT_NEAR(gp[1], lat.row_of_lat(62.0) - lat.row_of_lat(60.0), 0.02 * gp[1]);
  EXPECT_NEAR(gp[0], 8.0, 1e-9);  // 4° of arc·cos 61° over pixels of 0.5°·cos 61° (no rotation)
  EXPECT_NEAR(gp[1], 2.0 / (0.5 * std::cos(61.0 * aq::kDegToRad)), 1e-9);
  EXPECT_EQ(aq::handoff::suggest_ny(g, lat, PoleRotation(), 1, 0), 10);  // ceil(8.25) = 9 -> even
}

}  // namespace unit_handoff_coastal_blocks_test

// SPDX-License-Identifier: GPL-3.0-or-later
// K-cursor fill on drawn masks (seed 002 Fig. 2): channel widths vs K, the λ seam, lakes, seeds.
#include "mask/k_cursor_fill.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "unit/mask/mask_drawing.hpp"

namespace aq::mask::unit_mask_k_cursor_fill_test {
namespace {

using test::draw;
using test::marks;
using test::render;

std::string fill_drawing(const std::vector<std::string_view>& rows, int k) {
  const Bitmap wet = draw(rows);
  const std::vector<PixelIJ> seeds = marks(rows);
  return render(k_fill(wet, k, seeds));
}

std::string join(const std::vector<std::string_view>& rows) {
  std::string s;
  for (const auto r : rows) s += std::string(r) + "\n";
  return s;
}

// A 1-pixel channel (one row high) between two basins. 'S' marks the seed window's lower-left
// pixel (a K-window extends up and to the east from it).
const std::vector<std::string_view> kOnePixelChannel = {
    // clang-format off
    "............",
    ".###....###.",
    ".###....###.",
    ".##########.",
    ".###....###.",
    ".S##....###.",
    "............",
    // clang-format on
};

TEST(KFill, OnePixelChannelIsCrossedAtK1) {
  EXPECT_EQ(fill_drawing(kOnePixelChannel, 1), join({
                                                   // clang-format off
                                                   "............",
                                                   ".###....###.",
                                                   ".###....###.",
                                                   ".##########.",
                                                   ".###....###.",
                                                   ".###....###.",
                                                   "............",
                                                   // clang-format on
                                               }));
}

TEST(KFill, OnePixelChannelIsNotCrossedAtK2) {
  EXPECT_EQ(fill_drawing(kOnePixelChannel, 2), join({
                                                   // clang-format off
                                                   "............",
                                                   ".###........",
                                                   ".###........",
                                                   ".###........",
                                                   ".###........",
                                                   ".###........",
                                                   "............",
                                                   // clang-format on
                                               }));
}

// A 2-pixel channel between two 4-pixel-wide basins.
const std::vector<std::string_view> kTwoPixelChannel = {
    // clang-format off
    "..............",
    ".####....####.",
    ".####....####.",
    ".############.",
    ".############.",
    ".S###....####.",
    "..............",
    // clang-format on
};

TEST(KFill, TwoPixelChannelIsCrossedAtK2) {
  EXPECT_EQ(fill_drawing(kTwoPixelChannel, 2),
            join({
                // clang-format off
                "..............",
                ".####....####.",
                ".####....####.",
                ".############.",
                ".############.",
                ".####....####.",
                "..............",
                // clang-format on
            }));
}

TEST(KFill, TwoPixelChannelIsNotCrossedAtK3) {
  EXPECT_EQ(fill_drawing(kTwoPixelChannel, 3),
            join({
                // clang-format off
                "..............",
                ".####.........",
                ".####.........",
                ".####.........",
                ".####.........",
                ".####.........",
                "..............",
                // clang-format on
            }));
}

TEST(KFill, ChannelAcrossTheSeamConnectsBothBasins) {
  // The basins touch nothing inside the drawing; the only link is the 2-pixel channel that leaves
  // the east edge and comes back from the west edge.
  const std::vector<std::string_view> rows = {
      // clang-format off
      "............",
      "..###..###..",
      "#####..#####",
      "#####..#####",
      "..S##..###..",
      "............",
      // clang-format on
  };
  EXPECT_EQ(fill_drawing(rows, 2),
            join({
                // clang-format off
                "............",
                "..###..###..",
                "#####..#####",
                "#####..#####",
                "..###..###..",
                "............",
                // clang-format on
            }));
  // Cut the channel just east of the seam: the K=2 fill can no longer leave the west basin.
  std::vector<std::string_view> cut = rows;
  cut[2] = "#####..####.";
  cut[3] = "#####..####.";
  EXPECT_EQ(fill_drawing(cut, 2),
            join({
                // clang-format off
                "............",
                "..###.......",
                "#####.......",
                "#####.......",
                "..###.......",
                "............",
                // clang-format on
            }));
}

TEST(KFill, LakeStaysOut) {
  const std::vector<std::string_view> rows = {
      // clang-format off
      "##########",
      "#S#######.",
      "###.....##",
      "###.###.##",
      "###.###.##",
      "###.....##",
      "##########",
      // clang-format on
  };
  EXPECT_EQ(fill_drawing(rows, 1),
            join({
                // clang-format off
                "##########",
                "#########.",
                "###.....##",
                "###.....##",
                "###.....##",
                "###.....##",
                "##########",
                // clang-format on
            }));
}

TEST(KFill, WindowsNeverCrossThePoles) {
  // Rows 0 and ny-1 are wet, but a K=2 window at the top row would need a row above the pole.
  const Bitmap wet = draw({"####", "####", "####"});
  const Bitmap w = all_wet_windows(wet, 2);
  EXPECT_EQ(render(w), "....\n####\n####\n");
  EXPECT_EQ(render(dilate_windows(w, 2)), "####\n####\n####\n");
  EXPECT_EQ(render(all_wet_windows(wet, 4)), "....\n....\n....\n");
}

TEST(KFill, DiagonalNeighboursAreNotConnected) {
  const std::vector<std::string_view> rows = {
      // clang-format off
      ".....",
      "..#..",
      ".S...",
      ".....",
      // clang-format on
  };
  EXPECT_EQ(fill_drawing(rows, 1), join({".....", ".....", ".#...", "....."}));
  const ComponentStats cs = count_components(draw(rows));
  EXPECT_EQ(cs.count, 2);
  EXPECT_EQ(cs.largest, 1);
}

TEST(KFill, ComponentsWrapAcrossTheSeamAndCountProbeHits) {
  const Bitmap m = draw({
      // clang-format off
      "#..#..##",
      "#..#....",
      "........",
      "##.....#",
      // clang-format on
  });
  const Bitmap probe = draw({
      // clang-format off
      "........",
      "........",
      "........",
      "#.......",
      // clang-format on
  });
  const ComponentStats cs = count_components(m, &probe);
  // {(0,3),(0,2),(6,3),(7,3)} via the seam, {(3,3),(3,2)}, {(0,0),(1,0),(7,0)} via the seam.
  EXPECT_EQ(cs.count, 3);
  EXPECT_EQ(cs.largest, 4);
  EXPECT_EQ(cs.touching_probe, 1);
  EXPECT_EQ(cs.cells_touching_probe, 3);
  // The same figures with a scratch bitmap of the same shape lending its storage (k_cursor_fill
  // lends its spent windows), which is reused, not reallocated; the input is untouched.
  Bitmap scratch = probe;
  const std::uint64_t* storage = scratch.words().data();
  const Bitmap before = m;
  const ComponentStats lent = count_components(m, &probe, &scratch);
  EXPECT_EQ(lent.count, cs.count);
  EXPECT_EQ(lent.largest, cs.largest);
  EXPECT_EQ(lent.touching_probe, cs.touching_probe);
  EXPECT_EQ(lent.cells_touching_probe, cs.cells_touching_probe);
  EXPECT_EQ(scratch.words().data(), storage);
  EXPECT_EQ(m, before);
}

TEST(KFill, FullRowRunAndRepeatedSeedsCountOnce) {
  const Bitmap wet = draw({"......", "######", "######", "......"});
  std::vector<std::int64_t> per_seed;
  const std::vector<PixelIJ> seeds = {{2, 1}, {5, 2}};
  const Bitmap f = k_fill(wet, 2, seeds, &per_seed);
  EXPECT_EQ(f.count(), 12);
  ASSERT_EQ(per_seed.size(), 2U);
  EXPECT_EQ(per_seed[0], 6);  // the six windows of row 1 (periodic)
  EXPECT_EQ(per_seed[1], 0);  // (5, 2) is not an all-wet window: contributes nothing
}

// Geographic seeds on a 16×8 lattice of 22.5° pixels.
const std::vector<std::string_view> kBlock = {
    // clang-format off
    "................",
    "................",
    "....######......",
    "....######......",
    "....######......",
    "................",
    "................",
    "................",
    // clang-format on
};

Lattice coarse_lattice() { return Lattice::make(22.5, 0, -180.0); }

TEST(KFillSeeds, SeedInsideAWindowIsNotMoved) {
  const Lattice lat = coarse_lattice();
  ASSERT_EQ(lat.nx, 16);
  ASSERT_EQ(lat.ny, 8);
  const Bitmap wet = draw(kBlock);
  std::vector<std::string> warnings;
  const Logger log([&](LogLevel l, std::string_view m) {
    if (l == LogLevel::kWarning) warnings.emplace_back(m);
  });
  // Pixel (6, 4): centre (-33.75, 11.25).
  const KFillResult r = k_cursor_fill(wet, lat, PoleRotation(), 2, {{-33.75, 11.25}}, 5.0, log);
  ASSERT_EQ(r.seeds.size(), 1U);
  EXPECT_FALSE(r.seeds[0].moved);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(r.stats.filled_pixels, 18);
  EXPECT_EQ(r.stats.wet_left_out, 0);
  EXPECT_EQ(r.stats.wet_components, 1);
  EXPECT_EQ(r.stats.all_wet_windows, 10);
  EXPECT_EQ(r.stats.reached_windows, 10);
  // The seed's pixel belongs to 4 windows; the nearest centre is a vertex of the pixel: ties go to
  // the smallest (j, i) among equal distances, which here is unique by the sphere's geometry.
  const PixelIJ w = r.seeds[0].window;
  EXPECT_TRUE(w.i >= 5 && w.i <= 6 && w.j >= 3 && w.j <= 4) << w.i << "," << w.j;
}

TEST(KFillSeeds, SeedOnLandMovesWithinRadiusAndSaysSo) {
  const Lattice lat = coarse_lattice();
  const Bitmap wet = draw(kBlock);
  std::vector<std::string> warnings;
  const Logger log([&](LogLevel l, std::string_view m) {
    if (l == LogLevel::kWarning) warnings.emplace_back(m);
  });
  // Pixel (11, 4) is land; the nearest window centre is that of window (8, 4) at (22.5, 22.5):
  // cos d = sin 11.25° sin 22.5° + cos 11.25° cos 22.5° cos 56.25°, d = 54.68° (window (8, 3) at
  // (22.5, 0) is 56.98° away).
  const KFillResult r = k_cursor_fill(wet, lat, PoleRotation(), 2, {{78.75, 11.25}}, 60.0, log);
  ASSERT_EQ(r.seeds.size(), 1U);
  EXPECT_TRUE(r.seeds[0].moved);
  EXPECT_EQ(r.seeds[0].window, (PixelIJ{8, 4}));
  EXPECT_NEAR(r.seeds[0].moved_deg, 54.68, 0.01);
  EXPECT_NEAR(r.seeds[0].window_center.lon_deg, 22.5, 1e-9);
  EXPECT_NEAR(r.seeds[0].window_center.lat_deg, 22.5, 1e-9);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_THAT(warnings[0], testing::HasSubstr("mask.seeds[0] = (78.75, 11.25)"));
  EXPECT_THAT(warnings[0], testing::HasSubstr("moved 54.68"));
  EXPECT_THAT(warnings[0], testing::HasSubstr("(22.5000, 22.5000)"));
  EXPECT_EQ(r.stats.filled_pixels, 18);
}

TEST(KFillSeeds, SeedOnLandOutsideRadiusIsAConfigErrorNamingTheSeed) {
  const Lattice lat = coarse_lattice();
  const Bitmap wet = draw(kBlock);
  try {
    (void)k_cursor_fill(wet, lat, PoleRotation(), 2, {{-33.75, 11.25}, {78.75, 11.25}}, 30.0, Logger::null());
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("mask.seeds[1] = (78.75, 11.25)"));
    EXPECT_THAT(e.what(), testing::HasSubstr("mask.seed_radius_deg = 30"));
  }
}

// mask.seeds, mask.cursor and mask.seed_radius_deg are validated at load (tests/unit/config); the
// fill refuses values outside their ranges as a bug.
TEST(KFillSeeds, BadSeedsAndCursorBreakThePreconditions) {
  const Lattice lat = coarse_lattice();
  const Bitmap wet = draw(kBlock);
  EXPECT_THROW((void)k_cursor_fill(wet, lat, PoleRotation(), 2, {{0.0, 95.0}}, 5.0, Logger::null()), InternalError);
  EXPECT_THROW((void)k_cursor_fill(wet, lat, PoleRotation(), 2, {}, 5.0, Logger::null()), InternalError);
  EXPECT_THROW((void)k_cursor_fill(wet, lat, PoleRotation(), 0, {{-33.75, 11.25}}, 5.0, Logger::null()), InternalError);
  EXPECT_THROW((void)k_cursor_fill(wet, lat, PoleRotation(), 65, {{-33.75, 11.25}}, 5.0, Logger::null()),
               InternalError);
  EXPECT_THROW((void)k_cursor_fill(wet, lat, PoleRotation(), 2, {{-33.75, 11.25}}, -1.0, Logger::null()),
               InternalError);
}

TEST(KFillSeeds, NearestWindowAcrossTheSeamAndOverThePole) {
  const Lattice lat = coarse_lattice();
  // Across the seam: windows (0, 3) and (1, 3) only; the seed at pixel (14, 3), centre
  // (146.25, -11.25), is 56.98° from window (0, 3) (centre (-157.5, 0), 56.25° of λ over the seam).
  const Bitmap seam = draw({
      // clang-format off
      "................",
      "................",
      "................",
      "###.............",
      "###.............",
      "................",
      "................",
      "................",
      // clang-format on
  });
  KFillResult r = k_cursor_fill(seam, lat, PoleRotation(), 2, {{146.25, -11.25}}, 60.0, Logger::null());
  EXPECT_EQ(r.seeds[0].window, (PixelIJ{0, 3}));
  EXPECT_NEAR(r.seeds[0].moved_deg, 56.98, 0.01);
  // Over the pole: the only window (8, 6), centre (22.5, 67.5), seen from (-168.75, 78.75):
  // cos d = sin 78.75° sin 67.5° + cos 78.75° cos 67.5° cos 191.25°, d = 33.60°.
  const Bitmap polar = draw({
      // clang-format off
      "........##......",
      "........##......",
      "................",
      "................",
      "................",
      "................",
      "................",
      "................",
      // clang-format on
  });
  r = k_cursor_fill(polar, lat, PoleRotation(), 2, {{-168.75, 78.75}}, 40.0, Logger::null());
  EXPECT_EQ(r.seeds[0].window, (PixelIJ{8, 6}));
  EXPECT_NEAR(r.seeds[0].moved_deg, 33.60, 0.01);
  EXPECT_EQ(r.stats.filled_pixels, 4);
}

TEST(KFillSeeds, SecondSeedInTheSameFillIsReportedAsSuch) {
  const Lattice lat = coarse_lattice();
  const Bitmap wet = draw(kBlock);
  const KFillResult r =
      k_cursor_fill(wet, lat, PoleRotation(), 1, {{-33.75, 11.25}, {11.25, -11.25}}, 0.0, Logger::null());
  ASSERT_EQ(r.seeds.size(), 2U);
  EXPECT_EQ(r.seeds[0].windows_reached, 18);
  EXPECT_EQ(r.seeds[1].windows_reached, 0);
  EXPECT_EQ(r.seeds[1].same_fill_as, 0);
}

TEST(KFillSeeds, SeedsAreMappedThroughThePoleRotation) {
  // A rotation that moves the geographic point (0, 0) to somewhere else in the lattice: the seed
  // must land on the window that holds the rotated point.
  const Lattice lat = Lattice::make(1.0, 0, -180.0);
  const PoleRotation rot(-44.858333, 78.141667);
  double rlon = 0.0, rlat = 0.0;
  rot.to_rotated(10.0, -40.0, rlon, rlat);
  Bitmap wet(lat.nx, lat.ny);
  double x = 0.0, y = 0.0;
  deg_to_lattice_xy(lat, {rlon, rlat}, x, y);
  const auto pi = static_cast<std::int64_t>(x), pj = static_cast<std::int64_t>(y);
  for (std::int64_t dj = -3; dj <= 3; ++dj)
    for (std::int64_t di = -3; di <= 3; ++di) wet.set(wrap_index(pi + di, lat.nx), pj + dj);
  const KFillResult r = k_cursor_fill(wet, lat, rot, 3, {{10.0, -40.0}}, 0.0, Logger::null());
  EXPECT_FALSE(r.seeds[0].moved);
  EXPECT_EQ(r.stats.filled_pixels, 49);
  // The window centre maps back near the seed (within a window diagonal).
  EXPECT_LT(angular_distance_deg(r.seeds[0].window_center, {10.0, -40.0}), 3.0);
}

}  // namespace
}  // namespace aq::mask::unit_mask_k_cursor_fill_test

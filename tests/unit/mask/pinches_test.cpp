// SPDX-License-Identifier: GPL-3.0-or-later
// Pinch vertices (1001 / 0110 blocks) of drawn masks and their removal.
#include "mask/pinches.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "mask/k_cursor_fill.hpp"
#include "unit/mask/mask_drawing.hpp"

namespace aq::mask::unit_mask_pinches_test {
namespace {

using test::draw;
using test::render;

TEST(Pinches, BothPatternsAndTheSeamAreFound) {
  const Bitmap f = draw({
      // clang-format off
      "#.....",  // j = 3: (0,3) touches (5,2) at vertex (0,3) across the seam
      ".....#",  // j = 2
      "..#...",  // j = 1
      ".#.#..",  // j = 0
      // clang-format on
  });
  const std::vector<Pinch> p = find_pinches(f);
  ASSERT_EQ(p.size(), 3U);
  EXPECT_EQ(p[0].vertex, (PixelIJ{2, 1}));  // NE (2,1) + SW (1,0)
  EXPECT_EQ(p[0].pattern, PinchPattern::kNeSw);
  EXPECT_EQ(p[1].vertex, (PixelIJ{3, 1}));  // NW (2,1) + SE (3,0)
  EXPECT_EQ(p[1].pattern, PinchPattern::kNwSe);
  EXPECT_EQ(p[2].vertex, (PixelIJ{0, 3}));  // NE (0,3) + SW (5,2)
  EXPECT_EQ(p[2].pattern, PinchPattern::kNeSw);
  EXPECT_EQ(count_pinches(f), 3);
}

TEST(Pinches, FullBlocksEdgesAndPolesAreNotPinches) {
  EXPECT_EQ(count_pinches(draw({"##..", "##..", "....", "#..#"})), 0);
  // A checkerboard row pair: every vertex of the middle row, including I = 0 across the seam.
  EXPECT_EQ(count_pinches(draw({".#.#", "#.#."})), 4);
}

TEST(Pinches, MatchBruteForceOnRandomMasks) {
  for (std::uint32_t s = 0; s < 30; ++s) {
    const std::int64_t nx = 5 + s * 7, ny = 3 + s % 11;
    const Bitmap f = test::random_bitmap(nx, ny, 0.5, s);
    std::vector<Pinch> ref;
    for (std::int64_t J = 1; J < ny; ++J)
      for (std::int64_t I = 0; I < nx; ++I) {
        const std::int64_t w = (I + nx - 1) % nx;
        const bool nw = f.get(w, J), ne = f.get(I, J), sw = f.get(w, J - 1), se = f.get(I, J - 1);
        if (nw && se && !ne && !sw) ref.push_back({{I, J}, PinchPattern::kNwSe, {}, {}});
        if (ne && sw && !nw && !se) ref.push_back({{I, J}, PinchPattern::kNeSw, {}, {}});
      }
    const std::vector<Pinch> got = find_pinches(f);
    ASSERT_EQ(got.size(), ref.size()) << s;
    for (std::size_t k = 0; k < ref.size(); ++k) {
      ASSERT_EQ(got[k].vertex, ref[k].vertex) << s;
      ASSERT_EQ(got[k].pattern, ref[k].pattern) << s;
    }
    EXPECT_EQ(count_pinches(f), static_cast<std::int64_t>(ref.size()));
  }
}

TEST(Pinches, LocatedThroughTheLattice) {
  const Lattice l = Lattice::make(22.5, 0, -180.0);  // 16 × 8
  Bitmap f(l.nx, l.ny);
  f.set(3, 4);  // NE of vertex (3, 4)
  f.set(2, 3);  // SW
  std::vector<Pinch> p = find_pinches(f);
  ASSERT_EQ(p.size(), 1U);
  locate_pinches(p, l, PoleRotation());
  EXPECT_DOUBLE_EQ(p[0].geographic.lon_deg, -180.0 + 3 * 22.5);
  EXPECT_DOUBLE_EQ(p[0].geographic.lat_deg, -90.0 + 4 * 22.5);
}

TEST(PinchRemoval, TieGoesToTheSmallerPixelIndex) {
  Bitmap f = draw({
      // clang-format off
      ".####.",
      ".#..#.",
      ".#.#..",  // pinch at vertex (4, 2): NE (4, 2) and SW (3, 1), both dead ends
      ".###..",
      // clang-format on
  });
  const std::vector<PixelIJ> seeds = {{1, 0}};
  ASSERT_EQ(k_fill(f, 1, seeds), f);
  const PinchRemovalStats st = remove_pinches(f, 1, seeds);
  EXPECT_EQ(render(f), ".####.\n.#..#.\n.#....\n.###..\n");  // (3, 1) has index 9 < 16
  EXPECT_EQ(st.pinches_found, 1);
  EXPECT_EQ(st.rounds, 1);
  EXPECT_EQ(st.pixels_chosen, 1);
  EXPECT_EQ(st.pixels_removed, 1);
  EXPECT_EQ(st.unresolved, 0);
}

TEST(PinchRemoval, NeverCutsTheOnlyLinkWhenTheOtherPixelIsADeadEnd) {
  // Pinch at vertex (2, 2): SW (1, 1) is the only link of (0, 1), (0, 2) to the rest; NE (2, 2)
  // hangs below the top row. Index order alone would take (1, 1) and cut off two pixels.
  Bitmap f = draw({
      // clang-format off
      "..####.",
      "#.#..#.",
      "##...#.",
      ".#####.",
      // clang-format on
  });
  const std::vector<PixelIJ> seeds = {{1, 0}};
  ASSERT_EQ(k_fill(f, 1, seeds), f);
  const PinchRemovalStats st = remove_pinches(f, 1, seeds);
  EXPECT_EQ(render(f), "..####.\n#....#.\n##...#.\n.#####.\n");
  EXPECT_EQ(st.pixels_removed, 1);
}

TEST(PinchRemoval, NeverTakesASeedWindowPixel) {
  Bitmap f = draw({
      // clang-format off
      ".####.",
      ".#..#.",
      ".#.#..",
      ".###..",
      // clang-format on
  });
  const std::vector<PixelIJ> seeds = {{3, 1}};  // the pixel the tie-break would take
  ASSERT_EQ(k_fill(f, 1, seeds), f);
  (void)remove_pinches(f, 1, seeds);
  EXPECT_EQ(render(f), ".####.\n.#....\n.#.#..\n.###..\n");
}

// Lower-left pixel of a window in the largest 4-connected component of all-wet K-windows.
PixelIJ seed_in_largest_component(const Bitmap& wet, int k) {
  Bitmap rem = all_wet_windows(wet, k);
  PixelIJ best{-1, -1};
  std::int64_t best_n = 0;
  for (std::int64_t j = 0; j < rem.ny(); ++j)
    for (std::int64_t i = 0; i < rem.nx(); ++i) {
      if (!rem.get(i, j)) continue;
      const std::int64_t n = flood_consume(rem, {i, j}).cells;
      if (n > best_n) {
        best_n = n;
        best = {i, j};
      }
    }
  return best;
}

TEST(PinchRemoval, ResultIsAPinchFreeKFillOfItselfOnRandomMasks) {
  int with_pinches = 0;
  for (std::uint32_t s = 0; s < 40; ++s) {
    const int k = 1 + static_cast<int>(s % 3);
    const std::int64_t nx = 40 + 3 * s, ny = 20 + s;
    const bool smooth = (s / 3) % 2 == 0;
    const Bitmap wet =
        smooth ? test::smooth_random_bitmap(nx, ny, 0.2 * (s % 4), s) : test::random_bitmap(nx, ny, 0.65 + 0.1 * k, s);
    const PixelIJ seed = seed_in_largest_component(wet, k);
    if (seed.i < 0) continue;
    const std::vector<PixelIJ> seeds = {seed};
    const Bitmap filled = k_fill(wet, k, seeds);
    Bitmap out = filled;
    const PinchRemovalStats st = remove_pinches(out, k, seeds);
    with_pinches += st.pinches_found > 0 ? 1 : 0;
    EXPECT_EQ(count_pinches(out), 0) << s;
    EXPECT_EQ(st.unresolved, 0) << s;
    EXPECT_EQ(k_fill(out, k, seeds), out) << s;  // the K-cursor property holds exactly
    for (std::size_t q = 0; q < out.words().size(); ++q) ASSERT_EQ(out.words()[q] & ~filled.words()[q], 0U) << s;
    EXPECT_EQ(st.pixels_removed, filled.count() - out.count());
    // On smooth masks removal is local: a few pixels per pinch, no basin is lost. On noise every
    // pixel is a bridge and cut-off pieces are expected, but never most of the fill.
    if (smooth)
      EXPECT_LE(st.pixels_removed, 4 * k * k * st.pinches_found) << s;
    else
      EXPECT_GT(out.count(), filled.count() / 2) << s;
  }
  EXPECT_GT(with_pinches, 20);
}

}  // namespace
}  // namespace aq::mask::unit_mask_pinches_test

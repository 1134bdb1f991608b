// SPDX-License-Identifier: GPL-3.0-or-later
// ROMS depth: clip to hmin, r-factor smoothing on wet faces that only deepens, is minimal (every
// raised point is held by a tight neighbour), independent of sweep order, and leaves land alone.
#include "curvilinear/common/roms_depth.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"

namespace aq::curvilinear::unit_curvilinear_roms_depth_test {
namespace {

std::size_t at(int ni, int i, int j) { return static_cast<std::size_t>(j * ni + i); }

TEST(RomsDepth, ClipsToHminEverywhereAndKeepsTheRest) {
  const std::vector<double> hraw = {-50.0, 3.0, 10.0, 250.0, 0.0, 4000.0};
  const std::vector<std::uint8_t> mask = {0, 1, 1, 1, 0, 1};
  DepthOptions o;
  o.hmin_m = 10.0;
  const DepthResult r = roms_depth(hraw, mask, 3, 2, o);
  EXPECT_EQ(r.h, (std::vector<double>{10.0, 10.0, 10.0, 250.0, 10.0, 4000.0}));
  EXPECT_EQ(r.clipped, 3);      // -50, 3, 0
  EXPECT_EQ(r.clipped_wet, 1);  // 3
  EXPECT_EQ(r.sweeps, 0);
  EXPECT_DOUBLE_EQ(r.rx0_before, (4000.0 - 10.0) / 4010.0);  // the wet pair (2, 5); 3 and 5 are not neighbours
}

TEST(RomsDepth, SmoothingDeepensTheShelfToTheBoundAndNoMore) {
  // A 1-D step: 20 m shelf west of a 2000 m cliff, on a 12 x 3 wet grid.
  const int ni = 12, nj = 3;
  std::vector<double> hraw(static_cast<std::size_t>(ni * nj));
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) hraw[at(ni, i, j)] = i < 8 ? 20.0 : 2000.0;
  const std::vector<std::uint8_t> wet(hraw.size(), 1);
  DepthOptions o;
  o.hmin_m = 5.0;
  o.rmax = 0.2;
  const DepthResult r = roms_depth(hraw, wet, ni, nj, o);
  const double c = 0.8 / 1.2;
  EXPECT_GT(r.rx0_before, 0.9);
  EXPECT_LE(r.rx0_after, 0.2 + 1e-12);
  EXPECT_LE(max_r_factor(r.h, wet, ni, nj), 0.2 + 1e-12);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      // The least solution: 2000·c^(distance to the cliff), or the raw depth where that is deeper.
      const double expected = i < 8 ? std::max(20.0, 2000.0 * std::pow(c, 8 - i)) : 2000.0;
      EXPECT_NEAR(r.h[at(ni, i, j)], expected, 1e-9 * expected) << i << "," << j;
      EXPECT_GE(r.h[at(ni, i, j)], hraw[at(ni, i, j)]);
    }
  EXPECT_EQ(r.smoothed, 3 * 8);  // every shelf column: even i = 0 needs 2000·c^8 = 78 m > 20 m
  EXPECT_GT(r.max_deepening_m, 1000.0);
  EXPECT_GT(r.volume_added_rel, 0.0);
  EXPECT_GT(r.sweeps, 1);
}

TEST(RomsDepth, SmoothingIsMinimalAndLeavesLandAlone) {
  // Random-ish field with land; every deepened wet point must have a wet neighbour holding it
  // exactly at the bound (h = c·h_neighbour), else it could be shallower.
  const int ni = 17, nj = 13;
  std::vector<double> hraw(static_cast<std::size_t>(ni * nj));
  std::vector<std::uint8_t> mask(hraw.size(), 1);
  unsigned s = 12345;
  for (std::size_t k = 0; k < hraw.size(); ++k) {
    s = s * 1103515245u + 12345u;
    hraw[k] = 5.0 + static_cast<double>((s >> 8) % 3000);
    mask[k] = ((s >> 20) % 7 == 0) ? 0 : 1;
  }
  DepthOptions o;
  o.hmin_m = 10.0;
  o.rmax = 0.15;
  const DepthResult r = roms_depth(hraw, mask, ni, nj, o);
  const double c = 0.85 / 1.15;
  EXPECT_LE(r.rx0_after, 0.15 + 1e-12);
  EXPECT_GT(r.smoothed, 0);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const std::size_t k = at(ni, i, j);
      const double clipped = std::max(hraw[k], 10.0);
      if (mask[k] == 0) {
        EXPECT_EQ(r.h[k], clipped);
        continue;
      }
      ASSERT_GE(r.h[k], clipped);
      if (r.h[k] == clipped) continue;
      bool held = false;
      for (const auto& [di, dj] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        const int a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= ni || b >= nj || mask[at(ni, a, b)] == 0) continue;
        held = held || r.h[k] == c * r.h[at(ni, a, b)];
      }
      EXPECT_TRUE(held) << "point " << i << "," << j << " was deepened more than needed";
    }
  // Sweep order does not matter: the transposed problem gives the transposed answer.
  std::vector<double> ht(hraw.size());
  std::vector<std::uint8_t> mt(hraw.size());
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      ht[at(nj, j, i)] = hraw[at(ni, i, j)];
      mt[at(nj, j, i)] = mask[at(ni, i, j)];
    }
  const DepthResult rt = roms_depth(ht, mt, nj, ni, o);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) EXPECT_EQ(rt.h[at(nj, j, i)], r.h[at(ni, i, j)]);
}

// roms.hmin_m and roms.rmax are validated at load (tests/unit/config); out of range here is a bug.
TEST(RomsDepth, BadOptionsBreakThePreconditions) {
  const std::vector<double> h = {10.0, 20.0};
  const std::vector<std::uint8_t> m = {1, 1};
  DepthOptions o;
  o.hmin_m = 0.0;
  EXPECT_THROW(roms_depth(h, m, 2, 1, o), InternalError);
  o.hmin_m = 1.0;
  o.rmax = 1.0;
  EXPECT_THROW(roms_depth(h, m, 2, 1, o), InternalError);
  o.rmax = 0.0;
  EXPECT_THROW(roms_depth(h, m, 3, 1, o), InternalError);
  EXPECT_THROW(roms_depth({10.0, std::nan("")}, m, 2, 1, o), InternalError);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_roms_depth_test

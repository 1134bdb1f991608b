// SPDX-License-Identifier: GPL-3.0-or-later
// Model-ready ROMS depths by default: a regional config without roms.rmax smooths a steep
// synthetic basin to rx0 <= 0.2, and rx1 (on the reference vertical grid) drops with it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "config/regional.hpp"
#include "curvilinear/common/roms_depth.hpp"
#include "support/temp_dir.hpp"

namespace unit_app_model_ready_test {

namespace {

TEST(ModelReady, DefaultRmaxSmoothsASteepBasinToRx0OfAtMostPointTwo) {
  aq::testing::TempDir dir;
  const auto cfg = dir / "r.toml";
  {
    std::ofstream f(cfg);
    f << "[regional]\nname = \"x\"\n";
  }
  const auto loaded = aq::config::load_regional(cfg.string(), {});
  EXPECT_EQ(loaded.options.roms.rmax, 0.2);

  // A basin 4000 m deep with a 20 m shelf one cell away: rx0 = 0.99 before smoothing.
  const int ni = 30, nj = 20;
  std::vector<double> hraw(static_cast<std::size_t>(ni * nj));
  std::vector<std::uint8_t> mask(hraw.size(), 1);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) hraw[static_cast<std::size_t>(j * ni + i)] = (i > 8 && i < 22 && j > 5) ? 4000.0 : 20.0;
  aq::curvilinear::DepthOptions o;
  o.hmin_m = loaded.options.roms.hmin_m;
  o.rmax = loaded.options.roms.rmax;
  const auto d = aq::curvilinear::roms_depth(hraw, mask, ni, nj, o);
  EXPECT_GT(d.rx0_before, 0.98);
  EXPECT_LE(d.rx0_after, 0.2 + 1e-12);
  EXPECT_GT(d.rx1_before, 10.0);
  EXPECT_LT(d.rx1_after, d.rx1_before / 2.0);
  EXPECT_NEAR(aq::curvilinear::max_r_factor(d.h, mask, ni, nj), d.rx0_after, 1e-15);
}

TEST(ModelReady, Rx1IsZeroOnAFlatBottomAndGrowsWithTheStep) {
  const int ni = 4, nj = 3;
  std::vector<std::uint8_t> mask(12, 1);
  std::vector<double> flat(12, 500.0), step(12, 500.0);
  EXPECT_EQ(aq::curvilinear::max_rx1(flat, mask, ni, nj), 0.0);
  for (int j = 0; j < nj; ++j) step[static_cast<std::size_t>(j * ni + 3)] = 600.0;
  const double r1 = aq::curvilinear::max_rx1(step, mask, ni, nj);
  for (int j = 0; j < nj; ++j) step[static_cast<std::size_t>(j * ni + 3)] = 1000.0;
  const double r2 = aq::curvilinear::max_rx1(step, mask, ni, nj);
  EXPECT_GT(r1, 0.0);
  EXPECT_GT(r2, r1);
  // Land faces do not count.
  for (int j = 0; j < nj; ++j) mask[static_cast<std::size_t>(j * ni + 3)] = 0;
  EXPECT_EQ(aq::curvilinear::max_rx1(step, mask, ni, nj), 0.0);
}

}  // namespace

}  // namespace unit_app_model_ready_test

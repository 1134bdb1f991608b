// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of 1-D equidistribution of boundary nodes (seed 004, digest B.2).
#include "curvilinear/elliptic/boundary_equidistribution.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aq::curvilinear::unit_curvilinear_boundary_equidistribution_test {
namespace {

TEST(Equidistribution, UnitWeightGivesEqualArcLength) {
  const ArcPolyline line({{0, 0}, {3, 0}, {3, 4}});  // length 7
  const auto s = equidistribute(line, 8, {});
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(s[static_cast<std::size_t>(k)], k, 1e-14);
  EXPECT_NEAR(line.at(4.0).x, 3.0, 1e-15);
  EXPECT_NEAR(line.at(4.0).y, 1.0, 1e-15);
}

TEST(Equidistribution, ProductOfStepAndWeightIsConstant) {
  std::vector<PlanePoint> pts;
  for (int k = 0; k <= 1000; ++k) pts.push_back({k / 1000.0, 0.0});
  const ArcPolyline line(pts);
  const ControlFunction w = ControlFunction::parse("1 + 9*x^2");
  const auto s = equidistribute(line, 41, w);
  double lo = 1e9, hi = 0.0;
  for (std::size_t k = 0; k + 1 < s.size(); ++k) {
    const double v = (s[k + 1] - s[k]) * w(0.5 * (s[k] + s[k + 1]), 0.0);
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  EXPECT_LT(hi / lo - 1.0, 1e-8);
  EXPECT_GT(s[1] - s[0], 5.0 * (s[40] - s[39]));  // denser where w is large
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_boundary_equidistribution_test

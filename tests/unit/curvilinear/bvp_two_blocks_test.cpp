// SPDX-License-Identifier: GPL-3.0-or-later
// Two blocks of the orthogonal-family method sharing an interface (seed 003 multi-block; digest
// orthogonal_bvp_and_elliptic.md A.9): seed 003's channel cut at x = 1 by a straight interface;
// grid lines continuous (C0 to round-off) and smooth (C1: a small kink, shrinking with h) across it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "curvilinear/bvp/bvp_two_blocks.hpp"
#include "curvilinear/bvp/transfinite_interpolation.hpp"

namespace aq::curvilinear::unit_curvilinear_bvp_two_blocks_test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kCut = 1.0;  // both walls are horizontal there: the interface meets them at 90°

double bottom(double x) { return 0.25 * (1.0 - std::cos(kPi * x)); }
// Not symmetric about the cut (so B's derived levels differ from A's), horizontal at x = 0, 1, 2.
double top(double x) {
  const double s = std::sin(kPi * x);
  return 1.0 + 0.15 * (1.0 - std::cos(kPi * x)) + 0.1 * x * s * s;
}

SurfaceGrid block(double x0, double x1, int nx, int ny) {
  std::vector<Vec3> s, e, n, w;
  for (int i = 0; i < nx; ++i) {
    const double x = x0 + (x1 - x0) * i / (nx - 1);
    s.push_back({x, bottom(x), 0.0});
    n.push_back({x, top(x), 0.0});
  }
  for (int j = 0; j < ny; ++j) {
    const double v = static_cast<double>(j) / (ny - 1);
    w.push_back({x0, bottom(x0) + v * (top(x0) - bottom(x0)), 0.0});
    e.push_back({x1, bottom(x1) + v * (top(x1) - bottom(x1)), 0.0});
  }
  return transfinite_interpolation(s, e, n, w);
}

std::function<void(SurfaceGrid&)> projector(double x0, double x1) {
  return [x0, x1](SurfaceGrid& g) {
    for (int i = 0; i < g.nx_pts; ++i) {
      g(i, 0).y = bottom(g(i, 0).x);
      g(i, g.ny_pts - 1).y = top(g(i, g.ny_pts - 1).x);
    }
    for (int j = 0; j < g.ny_pts; ++j) {
      g(0, j).x = x0;
      g(g.nx_pts - 1, j).x = x1;
    }
  };
}

TwoBlockResult run(int n, int max_iterations = 3) {
  BvpOptions o;
  o.theta_levels = graded_levels(n);
  o.eta_levels = graded_levels(n);
  o.max_iterations = max_iterations;
  o.project = projector(0.0, kCut);
  return orthogonal_bvp_two_blocks(block(0.0, kCut, n + 1, n + 1), block(kCut, 2.0, 2 * n + 1, n + 1), o,
                                   graded_levels(2 * n), projector(kCut, 2.0));
}

TEST(BvpTwoBlocks, LinesAreContinuousAndSmoothAcrossTheInterface) {
  double kink_prev = 0.0;
  for (int n : {16, 32}) {
    const TwoBlockResult r = run(n);
    std::printf("two blocks n = %d: kink %.3e rad, f_max %.3e -> %.3e, f_avg %.3e -> %.3e\n", n, r.max_kink,
                r.f_max.front(), r.f_max.back(), r.f_avg.front(), r.f_avg.back());
    for (int q = 0; q <= n; ++q) {
      EXPECT_EQ(r.a(n, q).x, r.b(0, q).x);
      EXPECT_EQ(r.a(n, q).y, r.b(0, q).y);
    }
    // B's levels are not uniform: the interface nodes come from A.
    double dev = 0.0;
    for (int q = 0; q <= n; ++q)
      dev = std::max(dev, std::fabs(r.eta_levels_b[static_cast<std::size_t>(q)] - q / double(n)));
    EXPECT_GT(dev, 1e-3);
    // The angle between consecutive segments of a smooth line is O(h·curvature): C1 lines give a
    // kink that halves with h, C0-only lines one that stays O(1).
    EXPECT_LT(r.max_kink, 0.1);
    EXPECT_LT(r.f_avg.back(), 0.1 * r.f_avg.front());
    if (kink_prev > 0.0) {
      EXPECT_LT(r.max_kink, 0.6 * kink_prev);
    }
    kink_prev = r.max_kink;
  }
}

TEST(BvpTwoBlocks, OuterIterationsStopWhenFmaxAndFavgLevelOff) {
  // Digest A.8 for the pair: stop at the first k >= min_iterations (2) where f_max and f_avg over
  // both blocks changed by at most level_off (1 %) relative; the same grids as a run capped there.
  const TwoBlockResult r = run(16, 20);
  ASSERT_EQ(r.f_max.size(), static_cast<std::size_t>(r.iterations) + 1);
  EXPECT_GE(r.iterations, 2);
  EXPECT_LT(r.iterations, 20);
  const auto rel = [](const std::vector<double>& f, int k) {
    return std::fabs(f[static_cast<std::size_t>(k)] - f[static_cast<std::size_t>(k) - 1]) /
           std::max(std::fabs(f[static_cast<std::size_t>(k)]), std::fabs(f[static_cast<std::size_t>(k) - 1]));
  };
  EXPECT_LE(rel(r.f_max, r.iterations), 1e-2);
  EXPECT_LE(rel(r.f_avg, r.iterations), 1e-2);
  for (int k = 2; k < r.iterations; ++k) EXPECT_TRUE(rel(r.f_max, k) > 1e-2 || rel(r.f_avg, k) > 1e-2) << k;
  const TwoBlockResult capped = run(16, r.iterations);
  EXPECT_EQ(capped.iterations, r.iterations);
  EXPECT_EQ(capped.b(5, 7).x, r.b(5, 7).x);
  EXPECT_EQ(capped.b(5, 7).y, r.b(5, 7).y);
  std::printf("two blocks n = 16: stopped after %d outer iterations, f_max %.3e, f_avg %.3e\n", r.iterations,
              r.f_max.back(), r.f_avg.back());
  BvpOptions bad;
  bad.theta_levels = bad.eta_levels = graded_levels(4);
  bad.max_iterations = 0;
  EXPECT_THROW(orthogonal_bvp_two_blocks(block(0.0, kCut, 5, 5), block(kCut, 2.0, 9, 5), bad, graded_levels(8)),
               InternalError);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_bvp_two_blocks_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Test domains of seed 004 (digest orthogonal_bvp_and_elliptic.md B.8) as boundary-only grids:
// the swan and the B.8 Laplace-test domain, each side a dense polyline with nodes by 1-D
// equidistribution of w; and a uniform rectangle grid.
#pragma once

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/elliptic/boundary_equidistribution.hpp"
#include "support/uniform_grid.hpp"

namespace aq::curvilinear::test {

/// Boundary of an L × M grid from the four sides as parametric curves on t ∈ [0, 1] in the grid's
/// positive directions (south, north: west → east; east, west: south → north).
inline Grid2D boundary_grid(int L, int M, const std::function<PlanePoint(double)>& south,
                            const std::function<PlanePoint(double)>& east,
                            const std::function<PlanePoint(double)>& north,
                            const std::function<PlanePoint(double)>& west, const ControlFunction& w = {}) {
  Grid2D g(L, M);
  const auto side = [&](const std::function<PlanePoint(double)>& f, int n) {
    std::vector<PlanePoint> pts(2001);
    for (std::size_t k = 0; k < pts.size(); ++k) pts[k] = f(static_cast<double>(k) / 2000.0);
    return equidistributed_points(ArcPolyline(pts), n, w);
  };
  const auto s = side(south, L), n = side(north, L), e = side(east, M), wv = side(west, M);
  for (int i = 0; i < L; ++i) {
    g.x[g.at(i, 0)] = s[static_cast<std::size_t>(i)].x, g.y[g.at(i, 0)] = s[static_cast<std::size_t>(i)].y;
    g.x[g.at(i, M - 1)] = n[static_cast<std::size_t>(i)].x, g.y[g.at(i, M - 1)] = n[static_cast<std::size_t>(i)].y;
  }
  for (int j = 0; j < M; ++j) {
    g.x[g.at(0, j)] = wv[static_cast<std::size_t>(j)].x, g.y[g.at(0, j)] = wv[static_cast<std::size_t>(j)].y;
    g.x[g.at(L - 1, j)] = e[static_cast<std::size_t>(j)].x, g.y[g.at(L - 1, j)] = e[static_cast<std::size_t>(j)].y;
  }
  return g;
}

/// The swan (B.8 case 3): left x = 0, bottom y = 0, right x = 1 + 2y − 2y², top y = 1 − 3x + 3x².
inline Grid2D swan_boundary(int L, int M) {
  return boundary_grid(
      L, M,
      [](double t) {
        return PlanePoint{t, 0.0};
      },
      [](double t) {
        return PlanePoint{1.0 + 2.0 * t - 2.0 * t * t, t};
      },
      [](double t) {
        return PlanePoint{t, 1.0 - 3.0 * t + 3.0 * t * t};
      },
      [](double t) {
        return PlanePoint{0.0, t};
      });
}

/// B.8 case 4: 0 ≤ x ≤ 1, −1 ≤ y ≤ η(x) = −a cos(2πx).
inline Grid2D wavy_channel_boundary(int L, int M, double a, const ControlFunction& w = {}) {
  const auto eta = [a](double x) { return -a * std::cos(2.0 * std::numbers::pi * x); };
  return boundary_grid(
      L, M,
      [](double t) {
        return PlanePoint{t, -1.0};
      },
      [&](double t) {
        return PlanePoint{1.0, -1.0 + t * (eta(1.0) + 1.0)};
      },
      [&](double t) {
        return PlanePoint{t, eta(t)};
      },
      [&](double t) {
        return PlanePoint{0.0, -1.0 + t * (eta(0.0) + 1.0)};
      },
      w);
}

/// Uniform W × H rectangle grid with L × M nodes, SW corner at the origin.
inline Grid2D rectangle(int L, int M, double W, double H) { return aq::testing::uniform_grid(L, M, 0.0, W, 0.0, H); }

}  // namespace aq::curvilinear::test

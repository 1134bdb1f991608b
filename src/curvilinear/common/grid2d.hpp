// SPDX-License-Identifier: GPL-3.0-or-later
// A logically rectangular planar grid: the izogrid "supergrid" of (2nx+1) x (2ny+1) points.
// Index convention (row-major, eta rows):
//
//     j = ny_pts-1  +-----------------+   north side
//                   |                 |
//   west side       |   (i, j)        |   east side
//                   |                 |
//     j = 0         +-----------------+   south side
//                 i = 0           i = nx_pts-1
//
// point (i, j) is at index j * nx_pts + i. Coordinates are in the projection plane (metres or
// the projection's units); the contour runs counter-clockwise from the SW corner (0, 0).
#pragma once

#include <cstddef>
#include <vector>

#include "curvilinear/common/plane_point.hpp"

namespace aq::curvilinear {

struct Grid2D {
  int nx_pts = 0;  ///< points along xi (i)
  int ny_pts = 0;  ///< points along eta (j)
  std::vector<double> x, y;

  Grid2D() = default;
  Grid2D(int nx, int ny) : nx_pts(nx), ny_pts(ny), x(static_cast<std::size_t>(nx) * ny, 0.0), y(x.size(), 0.0) {}
  [[nodiscard]] std::size_t at(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_pts) + static_cast<std::size_t>(i);
  }
};

/// The boundary of `g` as a polyline counter-clockwise from the SW corner back to it
/// (2(nx_pts−1) + 2(ny_pts−1) + 1 points, the SW corner first and last).
inline std::vector<PlanePoint> grid_outline(const Grid2D& g) {
  std::vector<PlanePoint> out;
  const auto add = [&](int i, int j) { out.push_back({g.x[g.at(i, j)], g.y[g.at(i, j)]}); };
  for (int i = 0; i < g.nx_pts - 1; ++i) add(i, 0);
  for (int j = 0; j < g.ny_pts - 1; ++j) add(g.nx_pts - 1, j);
  for (int i = g.nx_pts - 1; i > 0; --i) add(i, g.ny_pts - 1);
  for (int j = g.ny_pts - 1; j >= 0; --j) add(0, j);
  return out;
}

}  // namespace aq::curvilinear

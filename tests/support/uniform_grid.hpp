// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: the uniform planar grids the curvilinear, grid-file and hand-off tests build (the
// one builder; a test that wants curved lines maps its points afterwards).
#pragma once

#include "curvilinear/common/grid2d.hpp"

namespace aq::testing {

/// nx_pts × ny_pts points, equally spaced over [x0, x1] × [y0, y1]: point (i, j) at
/// x0 + (x1 − x0)·i/(nx_pts − 1), y0 + (y1 − y0)·j/(ny_pts − 1). nx_pts, ny_pts >= 2.
inline curvilinear::Grid2D uniform_grid(int nx_pts, int ny_pts, double x0, double x1, double y0, double y1) {
  curvilinear::Grid2D g(nx_pts, ny_pts);
  for (int j = 0; j < ny_pts; ++j)
    for (int i = 0; i < nx_pts; ++i) {
      g.x[g.at(i, j)] = x0 + (x1 - x0) * i / (nx_pts - 1);
      g.y[g.at(i, j)] = y0 + (y1 - y0) * j / (ny_pts - 1);
    }
  return g;
}

/// The (2L+1) × (2M+1) supergrid of L × M cells over [−w, w] × [−h, h] (plane units).
inline curvilinear::Grid2D uniform_supergrid(int L, int M, double w, double h) {
  return uniform_grid(2 * L + 1, 2 * M + 1, -w, w, -h, h);
}

}  // namespace aq::testing

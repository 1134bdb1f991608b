// SPDX-License-Identifier: GPL-3.0-or-later
// f_max, f_avg of seed 003; see surface_orthogonality.hpp.
#include "curvilinear/bvp/surface_orthogonality.hpp"

#include <algorithm>
#include <cmath>

namespace aq::curvilinear {

SurfaceOrthogonality surface_orthogonality(const SurfaceGrid& g) {
  SurfaceOrthogonality out;
  double area = 0.0, sum = 0.0;
  for (int j = 0; j + 1 < g.ny_pts; ++j) {
    for (int i = 0; i + 1 < g.nx_pts; ++i) {
      const Vec3 p1 = g(i, j), p2 = g(i + 1, j), p3 = g(i + 1, j + 1), p4 = g(i, j + 1);
      const Vec3 n = cross(p3 - p1, p4 - p2);
      const double s2 = norm(n);
      if (!(s2 > 0.0)) continue;
      const Vec3 u = (1.0 / s2) * n;
      Vec3 a = (p2 - p1) + (p3 - p4), b = (p4 - p1) + (p3 - p2);
      a = a - dot(a, u) * u;
      b = b - dot(b, u) * u;
      const double la = norm(a), lb = norm(b);
      if (!(la > 0.0) || !(lb > 0.0)) continue;
      const double c = dot(a, b) / (la * lb);
      out.f_max = std::max(out.f_max, std::fabs(c));
      area += 0.5 * s2;
      sum += 0.5 * s2 * c * c;
    }
  }
  out.f_avg = area > 0.0 ? std::sqrt(sum / area) : 0.0;
  return out;
}

}  // namespace aq::curvilinear

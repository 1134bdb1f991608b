// SPDX-License-Identifier: GPL-3.0-or-later
// Triangles on the unit sphere (see sphere_geometry.hpp).
#include "mesh/sphere_geometry.hpp"

#include <cmath>

#include "core/sphere_vectors.hpp"
#include "core/types.hpp"

namespace aq::mesh {

namespace {

using Vec3 = sphere::Vec3;
using sphere::cross;
using sphere::dot;

}  // namespace

Vec3 unit_vector_deg(double lon_deg, double lat_deg) { return sphere::unit_deg(lon_deg, lat_deg); }

double spherical_triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double det = dot(a, cross(b, c));
  const double den = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
  return 2.0 * std::atan2(det, den);
}

std::array<double, 3> spherical_angles_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    // Between the great circles p->q and p->r: their tangent directions at p.
    const Vec3 tq = cross(cross(p, q), p), tr = cross(cross(p, r), p);
    return std::atan2(std::sqrt(dot(cross(tq, tr), cross(tq, tr))), dot(tq, tr)) * kRadToDeg;
  };
  return {angle(a, b, c), angle(b, c, a), angle(c, a, b)};
}

}  // namespace aq::mesh

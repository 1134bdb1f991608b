// SPDX-License-Identifier: GPL-3.0-or-later
// Points of the unit sphere as 3-vectors, and the few products the geometry on it needs: one
// definition for the stages that draw great-circle arcs (mask's passage carving, raster's
// elevation edits) and the mesh's spherical triangles.
#pragma once

#include <array>
#include <cmath>

#include "core/types.hpp"

namespace aq::sphere {

using Vec3 = std::array<double, 3>;

/// The unit vector of (lon, lat) in degrees: x towards (0°, 0°), y towards (90°E, 0°), z north.
inline Vec3 unit_deg(double lon_deg, double lat_deg) {
  const double lo = lon_deg * kDegToRad, la = lat_deg * kDegToRad;
  return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
}
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

}  // namespace aq::sphere

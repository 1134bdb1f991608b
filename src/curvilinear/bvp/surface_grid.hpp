// SPDX-License-Identifier: GPL-3.0-or-later
// A logically rectangular grid of points in R^3: the reference and result grids of the
// orthogonal-family method (seed 003; digest orthogonal_bvp_and_elliptic.md A.2, A.4), planar
// (z = 0, plane units) or on a surface (the unit sphere). Same index convention as Grid2D
// (grid2d.hpp): point (i, j) at j·nx_pts + i, i along ξ (west -> east), j along η (south -> north).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace aq::curvilinear {

/// Point or vector of R^3.
struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
/// a + t (b − a).
inline Vec3 lerp(Vec3 a, Vec3 b, double t) { return a + t * (b - a); }

struct SurfaceGrid {
  int nx_pts = 0;  ///< points along ξ (i)
  int ny_pts = 0;  ///< points along η (j)
  std::vector<Vec3> p;

  SurfaceGrid() = default;
  SurfaceGrid(int nx, int ny)
      : nx_pts(nx), ny_pts(ny), p(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)) {}
  [[nodiscard]] std::size_t at(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_pts) + static_cast<std::size_t>(i);
  }
  [[nodiscard]] Vec3 operator()(int i, int j) const { return p[at(i, j)]; }
  Vec3& operator()(int i, int j) { return p[at(i, j)]; }
};

}  // namespace aq::curvilinear

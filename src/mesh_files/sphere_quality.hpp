// SPDX-License-Identifier: GPL-3.0-or-later
// Shape quality of a triangle mesh on the sphere (issue 12): the figures finite-element ocean
// models take their time step and accuracy from, computed for the triangles as written to the
// geographic files (mesh_files/geographic_mesh.hpp: after the pole cap), from the nodes' lon/lat
// only, so they hold for any lattice.
//
// Per triangle (unit sphere, great-circle edges):
//   min angle        smallest of the three angles between the great circles at the vertices
//                    (those of spherical_angles_deg), degrees; 60° for an equilateral triangle
//   max angle        largest of them, degrees (90° for a right-isosceles triangle). Very obtuse
//                    triangles (the lon–lat lattice's transition triangles near the poles reach
//                    171°) make the stiffness matrix of linear elements far from an M-matrix:
//                    FESOM2's SSH solver needed 26–60× the iterations on them
//   edge ratio       longest / shortest great-circle edge (≥ 1; √2 for a right-isosceles one)
//   neighbour ratio  max over the edge neighbours of larger / smaller spherical area (1 without
//                    neighbours; +inf next to a zero-area triangle)
//   size             mean great-circle edge length on the authalic sphere (6371.0072 km), km
//
// Summary: quantiles are exact order statistics, the value of rank ⌊q·(n−1)⌋ in ascending order
// (p0 = the minimum), found by a radix select over the floats' bit patterns (two histogram
// passes of 16 bits each). Histograms are integer counts made per thread and summed, so the
// result does not depend on the thread count; per-triangle values are computed independently.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/report.hpp"
#include "mesh/mesh.hpp"

namespace aq::io {

/// Per-triangle shape values, indexed like Mesh::triangles.
struct TriangleShapes {
  std::vector<float> min_angle_deg;
  std::vector<float> max_angle_deg;
  std::vector<float> edge_ratio;
  std::vector<float> neighbour_area_ratio;
  std::vector<float> size_km;
};

struct SphereQuality {
  std::int64_t triangles = 0;
  double min_angle_p0_deg = 0, min_angle_p1_deg = 0, min_angle_p5_deg = 0, min_angle_p50_deg = 0;
  double below_20_deg_percent = 0, below_30_deg_percent = 0;  ///< share of triangles with min angle < 20°, < 30°
  double max_angle_p50_deg = 0, max_angle_p99_deg = 0, max_angle_max_deg = 0;
  std::int64_t max_angle_above_120_deg = 0;  ///< triangles with an angle above 120°
  double edge_ratio_p50 = 0, edge_ratio_p99 = 0, edge_ratio_max = 0;
  double neighbour_area_ratio_p99 = 0, neighbour_area_ratio_max = 0;
  double size_p50_km = 0;

  /// The "quality" report section (angles to 0.01°, ratios to 1e-4, shares to 0.01 %).
  [[nodiscard]] Json json() const;
  /// One log line.
  [[nodiscard]] std::string describe() const;
};

/// Shape values of every triangle of `mesh` (parallel; bit-identical for any thread count).
/// Throws InternalError when a triangle names a node out of range.
TriangleShapes triangle_shapes(const mesh::Mesh& mesh);

/// Triangles with an angle above a threshold (spherical angles of the nodes' lon/lat).
struct ObtuseTriangles {
  std::int64_t count = 0;
  double max_angle_deg = 0.0;          ///< largest angle of any triangle
  double from_lattice_lat_deg = 90.0;  ///< smallest |lattice-system latitude| of a node of such a triangle
};
/// Counts the triangles of `mesh` with an angle above `threshold_deg`; their latitude is that of
/// the lattice system (rlat_deg: rotated with a rotated pole).
ObtuseTriangles obtuse_triangles(const mesh::Mesh& mesh, double threshold_deg);

/// The summary of `shapes` (all zero for no triangles).
SphereQuality summarize_quality(const TriangleShapes& shapes);

/// Value of rank ⌊q·(n−1)⌋ of `values` (non-negative, NaN-free) in ascending order, q in [0, 1];
/// exact, without sorting. Throws InternalError on an empty vector.
float order_statistic(const std::vector<float>& values, double q);
/// The same for several q at once (two passes over the values in all).
std::vector<float> order_statistics(const std::vector<float>& values, const std::vector<double>& qs);

}  // namespace aq::io

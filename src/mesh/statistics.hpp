// SPDX-License-Identifier: GPL-3.0-or-later
// Quality facts and physical sizes of a triangle mesh (seed 002: "сгущение сетки подобными
// треугольными элементами с коэффициентами подобия (√2)^-k"; ARCHITECTURE §4.6):
//
//  * topology: every interior edge in exactly 2 triangles with opposite directions (consistent
//    orientation, conformity), every boundary edge in 1, and the triangle boundary equals
//    Mesh::boundary_edges; Euler V − E + F = 2c − b − p, with c the edge-connected components
//    (1 for a K-cursor fill, giving the 2 − b − p of the specification), b boundary loops and p
//    pinch vertices (quadtree/nodes.hpp explains the left-turn rule that makes this hold);
//  * geometry in lattice units (exact integers): every triangle right isosceles and
//    anticlockwise, legs Δ0·(√2)^-k with k in 0..2L (the similarity classes), total triangle area
//    = filled area (pixels of the squares);
//  * on WGS84 with GeographicLib: element areas (m², geodesic triangles, PolygonArea) and edge
//    lengths (m, geodesic Inverse) with min/median/max per level, the total wet area in km², and
//    the filled area of the lattice cells (exact ellipsoidal lat/lon cells without rotation; cells
//    of the rotated lattice on WGS84 by quadrature of the ellipsoid's area density with rotation)
//    for comparison. The geodesic boundary edges do not follow the lattice parallels, so the two
//    areas differ by lenses along the boundary; the check accepts twice their bound
//    (StatisticsOptions::area_tolerance).
//
// A mesh of squares only (mesh.elements = "squares") is checked on its squares instead, as
// polygons through corners and midside nodes (topology, Euler, orientation and exact area in
// lattice units, geodesic areas; the right-isosceles and similarity checks are for triangles).
//
// Without rotation, areas and lengths depend only on the rows, not on λ, and are computed once per
// (level, row, template shape) and looked up; with rotation (and for square faces) each edge's
// geodesic is solved once (length and S12, the area between it and the equator) and an element's
// area is the sum of ±S12 over its edges, reduced as PolygonArea does (parallel, per edge/element).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/report.hpp"
#include "mesh/mesh.hpp"

namespace aq::mesh {

struct LevelStatistics {
  int level = 0;
  std::int64_t triangles = 0;
  double area_min_m2 = 0.0, area_median_m2 = 0.0, area_max_m2 = 0.0;  ///< median: lower middle value
  std::int64_t edges = 0;  ///< edges whose finest adjacent triangle has this level
  double edge_min_m = 0.0, edge_median_m = 0.0, edge_max_m = 0.0;
};

struct MeshStatistics {
  // Topology.
  std::int64_t nodes = 0, used_nodes = 0, triangles = 0, edges = 0, interior_edges = 0, boundary_edges = 0;
  std::int64_t boundary_loops = 0, pinch_nodes = 0, components = 0;
  std::int64_t euler = 0;              ///< V − E + F (V = nodes used by triangles)
  std::int64_t euler_expected = 0;     ///< 2c − b − p
  std::int64_t bad_edges = 0;          ///< edges in more than 2 triangles, or in 2 with the same direction
  std::int64_t boundary_mismatch = 0;  ///< edges in exactly one of {triangle boundary, Mesh::boundary_edges}
  // Geometry in lattice units.
  std::int64_t not_right_isosceles = 0;
  std::int64_t clockwise = 0;                ///< clockwise or degenerate triangles
  std::int64_t twice_triangle_area_px2 = 0;  ///< Σ 2·area, pixel² units
  std::int64_t filled_pixels = 0;            ///< Σ side² over the squares
  std::vector<std::int64_t> similarity;      ///< triangles per k (legs Δ0·(√2)^-k), k = 0..2L
  // On WGS84.
  bool geodesic = false;                  ///< the physical sizes below were computed
  double triangle_area_km2 = 0.0;         ///< Σ geodesic triangle (or square) areas: the total wet area
  double filled_area_km2 = 0.0;           ///< Σ lattice cell areas of the squares
  double area_relative_difference = 0.0;  ///< |triangle − filled| / filled
  double area_tolerance = 0.0;            ///< the tolerance used
  std::vector<LevelStatistics> levels;    ///< levels that have triangles
  /// The first non-finite value of each quantity (node coordinates and depths; with `geodesic`
  /// also cell rows, triangle areas, edge lengths and the totals), one message each, naming the
  /// element / node / row and its coordinates. Any entry fails the checks.
  std::vector<std::string> non_finite;

  /// Names of the failed checks (empty when the mesh passes all of them).
  [[nodiscard]] std::vector<std::string> failed_checks() const;
};

struct StatisticsOptions {
  bool geodesic = true;  ///< compute areas and lengths on WGS84 (GeographicLib)
  /// Accepted relative difference of the two areas on WGS84; 0 = automatic: twice the bound of
  /// the lenses between the boundary edges' geodesics and the lattice lines they stand for
  /// (statistics.cpp derives it; second order in the pixel size for a given coast).
  double area_tolerance = 0.0;
};

/// Min, lower median (rank ⌊(n − 1)/2⌋) and max of `v` (reorders it); zeros when empty.
std::array<double, 3> min_median_max(std::span<double> v);
/// The same for the multiset of values v[k].first, each v[k].second times (reorders v), and the
/// multiset's size n: what min_median_max gives for the values written out, in any order. nullopt
/// when a value is negative (−0 included) or not finite: then equal values could differ in their
/// bits (−0 and +0) or not compare at all (NaN), and only the values in their order tell.
std::optional<std::array<double, 3>> weighted_min_median_max(std::vector<std::pair<double, std::int64_t>>& v,
                                                             std::int64_t& n);

/// Statistics and checks of the triangles of `mesh` (a mesh without triangles gives zero counts
/// except nodes and filled area). Does not throw on a bad mesh: see failed_checks(). Throws
/// InternalError when node ids are out of range or there are 2^32 nodes or more.
MeshStatistics compute_statistics(const Mesh& mesh, const StatisticsOptions& options = {});

/// The "statistics" report section.
Json statistics_json(const MeshStatistics& s);

}  // namespace aq::mesh

// SPDX-License-Identifier: GPL-3.0-or-later
// The geographic mesh (io/geographic_mesh.hpp): a wet pole row becomes a pole cap (or, when the
// polar row is not all ocean, a merged pole node); no triangle of zero area on the sphere, no
// two nodes at one point, conforming, the same total area, the boundary without the polar loop.
#include "mesh_files/geographic_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "support/io_test_mesh.hpp"

namespace aq::io::unit_mesh_files_geographic_mesh_test {
namespace {

using testing::arctic_mesh;

const ElevationSampler kSampler = [](const std::vector<double>& lon, const std::vector<double>& lat,
                                     std::vector<double>& out) {
  out.resize(lon.size());
  for (std::size_t k = 0; k < lon.size(); ++k) out[k] = -1000.0 - lat[k];
};

struct Facts {
  std::int64_t duplicate_points = 0, tiny_triangles = 0, clockwise = 0, bad_edges = 0, boundary_mismatch = 0;
  double area = 0.0;
};

Facts facts(const mesh::Mesh& m) {
  Facts f;
  std::vector<std::array<double, 3>> v;
  for (NodeId n = 0; n < m.node_count(); ++n) v.push_back(unit_vector_deg(m.lon_deg[n], m.lat_deg[n]));
  std::set<std::tuple<long long, long long, long long>> points;
  for (const auto& p : v) {
    auto q = [](double x) { return std::llround(x * 1e10); };
    if (!points.insert({q(p[0]), q(p[1]), q(p[2])}).second) ++f.duplicate_points;
  }
  std::map<std::pair<NodeId, NodeId>, int> half;
  for (const auto& t : m.triangles) {
    const double a = spherical_triangle_area(v[t[0]], v[t[1]], v[t[2]]);
    if (std::abs(a) < 1e-12) ++f.tiny_triangles;
    if (a < 0.0) ++f.clockwise;
    f.area += a;
    for (int e = 0; e < 3; ++e) ++half[{t[e], t[(e + 1) % 3]}];
  }
  std::set<std::pair<NodeId, NodeId>> boundary;
  for (const auto& [e, k] : half) {
    if (k != 1) ++f.bad_edges;
    if (half.count({e.second, e.first}) == 0) boundary.insert(e);
  }
  std::set<std::pair<NodeId, NodeId>> declared;
  for (const auto& e : m.boundary_edges) declared.insert({e[0], e[1]});
  for (const auto& e : boundary) f.boundary_mismatch += declared.count(e) == 0 ? 1 : 0;
  for (const auto& e : declared) f.boundary_mismatch += boundary.count(e) == 0 ? 1 : 0;
  return f;
}

TEST(GeographicMesh, LatticeMeshHasTheDegeneratePoleRow) {
  // What the writers got before: the test would fail on it.
  const Facts f = facts(arctic_mesh());
  EXPECT_EQ(f.duplicate_points, 35);  // 36 nodes on φ = 90°, one point
  EXPECT_EQ(f.tiny_triangles, 36);    // one triangle per level-0 square with two of them
}

TEST(GeographicMesh, CapReplacesThePolarRow) {
  const mesh::Mesh lm = arctic_mesh();
  const GeographicMesh g(lm, ElementKinds::kTriangles, kSampler);
  ASSERT_TRUE(g.changed());
  ASSERT_EQ(g.poles().size(), 1U);
  const PoleChange& c = g.poles()[0];
  EXPECT_TRUE(c.north);
  EXPECT_EQ(c.method, PoleMethod::kCap);
  EXPECT_EQ(c.ring_lat_deg, 80.0);
  EXPECT_EQ(c.ring_nodes, 37);                 // 36 corners + the midside node at I = 21
  EXPECT_EQ(c.removed_triangles, 2 * 35 + 5);  // 35 plain level-0 squares + one with 5 triangles
  EXPECT_EQ(c.removed_nodes, 36 + 1);          // the pole row and the centre node
  EXPECT_GE(c.min_angle_deg, 30.0);
  EXPECT_LE(c.max_valence, 9);
  EXPECT_GE(c.island_nodes, 4);
  EXPECT_LE(c.island_nodes, 7);
  EXPECT_LE(c.area_relative_change, 1e-12);

  const mesh::Mesh& m = g.mesh();
  const Facts f = facts(m), fl = facts(lm);
  EXPECT_EQ(f.duplicate_points, 0);
  EXPECT_EQ(f.tiny_triangles, 0);
  EXPECT_EQ(f.clockwise, 0);
  EXPECT_EQ(f.bad_edges, 0);
  EXPECT_EQ(f.boundary_mismatch, 0);
  // Written area + the polar island = the lattice mesh's area.
  const double island_sr = c.island_area_km2 / (6371.0072 * 6371.0072);
  EXPECT_NEAR(f.area + island_sr, fl.area, 1e-12 * fl.area);
  EXPECT_GT(island_sr, 0.0);
  EXPECT_LT(island_sr, 0.02 * fl.area);
  EXPECT_EQ(m.node_count(), lm.node_count() - c.removed_nodes + c.added_nodes);
  EXPECT_EQ(m.triangle_count(), lm.triangle_count() - c.removed_triangles + c.added_triangles);
  // The polar loop is gone, the coast loop along 70°N is kept, the island's loop is new.
  ASSERT_EQ(m.loops.size(), lm.loops.size());
  for (const auto& l : m.loops) EXPECT_FALSE(l.pole);
  EXPECT_EQ(static_cast<std::int64_t>(m.loops.back().nodes.size()), c.island_nodes);
  EXPECT_FALSE(m.loops.back().outer);
  // New nodes: flagged, not lattice vertices, depth from the sampler, none on the pole.
  std::int64_t cap_nodes = 0;
  for (NodeId n = 0; n < m.node_count(); ++n) {
    if ((m.node_flags[n] & mesh::kNodeCap) == 0) continue;
    ++cap_nodes;
    EXPECT_EQ(m.node_i[n], -1);
    EXPECT_DOUBLE_EQ(m.depth_m[n], -1000.0 - m.lat_deg[n]);
    EXPECT_GT(m.lat_deg[n], 80.0);
    EXPECT_LE(m.lat_deg[n], 90.0 - c.island_radius_deg + 1e-9);
  }
  EXPECT_EQ(cap_nodes, c.added_nodes);
}

// The copy is the write stage's largest array set (2.1 GB at 15"): every node and triangle array
// is reserved for exactly what it holds. A capacity of the lattice mesh's counts, which the cap's
// nodes exceed, doubled every array at the first cap node.
TEST(GeographicMesh, CapArraysHoldNoSpareCapacity) {
  const mesh::Mesh lm = arctic_mesh();
  const GeographicMesh g(lm, ElementKinds::kTriangles, kSampler);
  ASSERT_TRUE(g.changed());
  const mesh::Mesh& m = g.mesh();
  ASSERT_GT(m.node_count(), 0);
  for (const auto* v : {&m.node_i, &m.node_j}) EXPECT_EQ(v->capacity(), v->size());
  for (const auto* v : {&m.lon_deg, &m.lat_deg, &m.rlon_deg, &m.rlat_deg, &m.depth_m})
    EXPECT_EQ(v->capacity(), v->size());
  EXPECT_EQ(m.node_flags.capacity(), m.node_flags.size());
  EXPECT_EQ(m.triangles.capacity(), m.triangles.size());
  EXPECT_EQ(m.triangle_level.capacity(), m.triangle_level.size());
  EXPECT_EQ(m.triangle_square.capacity(), m.triangle_square.size());
  EXPECT_EQ(g.source_triangle().capacity(), g.source_triangle().size());
}

TEST(GeographicMesh, RotatedLatticeCapsInTheLatticeFrame) {
  const Lattice lat = Lattice::make(10.0, 1, -180.0);
  std::vector<testing::LeafSpec> leaves;
  for (std::int64_t i = 0; i < lat.nx; i += 2) {
    leaves.push_back({0, i, 32});
    leaves.push_back({0, i, 34});
  }
  mesh::RotationInfo rot;
  rot.enabled = true;
  rot.pole_lon_deg = -44.858333;
  rot.pole_lat_deg = 78.141667;
  const mesh::Mesh lm = testing::make_leaf_mesh(lat, leaves, true, rot);
  const GeographicMesh g(lm, ElementKinds::kTriangles, kSampler);
  ASSERT_EQ(g.poles().size(), 1U);
  EXPECT_EQ(g.poles()[0].method, PoleMethod::kCap);
  const Facts f = facts(g.mesh()), fl = facts(lm);
  EXPECT_EQ(f.duplicate_points, 0);
  EXPECT_EQ(f.tiny_triangles, 0);
  EXPECT_EQ(f.clockwise, 0);
  EXPECT_EQ(f.bad_edges, 0);
  const double island_sr = g.poles()[0].island_area_km2 / (6371.0072 * 6371.0072);
  EXPECT_NEAR(f.area + island_sr, fl.area, 1e-11 * fl.area);
  // The island sits on the rotated pole: every node at least its radius away from it.
  const mesh::Mesh& m = g.mesh();
  const auto pole = unit_vector_deg(-44.858333, 78.141667);
  for (NodeId n = 0; n < m.node_count(); ++n) {
    const auto v = unit_vector_deg(m.lon_deg[n], m.lat_deg[n]);
    const double d = std::acos(std::min(1.0, v[0] * pole[0] + v[1] * pole[1] + v[2] * pole[2])) / kDegToRad;
    EXPECT_GE(d, g.poles()[0].island_radius_deg - 1e-9);
  }
}

TEST(GeographicMesh, PolarRowWithLandFallsBackToTheMerge) {
  const mesh::Mesh lm = arctic_mesh(false);
  const GeographicMesh g(lm, ElementKinds::kTriangles, kSampler);
  ASSERT_EQ(g.poles().size(), 1U);
  const PoleChange& c = g.poles()[0];
  EXPECT_EQ(c.method, PoleMethod::kMerge);
  EXPECT_NE(c.reason.find("not all ocean"), std::string::npos) << c.reason;
  EXPECT_EQ(c.removed_nodes, 35);  // the 36 pole-row nodes (the land square leaves no gap) into one
  EXPECT_EQ(c.removed_triangles, 35);
  const Facts f = facts(g.mesh());
  EXPECT_EQ(f.duplicate_points, 0);
  EXPECT_EQ(f.tiny_triangles, 0);
  EXPECT_EQ(f.clockwise, 0);
  EXPECT_EQ(f.boundary_mismatch, 0);
  EXPECT_NEAR(f.area, facts(lm).area, 1e-12 * f.area);
}

// Squares (mesh.elements = squares or both): the pole row is merged; no two nodes at one point,
// every square polygon keeps >= 3 distinct nodes and positive area on the sphere, the area is
// the lattice mesh's, and "both" keeps its triangles consistent with their squares.
TEST(GeographicMesh, SquaresMergeThePoleRow) {
  const mesh::Mesh lm = arctic_mesh();
  ASSERT_FALSE(lm.squares.empty());
  for (const ElementKinds kinds : {ElementKinds::kSquares, ElementKinds::kBoth}) {
    const GeographicMesh g(lm, kinds, kSampler);
    ASSERT_TRUE(g.changed());
    ASSERT_EQ(g.poles().size(), 1U);
    EXPECT_EQ(g.poles()[0].method, PoleMethod::kMerge);
    EXPECT_NE(g.poles()[0].reason.find("squares"), std::string::npos) << g.poles()[0].reason;
    EXPECT_EQ(g.poles()[0].removed_nodes, 35);
    const mesh::Mesh& m = g.mesh();
    ASSERT_EQ(m.squares.size(), lm.squares.size());
    ASSERT_EQ(m.square_midside.size(), lm.square_midside.size());
    const Facts f = facts(m);
    EXPECT_EQ(f.duplicate_points, 0);
    EXPECT_EQ(f.tiny_triangles, 0);
    EXPECT_EQ(f.clockwise, 0);
    std::vector<std::array<double, 3>> v;
    for (NodeId n = 0; n < m.node_count(); ++n) v.push_back(unit_vector_deg(m.lon_deg[n], m.lat_deg[n]));
    double squares_area = 0.0;
    int three_node_squares = 0;
    for (ElementId s = 0; s < m.square_count(); ++s) {
      std::array<NodeId, kMaxSquarePolygon> p{};
      const int k = square_polygon(m, s, p);
      ASSERT_GE(k, 3) << "square " << s;
      three_node_squares += k == 3 ? 1 : 0;
      double a = 0.0;  // fan from the first node
      for (int e = 1; e + 1 < k; ++e) a += spherical_triangle_area(v[p[0]], v[p[e]], v[p[e + 1]]);
      EXPECT_GT(a, 1e-6) << "square " << s;
      squares_area += a;
      for (int e = 0; e < k; ++e) EXPECT_NE(p[e], p[(e + 1) % k]) << "square " << s;
    }
    // The 36 level-0 squares on the 80–90°N row, but for the one above the split square, whose
    // south side has a hanging node (4 nodes).
    EXPECT_EQ(three_node_squares, 35);
    EXPECT_NEAR(squares_area, facts(lm).area, 1e-12 * squares_area);
    if (kinds == ElementKinds::kBoth) {
      EXPECT_EQ(m.triangles.size() + 36, lm.triangles.size());  // one degenerate triangle per polar square
      for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        const auto& sq = m.squares[static_cast<std::size_t>(m.triangle_square[t])];
        for (const NodeId n : m.triangles[t]) {
          const double lat_sq = m.lat_deg[sq[0]];
          EXPECT_GE(m.lat_deg[n], lat_sq - 1e-9) << "triangle " << t << " outside its square";
        }
      }
    }
  }
}

TEST(GeographicMesh, MeshesWithoutPoleRowsAreUnchanged) {
  const Lattice lat = Lattice::make(10.0, 1, -180.0);
  const mesh::Mesh no_pole = testing::make_leaf_mesh(lat, {{0, 0, 20}, {0, 2, 20}});
  const GeographicMesh g(no_pole, ElementKinds::kTriangles, kSampler);
  EXPECT_FALSE(g.changed());
  EXPECT_TRUE(g.poles().empty());
  EXPECT_EQ(&g.mesh(), &no_pole);
}

TEST(GeographicMesh, SphericalHelpers) {
  const auto a = unit_vector_deg(0, 0), b = unit_vector_deg(90, 0), c = unit_vector_deg(0, 90);
  EXPECT_NEAR(spherical_triangle_area(a, b, c), kPi / 2.0, 1e-15);
  EXPECT_NEAR(spherical_triangle_area(a, c, b), -kPi / 2.0, 1e-15);
  for (const double ang : spherical_angles_deg(a, b, c)) EXPECT_NEAR(ang, 90.0, 1e-12);
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_geographic_mesh_test

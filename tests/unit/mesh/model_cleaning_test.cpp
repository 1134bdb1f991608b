// SPDX-License-Identifier: GPL-3.0-or-later
// Cleaning for the models (mesh/model_cleaning.hpp) on synthetic coasts drawn as squares, each
// square either the 4-triangle cross template (S, E, N, W round a centre node; every triangle
// has two neighbours inside its square) or a hand-placed triangle:
//
//   one neighbour           pinch                    pinch whose removal leaves
//                                                    triangles with one neighbour
//   y=1  X X                y=2  X X X X             y=2  X X X X
//   y=0  X X                y=1  X . X X             y=1  X . X .
//        ^ T hangs on the   y=0  X X . .             y=0  X X . .
//          bottom edge           pinch at (2, 1)          pinch at (2, 1)
//
// The counts are checked exactly, and the result against an independent count of the defects.
#include "mesh/model_cleaning.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace aq::mesh::unit_mesh_model_cleaning_test {
namespace {

// Nodes at doubled integer coordinates (centres at odd ones), numbered by (y, x) on first use.
struct Builder {
  std::map<std::pair<int, int>, NodeId> ids;
  std::vector<std::array<std::pair<int, int>, 3>> tris;

  void triangle(std::pair<int, int> a, std::pair<int, int> b, std::pair<int, int> c) { tris.push_back({a, b, c}); }
  void cross(int x, int y) {  // the square [x, x+1] × [y, y+1], S, E, N, W (anticlockwise)
    const std::pair<int, int> sw{2 * x, 2 * y}, se{2 * x + 2, 2 * y}, ne{2 * x + 2, 2 * y + 2}, nw{2 * x, 2 * y + 2},
        c{2 * x + 1, 2 * y + 1};
    triangle(sw, se, c);
    triangle(se, ne, c);
    triangle(ne, nw, c);
    triangle(nw, sw, c);
  }
  Mesh mesh() {
    std::set<std::pair<int, int>> by_yx;
    for (const auto& t : tris)
      for (const auto& p : t) by_yx.insert({p.second, p.first});
    Mesh m;
    for (const auto& [y, x] : by_yx) {
      ids[{x, y}] = m.node_count();
      m.node_i.push_back(x);
      m.node_j.push_back(y);
      m.lon_deg.push_back(0.5 * x);
      m.lat_deg.push_back(0.5 * y);
      m.rlon_deg.push_back(0.5 * x);
      m.rlat_deg.push_back(0.5 * y);
      m.depth_m.push_back(-100.0);
      m.node_flags.push_back(0);
    }
    for (const auto& t : tris) {
      m.triangles.push_back({ids[t[0]], ids[t[1]], ids[t[2]]});
      m.triangle_level.push_back(0);
      m.triangle_square.push_back(-1);
    }
    return m;
  }
};

Mesh squares_mesh(const std::vector<std::string>& rows_top_down) {
  Builder b;
  const auto ny = static_cast<int>(rows_top_down.size());
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < static_cast<int>(rows_top_down[static_cast<std::size_t>(ny - 1 - y)].size()); ++x)
      if (rows_top_down[static_cast<std::size_t>(ny - 1 - y)][static_cast<std::size_t>(x)] == 'X') b.cross(x, y);
  return b.mesh();
}

// Independent count: triangles with < 2 edge neighbours, and nodes with more than two boundary
// edges (a node whose triangles form k fans has 2k of them).
std::pair<int, int> defects(const Mesh& m) {
  std::map<std::pair<NodeId, NodeId>, int> edge_count;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) ++edge_count[std::minmax(t[e], t[(e + 1) % 3])];
  int lonely = 0;
  std::map<NodeId, int> boundary_at;
  for (const auto& t : m.triangles) {
    int n = 0;
    for (int e = 0; e < 3; ++e) n += edge_count[std::minmax(t[e], t[(e + 1) % 3])] > 1 ? 1 : 0;
    lonely += n < 2 ? 1 : 0;
  }
  for (const auto& [e, c] : edge_count)
    if (c == 1) {
      ++boundary_at[e.first];
      ++boundary_at[e.second];
    }
  int pinches = 0;
  for (const auto& [v, c] : boundary_at) pinches += c > 2 ? 1 : 0;
  return {lonely, pinches};
}

// Every boundary edge is in exactly one loop, in the direction of its triangle (wet on the left),
// and the loops list their edges.
void expect_loops_match(const Mesh& m) {
  std::set<std::pair<NodeId, NodeId>> directed, boundary;
  std::map<std::pair<NodeId, NodeId>, int> edge_count;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) {
      directed.insert({t[e], t[(e + 1) % 3]});
      ++edge_count[std::minmax(t[e], t[(e + 1) % 3])];
    }
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e)
      if (edge_count[std::minmax(t[e], t[(e + 1) % 3])] == 1) boundary.insert({t[e], t[(e + 1) % 3]});
  std::set<std::pair<NodeId, NodeId>> in_loops;
  for (const auto& loop : m.loops)
    for (std::size_t k = 0; k < loop.nodes.size(); ++k)
      EXPECT_TRUE(in_loops.insert({loop.nodes[k], loop.nodes[(k + 1) % loop.nodes.size()]}).second);
  EXPECT_EQ(in_loops, boundary);
  EXPECT_EQ(m.boundary_edges.size(), boundary.size());
  for (std::size_t n = 0; n < m.node_flags.size(); ++n) {
    bool on = false;
    for (const auto& e : boundary) on = on || e.first == static_cast<NodeId>(n);
    EXPECT_EQ((m.node_flags[n] & kNodeBoundary) != 0, on) << "node " << n;
  }
}

TEST(ModelCleaning, RemovesATriangleHangingOnOneEdge) {
  Builder b;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) b.cross(x, y);
  b.triangle({0, 0}, {1, -1}, {2, 0});  // below the bottom edge of square (0, 0): one neighbour
  const Mesh m = b.mesh();
  ASSERT_EQ(defects(m), std::make_pair(1, 0));
  const ModelDefects d = find_model_defects(m.triangles, m.node_count());
  EXPECT_EQ(d.one_neighbour_triangles, 1);
  EXPECT_EQ(d.pinch_nodes, 0);

  const ModelMesh c(m);
  EXPECT_EQ(c.stats().one_neighbour_triangles, 1);
  EXPECT_EQ(c.stats().rounds, 1);
  EXPECT_EQ(c.stats().pinches, 0);
  EXPECT_EQ(c.stats().removed_nodes, 1);
  EXPECT_EQ(c.mesh().triangle_count(), 16);
  EXPECT_EQ(c.mesh().node_count(), m.node_count() - 1);
  EXPECT_EQ(defects(c.mesh()), std::make_pair(0, 0));
  ASSERT_EQ(c.mesh().loops.size(), 1u);
  EXPECT_EQ(c.mesh().loops[0].nodes.size(), 8u);
  expect_loops_match(c.mesh());
  EXPECT_EQ(c.source_triangle().size(), 16u);
  EXPECT_EQ(c.source_triangle().back(), 15);
  // The copy is reserved for exactly what it keeps (push_back alone left up to twice that).
  const Mesh& g = c.mesh();
  for (const auto* v : {&g.node_i, &g.node_j}) EXPECT_EQ(v->capacity(), v->size());
  for (const auto* v : {&g.lon_deg, &g.lat_deg, &g.rlon_deg, &g.rlat_deg, &g.depth_m}) EXPECT_EQ(v->capacity(), v->size());
  EXPECT_EQ(g.node_flags.capacity(), g.node_flags.size());
  EXPECT_EQ(g.triangles.capacity(), g.triangles.size());
  EXPECT_EQ(g.triangle_level.capacity(), g.triangle_level.size());
  EXPECT_EQ(g.triangle_square.capacity(), g.triangle_square.size());
  EXPECT_EQ(c.source_triangle().capacity(), c.source_triangle().size());
}

TEST(ModelCleaning, ResolvesAPinchKeepingTheFirstOfEqualFans) {
  const Mesh m = squares_mesh({"XXXX", "X.XX", "XX.."});
  ASSERT_EQ(defects(m), std::make_pair(0, 1));
  EXPECT_EQ(find_model_defects(m.triangles, m.node_count()).pinch_nodes, 1);

  const ModelMesh c(m);
  EXPECT_EQ(c.stats().pinches, 1);
  EXPECT_EQ(c.stats().pinch_triangles, 2);  // S and W of square (2, 1)
  EXPECT_EQ(c.stats().one_neighbour_triangles, 0);
  EXPECT_EQ(c.stats().rounds, 0);
  EXPECT_EQ(c.stats().removed_nodes, 0);
  EXPECT_EQ(c.mesh().triangle_count(), m.triangle_count() - 2);
  EXPECT_EQ(defects(c.mesh()), std::make_pair(0, 0));
  // The pinch joined the coast and the lake round (1, 1): one loop now.
  EXPECT_EQ(c.mesh().loops.size(), 1u);
  expect_loops_match(c.mesh());
  // Square (1, 0)'s triangles at the pinch (its E and N: triangles 5 and 6) are kept, square
  // (2, 1)'s S and W (the 2nd square of row 1: triangles 12 and 15) go.
  const auto& src = c.source_triangle();
  for (const ElementId kept : {5, 6}) EXPECT_TRUE(std::find(src.begin(), src.end(), kept) != src.end());
  for (const ElementId gone : {12, 15}) EXPECT_TRUE(std::find(src.begin(), src.end(), gone) == src.end());
}

TEST(ModelCleaning, APinchWhoseRemovalLeavesTrianglesWithOneNeighbour) {
  const Mesh m = squares_mesh({"XXXX", "X.X.", "XX.."});
  ASSERT_EQ(defects(m), std::make_pair(0, 1));  // no triangle with one neighbour to begin with

  const ModelMesh c(m);
  EXPECT_EQ(c.stats().pinches, 1);
  EXPECT_EQ(c.stats().pinch_triangles, 2);
  // Then square (2, 1)'s E has one neighbour (round 1), then its N (round 2).
  EXPECT_EQ(c.stats().one_neighbour_triangles, 2);
  EXPECT_EQ(c.stats().rounds, 2);
  EXPECT_EQ(c.stats().removed_nodes, 2);  // the square's centre and its SE corner (3, 1)
  EXPECT_EQ(c.mesh().triangle_count(), m.triangle_count() - 4);
  EXPECT_EQ(defects(c.mesh()), std::make_pair(0, 0));
  EXPECT_TRUE(find_model_defects(c.mesh().triangles, c.mesh().node_count()).none());
  expect_loops_match(c.mesh());
}

TEST(ModelCleaning, CleanMeshIsPassedThroughAndLoopsKeepTheirStart) {
  Mesh m = squares_mesh({"XX", "XX"});
  const ModelMesh c(m);
  EXPECT_EQ(&c.mesh(), &m);
  EXPECT_TRUE(c.source_triangle().empty());
  EXPECT_EQ(c.stats().one_neighbour_triangles + c.stats().pinches, 0);
}

TEST(ModelCleaning, LoopsUntouchedByTheCleaningAreUnchanged) {
  // The one-neighbour case with the input's loop given: the cleaned loop starts where it did.
  Builder b;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) b.cross(x, y);
  b.triangle({0, 0}, {1, -1}, {2, 0});
  Mesh m = b.mesh();
  auto id = [&](int x, int y) { return b.ids.at({x, y}); };
  BoundaryLoop loop;
  loop.outer = true;
  loop.nodes = {id(4, 2), id(4, 4), id(2, 4), id(0, 4), id(0, 2), id(0, 0), id(1, -1), id(2, 0), id(4, 0)};
  m.loops.push_back(loop);
  const ModelMesh c(m);
  ASSERT_EQ(c.mesh().loops.size(), 1u);
  EXPECT_TRUE(c.mesh().loops[0].outer);
  // The same nodes less the apex, from the same first node; the apex (lowest y) was node 0.
  ASSERT_EQ(id(1, -1), 0);
  const std::vector<NodeId> want{id(4, 2) - 1, id(4, 4) - 1, id(2, 4) - 1, id(0, 4) - 1,
                                 id(0, 2) - 1, id(0, 0) - 1, id(2, 0) - 1, id(4, 0) - 1};
  EXPECT_EQ(c.mesh().loops[0].nodes, want);
}

TEST(ModelCleaning, NothingLeftIsAnError) {
  Builder b;
  b.triangle({0, 0}, {2, 0}, {0, 2});
  b.triangle({2, 0}, {2, 2}, {0, 2});
  const Mesh m = b.mesh();
  EXPECT_THROW(ModelMesh{m}, NumericalError);
}

}  // namespace
}  // namespace aq::mesh::unit_mesh_model_cleaning_test

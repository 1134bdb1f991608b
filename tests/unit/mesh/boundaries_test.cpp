// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary typing (mesh/boundaries.hpp): open runs from the predicate, short pieces merged, land
// on a loop with open segments is mainland, other loops island (or mainland when outer), the
// segments share their end nodes, a loop open all round becomes two open segments.
#include "mesh/boundaries.hpp"

#include <gtest/gtest.h>

#include <set>
#include <utility>
#include <vector>

namespace aq::mesh::unit_mesh_boundaries_test {
namespace {

// One loop of n nodes 0..n-1 (edges k -> k+1), plus an optional island loop of 4 nodes.
Mesh ring_mesh(int n, bool island) {
  Mesh m;
  const int total = n + (island ? 4 : 0);
  for (int k = 0; k < total; ++k) {
    m.node_i.push_back(k);
    m.node_j.push_back(0);
    m.lon_deg.push_back(k);
    m.lat_deg.push_back(0.0);
  }
  BoundaryLoop outer;
  outer.outer = true;
  for (int k = 0; k < n; ++k) {
    outer.nodes.push_back(k);
    m.boundary_edges.push_back({k, (k + 1) % n});
    m.boundary_edge_loop.push_back(0);
  }
  m.loops.push_back(outer);
  if (island) {
    BoundaryLoop is;
    for (int k = 0; k < 4; ++k) {
      is.nodes.push_back(n + k);
      m.boundary_edges.push_back({n + k, n + (k + 1) % 4});
      m.boundary_edge_loop.push_back(1);
    }
    m.loops.push_back(is);
  }
  return m;
}

std::function<bool(NodeId, NodeId)> open_from(std::set<NodeId> starts) {
  return [starts](NodeId a, NodeId) { return starts.count(a) > 0; };
}

TEST(Boundaries, OpenRunMainlandPieceAndIsland) {
  Mesh m = ring_mesh(12, true);
  const BoundaryCounts c = type_boundaries(m, open_from({3, 4, 5, 6}), nullptr);
  EXPECT_EQ(c.open_segments, 1);
  EXPECT_EQ(c.open_edges, 4);
  EXPECT_EQ(c.mainland_segments, 1);
  EXPECT_EQ(c.islands, 1);
  ASSERT_EQ(m.segments.size(), 3u);
  EXPECT_EQ(m.segments[0].type, BoundaryType::kOpen);
  EXPECT_EQ(m.segments[0].nodes, (std::vector<NodeId>{3, 4, 5, 6, 7}));
  EXPECT_EQ(m.segments[1].type, BoundaryType::kMainland);
  EXPECT_FALSE(m.segments[1].closed);
  EXPECT_EQ(m.segments[1].nodes.front(), 7);  // from the open segment's last node
  EXPECT_EQ(m.segments[1].nodes.back(), 3);   // to its first
  EXPECT_EQ(m.segments[1].nodes.size(), 9u);
  EXPECT_EQ(m.segments[2].type, BoundaryType::kIsland);
  EXPECT_TRUE(m.segments[2].closed);
  ASSERT_EQ(m.boundary_edge_type.size(), m.boundary_edges.size());
  for (std::size_t e = 0; e < 12; ++e)
    EXPECT_EQ(m.boundary_edge_type[e], (e >= 3 && e <= 6) ? BoundaryType::kOpen : BoundaryType::kMainland) << e;
  EXPECT_EQ(m.boundary_edge_type[12], BoundaryType::kIsland);
}

TEST(Boundaries, ShortLandGapMergesOpenSegmentsAndShortOpenRunBecomesLand) {
  Mesh m = ring_mesh(20, false);
  // Open 2..5, land gap 6 (one edge), open 7..10; a lone open edge at 15.
  const BoundaryCounts c = type_boundaries(m, open_from({2, 3, 4, 5, 7, 8, 9, 10, 15}), nullptr);
  EXPECT_EQ(c.merged, 2);
  EXPECT_EQ(c.open_segments, 1);
  ASSERT_FALSE(m.segments.empty());
  EXPECT_EQ(m.segments[0].nodes, (std::vector<NodeId>{2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
  EXPECT_EQ(m.boundary_edge_type[15], BoundaryType::kMainland);
}

TEST(Boundaries, LoopOpenAllRoundIsTwoOpenSegments) {
  Mesh m = ring_mesh(10, false);
  std::set<NodeId> all;
  for (NodeId k = 0; k < 10; ++k) all.insert(k);
  const BoundaryCounts c = type_boundaries(m, open_from(all), nullptr);
  EXPECT_EQ(c.open_segments, 2);
  ASSERT_EQ(m.segments.size(), 2u);
  EXPECT_NE(m.segments[0].nodes.front(), m.segments[0].nodes.back());
  EXPECT_NE(m.segments[1].nodes.front(), m.segments[1].nodes.back());
  EXPECT_EQ(m.segments[0].nodes.back(), m.segments[1].nodes.front());
  EXPECT_EQ(m.segments[1].nodes.back(), m.segments[0].nodes.front());
}

TEST(Boundaries, NoOpenEdgeOuterLoopIsMainlandOthersIslands) {
  Mesh m = ring_mesh(8, true);
  const BoundaryCounts c = type_boundaries(m, open_from({}), nullptr);
  EXPECT_EQ(c.open_segments, 0);
  EXPECT_EQ(c.mainland_segments, 1);
  EXPECT_EQ(c.islands, 1);
  EXPECT_TRUE(m.segments[0].closed);
}

}  // namespace
}  // namespace aq::mesh::unit_mesh_boundaries_test

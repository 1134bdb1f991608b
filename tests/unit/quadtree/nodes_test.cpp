// SPDX-License-Identifier: GPL-3.0-or-later
// Nodes, midside nodes, boundary loops, pinches, poles and the seam (nodes.hpp).
#include "quadtree/nodes.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/error.hpp"
#include "quadtree/balance.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::quadtree::unit_quadtree_nodes_test {
namespace {

using testing::draw;
using testing::make_lattice;
using testing::random_mask;

std::vector<Leaf> balanced_leaves(const Bitmap& m, const Lattice& lat, int band = 0) {
  LevelMasks masks = make_level_masks(m, lat, band);
  balance(masks, BalanceMode::kFace);
  return extract_leaves(masks, lat);
}

/// Seam-unwrapped I step of an edge.
std::int64_t dx_of(const QuadNodes& q, const Lattice& lat, const std::array<NodeId, 2>& e) {
  std::int64_t dx = q.node_i[static_cast<std::size_t>(e[1])] - q.node_i[static_cast<std::size_t>(e[0])];
  if (dx > lat.nx / 2) dx -= lat.nx;
  if (dx < -lat.nx / 2) dx += lat.nx;
  return dx;
}

/// Structural checks every node set must pass.
void check_invariants(const QuadNodes& q, const std::vector<Leaf>& leaves, const Lattice& lat, const Bitmap& filled) {
  // Sorted by (J, I), I in [0, nx), unique.
  for (std::size_t n = 0; n < q.node_i.size(); ++n) {
    ASSERT_GE(q.node_i[n], 0);
    ASSERT_LT(q.node_i[n], lat.nx);
    ASSERT_GE(q.node_j[n], 0);
    ASSERT_LE(q.node_j[n], lat.ny);
    if (n > 0) {
      ASSERT_TRUE(q.node_j[n - 1] < q.node_j[n] || (q.node_j[n - 1] == q.node_j[n] && q.node_i[n - 1] < q.node_i[n]));
    }
    ASSERT_EQ((q.node_flags[n] & kSeamNode) != 0, q.node_i[n] == 0);
    ASSERT_EQ((q.node_flags[n] & kPoleNode) != 0, q.node_j[n] == 0 || q.node_j[n] == lat.ny);
  }
  // Nodes are exactly the leaf corners (plus centres, when asked).
  std::set<std::pair<std::int64_t, std::int64_t>> corners;
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const Leaf& f = leaves[k];
    const std::int64_t s = leaf_size(lat, f), i0 = leaf_i0(lat, f), j0 = leaf_j0(lat, f);
    const std::array<std::array<std::int64_t, 2>, 4> c{{{i0, j0}, {i0 + s, j0}, {i0 + s, j0 + s}, {i0, j0 + s}}};
    for (int v = 0; v < 4; ++v) {
      const std::int64_t i = wrap_index(c[static_cast<std::size_t>(v)][0], lat.nx),
                         j = c[static_cast<std::size_t>(v)][1];
      corners.insert({j, i});
      ASSERT_EQ(q.corners[k][static_cast<std::size_t>(v)], find_node(q, lat, i, j));
    }
  }
  std::int64_t centres = 0;
  for (const std::uint8_t fl : q.node_flags) centres += (fl & kCentreNode) != 0;
  EXPECT_EQ(static_cast<std::int64_t>(corners.size()) + centres, q.node_count());
  // Midside nodes: the side midpoint is some leaf's corner exactly when the code says so.
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const Leaf& f = leaves[k];
    const std::int64_t s = leaf_size(lat, f), i0 = leaf_i0(lat, f), j0 = leaf_j0(lat, f), h = s / 2;
    const std::array<std::array<std::int64_t, 2>, 4> mid{
        {{i0 + h, j0}, {i0 + s, j0 + h}, {i0 + h, j0 + s}, {i0, j0 + h}}};
    for (int side = 0; side < 4; ++side) {
      const auto& p = mid[static_cast<std::size_t>(side)];
      const bool expect = s >= 2 && corners.count({p[1], wrap_index(p[0], lat.nx)}) > 0;
      ASSERT_EQ((q.midside_code[k] >> side) & 1, expect ? 1 : 0);
      ASSERT_EQ(q.midside[k][static_cast<std::size_t>(side)] >= 0, expect);
      if (expect) {
        const NodeId m = q.midside[k][static_cast<std::size_t>(side)];
        ASSERT_EQ(m, find_node(q, lat, p[0], p[1]));
        ASSERT_TRUE(q.node_flags[static_cast<std::size_t>(m)] & kMidsideNode);
      }
    }
  }
  // Boundary: total length equals the naive count of filled/unfilled pixel sides; loops are
  // closed chains using every edge once; −∮ y dx over all loops is the filled area (wet on the left).
  std::int64_t length = 0, area = 0;
  ASSERT_EQ(q.boundary_edges.size(), q.boundary_edge_loop.size());
  std::int64_t next_edge = 0;
  for (std::size_t l = 0; l < q.loops.size(); ++l) {
    const LoopInfo& loop = q.loops[l];
    ASSERT_EQ(loop.first_edge, next_edge);
    ASSERT_GT(loop.edge_count, 0);
    next_edge += loop.edge_count;
    for (std::int64_t e = loop.first_edge; e < loop.first_edge + loop.edge_count; ++e) {
      const auto& edge = q.boundary_edges[static_cast<std::size_t>(e)];
      ASSERT_EQ(q.boundary_edge_loop[static_cast<std::size_t>(e)], static_cast<std::int32_t>(l));
      const std::int64_t nexti = (e + 1 < loop.first_edge + loop.edge_count) ? e + 1 : loop.first_edge;
      ASSERT_EQ(edge[1], q.boundary_edges[static_cast<std::size_t>(nexti)][0]) << "loop " << l << " is broken";
      const std::int64_t dx = dx_of(q, lat, edge);
      const std::int64_t dy = q.node_j[static_cast<std::size_t>(edge[1])] - q.node_j[static_cast<std::size_t>(edge[0])];
      ASSERT_TRUE((dx == 0) != (dy == 0));
      length += std::abs(dx) + std::abs(dy);
      area -= q.node_j[static_cast<std::size_t>(edge[0])] * dx;
      ASSERT_TRUE(q.node_flags[static_cast<std::size_t>(edge[0])] & kBoundaryNode);
    }
  }
  EXPECT_EQ(next_edge, static_cast<std::int64_t>(q.boundary_edges.size()));
  EXPECT_EQ(length, testing::naive_boundary_length(filled));
  EXPECT_EQ(area, filled.count());
  std::int64_t outer = 0;
  for (const LoopInfo& loop : q.loops) outer += loop.outer;
  EXPECT_EQ(outer, q.loops.empty() ? 0 : 1);
  // Pinches.
  const auto pinches = find_pinches(filled);
  ASSERT_EQ(pinches.size(), q.pinch_nodes.size());
  for (std::size_t k = 0; k < pinches.size(); ++k) {
    EXPECT_EQ(q.pinch_nodes[k], find_node(q, lat, pinches[k][0], pinches[k][1]));
  }
}

TEST(Nodes, SeamNodesAreIdentifiedAndGetTheMidsideOfTheFinerNeighbour) {
  // Seed Fig. 3: a level-0 leaf whose east side is the seam λ = lon0 + 360°, with two level-1
  // leaves across it at λ = lon0: its midside node on the seam is the node with I = 0.
  const Lattice lat = make_lattice(90.0, 2);  // 16 × 8, 4×4-pixel roots
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < 4; ++j)
    for (std::int64_t i = 12; i < 16; ++i) m.set(i, j);
  for (std::int64_t j = 0; j < 4; ++j)
    for (std::int64_t i = 0; i < 2; ++i) m.set(i, j);
  const std::vector<Leaf> leaves = balanced_leaves(m, lat);
  const QuadNodes q = build_nodes(leaves, lat);
  check_invariants(q, leaves, lat, m);
  const auto root = std::find(leaves.begin(), leaves.end(), Leaf{0, 3, 0});
  ASSERT_NE(root, leaves.end());
  const auto k = static_cast<std::size_t>(root - leaves.begin());
  EXPECT_EQ(q.midside_code[k], kSideE);
  const NodeId mid = q.midside[k][1];
  EXPECT_EQ(q.node_i[static_cast<std::size_t>(mid)], 0);
  EXPECT_EQ(q.node_j[static_cast<std::size_t>(mid)], 2);
  EXPECT_EQ(q.node_flags[static_cast<std::size_t>(mid)] & (kSeamNode | kMidsideNode), kSeamNode | kMidsideNode);
  // The root's east corners are the seam nodes (0, 0) and (0, 4), shared with the leaves at I = 0.
  EXPECT_EQ(q.corners[k][1], find_node(q, lat, 0, 0));
  EXPECT_EQ(q.corners[k][2], find_node(q, lat, 0, 4));
  EXPECT_EQ(find_node(q, lat, 16, 4), find_node(q, lat, 0, 4));
  // One region across the seam: one loop.
  EXPECT_EQ(q.loops.size(), 1u);
  EXPECT_TRUE(q.loops[0].outer);
}

TEST(Nodes, PinchLoopsTurnLeftAndDoNotCross) {
  // Two 2×2 blocks touching at the vertex (4, 4): one pinch, two loops through it.
  const Lattice lat = make_lattice(90.0, 2);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 2; j < 4; ++j)
    for (std::int64_t i = 2; i < 4; ++i) m.set(i, j);
  for (std::int64_t j = 4; j < 6; ++j)
    for (std::int64_t i = 4; i < 6; ++i) m.set(i, j);
  const std::vector<Leaf> leaves = balanced_leaves(m, lat);
  const QuadNodes q = build_nodes(leaves, lat);
  check_invariants(q, leaves, lat, m);
  ASSERT_EQ(q.pinch_nodes.size(), 1u);
  EXPECT_EQ(q.pinch_nodes[0], find_node(q, lat, 4, 4));
  ASSERT_EQ(q.loops.size(), 2u);
  EXPECT_EQ(q.loops[0].edge_count, 4);
  EXPECT_EQ(q.loops[1].edge_count, 4);
}

TEST(Nodes, PinchClosingARingMakesOneLoop) {
  // A ring of pixels around a hole, closed by a diagonal touch at its SW corner (left turns
  // join the hole's boundary and the outer boundary into one loop). rows[0] is the north.
  // clang-format off
  const Bitmap m = draw({"................",
                         "................",
                         "...###..........",
                         "...#.#..........",
                         "....##..........",
                         "................",
                         "................",
                         "................"});
  // clang-format on
  const Lattice lat = make_lattice(90.0, 2);
  const std::vector<Leaf> leaves = balanced_leaves(m, lat);
  const QuadNodes q = build_nodes(leaves, lat);
  check_invariants(q, leaves, lat, m);
  ASSERT_EQ(q.pinch_nodes.size(), 1u);
  EXPECT_EQ(q.pinch_nodes[0], find_node(q, lat, 4, 4));
  EXPECT_EQ(q.loops.size(), 1u);
  EXPECT_EQ(q.loops[0].edge_count, 16);
}

TEST(Nodes, AnnulusHasAnOuterAndAnInnerLoop) {
  const Lattice lat = make_lattice(30.0, 3);  // 96 × 48
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 8; j < 40; ++j)
    for (std::int64_t i = 16; i < 80; ++i)
      if (!(j >= 16 && j < 32 && i >= 32 && i < 64)) m.set(i, j);
  const std::vector<Leaf> leaves = balanced_leaves(m, lat);
  const QuadNodes q = build_nodes(leaves, lat);
  check_invariants(q, leaves, lat, m);
  ASSERT_EQ(q.loops.size(), 2u);
  // Loop 0 starts at the lowest node (16, 8): the outer boundary, anticlockwise.
  EXPECT_TRUE(q.loops[0].outer);
  EXPECT_FALSE(q.loops[1].outer);
  EXPECT_EQ(q.boundary_edges[0][0], find_node(q, lat, 16, 8));
  EXPECT_GT(q.node_i[static_cast<std::size_t>(q.boundary_edges[0][1])], 16);  // eastward first
  EXPECT_EQ(q.node_j[static_cast<std::size_t>(q.boundary_edges[0][1])], 8);
  EXPECT_TRUE(q.pinch_nodes.empty());
}

TEST(Nodes, PoleRowIsABoundaryLoopOfPoleNodes) {
  const Lattice lat = make_lattice(45.0, 3);  // 64 × 32
  Bitmap m = random_mask(lat.nx, lat.ny, 3u, 0.5, 0.0, 8);
  for (std::int64_t j = lat.ny - 4; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) m.set(i, j);
  for (std::int64_t i = 0; i < lat.nx; ++i) m.clear(i, lat.ny - 5);  // the polar cap is its own region
  const std::vector<Leaf> leaves = balanced_leaves(m, lat, 1);
  const QuadNodes q = build_nodes(leaves, lat);
  check_invariants(q, leaves, lat, m);
  int poles = 0;
  for (const LoopInfo& loop : q.loops) {
    if (!loop.pole) continue;
    ++poles;
    std::int64_t length = 0;
    for (std::int64_t e = loop.first_edge; e < loop.first_edge + loop.edge_count; ++e) {
      length -= dx_of(q, lat, q.boundary_edges[static_cast<std::size_t>(e)]);
      const NodeId a = q.boundary_edges[static_cast<std::size_t>(e)][0];
      EXPECT_EQ(q.node_j[static_cast<std::size_t>(a)], lat.ny);
      EXPECT_TRUE(q.node_flags[static_cast<std::size_t>(a)] & kPoleNode);
      EXPECT_LT(dx_of(q, lat, q.boundary_edges[static_cast<std::size_t>(e)]), 0);  // westward: wet below
    }
    EXPECT_EQ(length, lat.nx);
  }
  EXPECT_EQ(poles, 1);
}

class NodesRandom : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(NodesRandom, InvariantsHoldWithAndWithoutCentres) {
  const Lattice lat = make_lattice(45.0, 4);  // 128 × 64
  const Bitmap m = random_mask(lat.nx, lat.ny, GetParam(), 0.6, 0.01, 12);
  for (const int band : {0, 2}) {
    const std::vector<Leaf> leaves = balanced_leaves(m, lat, band);
    const QuadNodes plain = build_nodes(leaves, lat);
    check_invariants(plain, leaves, lat, m);
    const QuadNodes with = build_nodes(leaves, lat, NodeOptions{true});
    check_invariants(with, leaves, lat, m);
    std::int64_t centres = 0;
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      ASSERT_EQ(with.centre[k] >= 0, with.midside_code[k] != 0);
      ASSERT_LT(plain.centre[k], 0);
      if (with.centre[k] < 0) continue;
      ++centres;
      const std::int64_t s = leaf_size(lat, leaves[k]);
      ASSERT_EQ(with.centre[k], find_node(with, lat, leaf_i0(lat, leaves[k]) + s / 2, leaf_j0(lat, leaves[k]) + s / 2));
    }
    EXPECT_EQ(with.node_count(), plain.node_count() + centres);
    EXPECT_GT(centres, 0);
    EXPECT_FALSE(plain.pinch_nodes.empty());
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, NodesRandom, ::testing::Values(1u, 2u, 3u, 4u));

TEST(Nodes, RejectsUnsortedOrOverlappingLeaves) {
  const Lattice lat = make_lattice(90.0, 2);
  EXPECT_THROW(build_nodes({{0, 1, 0}, {0, 0, 0}}, lat), InternalError);
  EXPECT_THROW(build_nodes({{0, 0, 0}, {1, 1, 1}}, lat), InternalError);
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_nodes_test

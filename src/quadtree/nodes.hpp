// SPDX-License-Identifier: GPL-3.0-or-later
// Nodes, midside (hanging) nodes, boundary edges and loops, pinch vertices and the λ seam of a
// balanced quadtree (seed 002: "узлы сетки нумеруются... устанавливается принадлежность узлов и
// ребер границе и выделяются номера узлов, лежащих на серединах сторон квадратов", Fig. 3;
// ARCHITECTURE §4.5).
//
// Every node is a lattice vertex (I, J), 0 <= I < nx (I = nx is I = 0: the seam is automatic),
// 0 <= J <= ny. Nodes are numbered by (J, I) — the rank of the vertex in a row-major vertex
// bitmap — so the numbering is independent of the thread count.
//
// Corner, side and midside conventions of a leaf (anticlockwise in the (λ, φ) lattice plane):
//
//     NW ---------- N ---------- NE      corners  0 SW, 1 SE, 2 NE, 3 NW
//      |                          |      sides    0 S (SW->SE), 1 E (SE->NE),
//      |                          |               2 N (NE->NW), 3 W (NW->SW)
//      W            C             E      midside code: bit k set when side k has a
//      |                          |      midside node: S = 1, E = 2, N = 4, W = 8
//      |                          |      C = centre node (optional, see NodeOptions)
//     SW ---------- S ---------- SE
//
// A midside node of a leaf is the midpoint of one of its sides where a finer neighbour has a
// corner. Boundary edges are leaf sides, or halves of sides split by a midside node, with no
// filled pixel across; they are directed with the wet area on the left (the leaf's anticlockwise
// side direction). The lattice edge at φ = ±90° is a boundary (the pole loop without rotation).
//
// Pinch vertices: the filled set touches itself at a single corner, the four pixels around the
// vertex being filled in a diagonal pattern:
//
//     . #        # .        A boundary loop reaching a pinch turns LEFT (it stays with the pixel
//     # .   or   . #        it came along), so loops touch at the pinch but never cross; with this
//                           rule V - E + F = 2c - b - p (c edge-connected components, b loops,
//                           p pinches), i.e. 2 - b - p for the K-cursor fill (c = 1).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/lattice.hpp"
#include "core/types.hpp"
#include "quadtree/leaves.hpp"

namespace aq::quadtree {

/// Node flag bits; the values equal aq::mesh::NodeFlag.
enum NodeBits : std::uint8_t {
  kBoundaryNode = 1,  ///< end of a boundary edge
  kMidsideNode = 2,   ///< midpoint of a coarser leaf's side (hanging node of the square mesh)
  kCentreNode = 4,    ///< centre of a leaf with midside nodes (NodeOptions::centres)
  kPoleNode = 8,      ///< J = 0 or J = ny (φ = ±90° of the lattice)
  kSeamNode = 16,     ///< I = 0
};

/// Midside code bits (one per side, anticlockwise from the south side).
enum SideBits : std::uint8_t { kSideS = 1, kSideE = 2, kSideN = 4, kSideW = 8 };

struct NodeOptions {
  /// Also create the centre node of every leaf with at least one midside node (the triangle
  /// templates need it); centres are lattice vertices (such leaves have side >= 2 pixels) and
  /// are numbered by (J, I) together with the corners.
  bool centres = false;
};

/// A boundary loop: its edges are boundary_edges[first_edge .. first_edge + edge_count), in order.
struct LoopInfo {
  std::int64_t first_edge = 0;
  std::int64_t edge_count = 0;
  bool outer = false;  ///< largest extent (see QuadNodes::loops)
  bool pole = false;   ///< all nodes on J = 0 or all on J = ny
};

struct QuadNodes {
  // Nodes, sorted by (J, I).
  std::vector<std::int64_t> node_i, node_j;
  std::vector<std::uint8_t> node_flags;  ///< NodeBits

  // Per leaf, in the order of the leaves given.
  std::vector<std::array<NodeId, 4>> corners;  ///< SW, SE, NE, NW
  std::vector<std::array<NodeId, 4>> midside;  ///< S, E, N, W midside node or -1
  std::vector<std::uint8_t> midside_code;      ///< SideBits of the sides with a midside node
  std::vector<NodeId> centre;                  ///< centre node or -1

  /// Boundary edges (a -> b, wet on the left), grouped by loop and in loop order. Loops are
  /// found from the edge with the smallest (a, b) not yet used, so loop 0 starts at the lowest
  /// (J, I) boundary node; a loop's edges start at its lowest (a, b) edge.
  std::vector<std::array<NodeId, 2>> boundary_edges;
  std::vector<std::int32_t> boundary_edge_loop;
  /// Exactly one loop (when any) is `outer`: the one with the largest bounding box in the lattice
  /// plane (width = nx for a loop winding around the seam, × height in J), ties broken by more
  /// edges, then the lower id. For a region in the plane this is its outer boundary.
  std::vector<LoopInfo> loops;
  std::vector<NodeId> pinch_nodes;  ///< ascending

  [[nodiscard]] std::int64_t node_count() const { return static_cast<std::int64_t>(node_i.size()); }
};

/// Numbers the nodes of balanced leaves and finds midside nodes, boundary edges and loops and
/// pinch vertices. `leaves` must be in the deterministic order (leaves.hpp), non-overlapping and
/// face-balanced (2:1). Order and overlap are checked (InternalError); balance is not re-checked
/// here (quadtree::build_leaves proves it), and an unbalanced set may give wrong boundary edges,
/// which mesh::compute_statistics then reports (boundary_mismatch, Euler). InternalError also
/// when boundary tracing finds a node with no or more than two outgoing edges. Work
/// O(leaves + N/64), parallel except loop tracing.
QuadNodes build_nodes(const std::vector<Leaf>& leaves, const Lattice& lat, const NodeOptions& options = {});

/// What a leaf's neighbourhood holds — all that the numbering needs beyond the leaf itself, so
/// that nodes can be numbered without any bitmap of the lattice (the forest engine finds it over
/// its ghost layer, forest/mesh_nodes.hpp):
///   midside  SideBits: the midpoint of the side is a corner of another leaf;
///   covered  bit k: the pixel across the side at k is filled —
///            0 S at i0, 1 S at i0 + s/2, 2 E at j0, 3 E at j0 + s/2,
///            4 N at i0 + s/2, 5 N at i0, 6 W at j0 + s/2, 7 W at j0
///            (the pixels just outside the leaf of side s at (i0, j0); columns wrap, rows beyond
///            the lattice are not filled);
///   pinch    bit c: corner c (0 SW, 1 SE, 2 NE, 3 NW) is a pinch vertex of the filled set.
struct LeafNeighbourhood {
  std::uint8_t midside = 0;
  std::uint8_t covered = 0;
  std::uint8_t pinch = 0;
};

/// The neighbourhoods of `leaves` from a coverage bitmap of the lattice (the reference for
/// build_nodes_from_neighbourhoods; the same rules as build_nodes).
std::vector<LeafNeighbourhood> leaf_neighbourhoods(const std::vector<Leaf>& leaves, const Lattice& lat);

/// build_nodes from the leaves and their neighbourhoods alone: the same QuadNodes, with no bitmap
/// of the lattice (nodes numbered by sorting their (J, I) keys). `leaves` must be in the
/// deterministic order (InternalError otherwise).
QuadNodes build_nodes_from_neighbourhoods(const std::vector<Leaf>& leaves, const std::vector<LeafNeighbourhood>& nb,
                                          const Lattice& lat, const NodeOptions& options = {});

/// Node at lattice vertex (I mod nx, J), or -1; O(log nodes).
NodeId find_node(const QuadNodes& nodes, const Lattice& lat, std::int64_t i, std::int64_t j);

/// Pinch vertices of a filled pixel set as (I, J) pairs sorted by (J, I) (rows 1..ny-1; the seam wraps).
std::vector<std::array<std::int64_t, 2>> find_pinches(const Bitmap& filled);

}  // namespace aq::quadtree

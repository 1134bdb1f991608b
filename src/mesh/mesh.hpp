// SPDX-License-Identifier: GPL-3.0-or-later
// The global mesh handed from the discretizer to the writers (ARCHITECTURE §4.5–4.8).
// Topology is integer: every node is a lattice vertex (I, J) (see core/lattice.hpp); the
// geographic coordinates are computed from (I, J) only for output. Arrays are flat and indexed
// by NodeId / ElementId (0-based). Node numbering is sorted by (J, I); elements follow the
// deterministic leaf order (level-0 square row-major, Morton inside).
//
// Periodicity: I is kept in [0, nx). An element that crosses the seam has some nodes with I near
// nx-1..nx and some at I = 0; `unwrapped_i()` gives the I an element's node has when drawn on
// the λ–φ rectangle [lon0, lon0+360] (I = 0 becomes I = nx for such elements). Writers in the
// λ–φ plane duplicate those nodes and link them (MSH $Periodic); 3-D writers need nothing.
//
// Orientation: triangles and quads are anticlockwise in the (λ, φ) lattice plane (rotated
// coordinates when the pole is rotated).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/lattice.hpp"
#include "core/types.hpp"

namespace aq::mesh {

/// Bit flags of a node.
enum NodeFlag : std::uint8_t {
  kNodeBoundary = 1,  ///< on a boundary edge (coast, or the pole line without rotation)
  kNodeMidside = 2,   ///< hanging node of the square mesh (midpoint of a coarser leaf's side)
  kNodeCentre = 4,    ///< centre node added by a triangle template
  kNodePole = 8,      ///< on φ = ±90° of the lattice (all such nodes are one physical point)
  kNodeSeam = 16,     ///< on the seam I = 0
  kNodeCap = 32,      ///< added by the pole cap of a geographic mesh (io/geographic_mesh.hpp): not a
                      ///< lattice vertex, node_i = node_j = -1
  kNodeMoved = 64,    ///< an open-boundary node of a polygon domain moved off its lattice vertex (I, J)
                      ///< onto the polygon (mesh/open_snap.hpp): lon/lat, rlon/rlat and depth are the
                      ///< new position's; (I, J) stay the vertex it came from (the topology's key)
};

/// One closed boundary polyline. Nodes are listed in order, anticlockwise around the wet area
/// (the wet area on the left), first node not repeated at the end.
struct BoundaryLoop {
  std::vector<NodeId> nodes;
  bool outer = false;  ///< the loop with the largest enclosed extent (the "mainland" coast)
  bool pole = false;   ///< the loop is the lattice edge φ = ±90° (only without rotation)
};

/// Type of a boundary edge of a regional mesh (README "Regional FE meshes").
enum class BoundaryType : std::uint8_t {
  kMainland = 0,  ///< land: on a loop that has open segments, or the outer loop
  kIsland = 1,    ///< a closed land loop that is not the mainland
  kOpen = 2,      ///< on the domain edge, in water: an elevation (tide) boundary
  kRiver = 3,  ///< on the domain edge where a channel line (mask.channels) crosses it: a flux (river inflow) boundary
};

/// A typed piece of a boundary loop: an open segment (nodes in loop order, water on the left,
/// both ends shared with the land pieces around it), a mainland piece between two open
/// segments (from the last node of one to the first node of the next), or a whole closed loop
/// (`closed`: mainland or island, first node not repeated).
struct BoundarySegment {
  BoundaryType type = BoundaryType::kMainland;
  std::int32_t loop = 0;
  bool closed = false;
  std::vector<NodeId> nodes;
};

struct RotationInfo {
  bool enabled = false;
  double pole_lon_deg = 0.0;  ///< geographic position of the rotated system's North pole
  double pole_lat_deg = 90.0;
};

struct Mesh {
  Lattice lattice;
  RotationInfo rotation;
  /// > 0: the mesh reaches land up to this many metres above the datum (mask.min_depth_m < 0, a
  /// floodplain for wetting and drying): nodes above the datum have a negative depth in the files.
  double floodplain_top_m = 0.0;

  // Nodes.
  std::vector<std::int64_t> node_i, node_j;  ///< lattice coordinates, I in [0, nx), J in [0, ny]
  std::vector<double> lon_deg, lat_deg;      ///< geographic coordinates (after un-rotation)
  std::vector<double> rlon_deg, rlat_deg;    ///< lattice-system coordinates (== geographic without rotation)
  std::vector<double> depth_m;               ///< elevation in metres, negative below sea level
  std::vector<std::uint8_t> node_flags;      ///< NodeFlag bits

  // Triangles (present when mesh.elements is "triangles" or "both").
  std::vector<std::array<NodeId, 3>> triangles;
  std::vector<std::uint8_t> triangle_level;  ///< quadtree level of the square it came from
  std::vector<ElementId> triangle_square;    ///< index of that square in `squares`

  // Squares = quadtree leaves (always present; written when elements is "squares" or "both").
  std::vector<std::array<NodeId, 4>> squares;  ///< SW, SE, NE, NW corners (anticlockwise)
  std::vector<std::uint8_t> square_level;
  std::vector<std::array<NodeId, 4>> square_midside;  ///< midside node of side S, E, N, W or -1

  // Boundary.
  std::vector<std::array<NodeId, 2>> boundary_edges;  ///< wet area on the left of (a -> b)
  std::vector<std::int32_t> boundary_edge_loop;       ///< loop id of each boundary edge
  std::vector<BoundaryLoop> loops;
  std::vector<NodeId> pinch_nodes;  ///< where the wet area touches itself at a corner

  // Boundary types (regional meshes only; empty for the global mesh): mesh/boundaries.hpp.
  bool typed = false;                              ///< set by mesh::type_boundaries
  std::vector<BoundaryType> boundary_edge_type;    ///< per boundary edge
  std::vector<BoundarySegment> segments;           ///< open segments first (loop order), then land

  [[nodiscard]] std::int64_t node_count() const { return static_cast<std::int64_t>(node_i.size()); }
  [[nodiscard]] std::int64_t triangle_count() const { return static_cast<std::int64_t>(triangles.size()); }
  [[nodiscard]] std::int64_t square_count() const { return static_cast<std::int64_t>(squares.size()); }

  /// I of node `n` as drawn inside an element whose nodes are `nodes` (seam-unwrapped).
  template <std::size_t K>
  [[nodiscard]] std::int64_t unwrapped_i(const std::array<NodeId, K>& nodes, NodeId n) const {
    std::int64_t max_i = 0;
    for (const NodeId m : nodes) max_i = node_i[m] > max_i ? node_i[m] : max_i;
    const std::int64_t i = node_i[n];
    return (i == 0 && max_i > lattice.nx / 2) ? lattice.nx : i;
  }
  /// Offset (degrees of λ′ in the lattice plane) of node `n` from its lattice column: 0 unless
  /// the node was moved (kNodeMoved). A writer in the plane draws it at its column's λ′ plus this.
  [[nodiscard]] double plane_dx_deg(NodeId n) const {
    const auto p = static_cast<std::size_t>(n);
    if ((node_flags[p] & kNodeMoved) == 0) return 0.0;
    const double d = rlon_deg[p] - lattice.lon_of(node_i[p]);
    return d - 360.0 * std::round(d / 360.0);
  }
  /// Plane ordinate (Lattice::plane_y) of node `n`: its row's, or a moved node's own.
  [[nodiscard]] double plane_y_deg(NodeId n) const {
    const auto p = static_cast<std::size_t>(n);
    return (node_flags[p] & kNodeMoved) != 0 ? lattice.plane_y_of_lat(rlat_deg[p]) : lattice.plane_y_of(node_j[p]);
  }
  /// Whether some node was moved off its lattice vertex (kNodeMoved).
  [[nodiscard]] bool has_moved_nodes() const {
    for (const std::uint8_t f : node_flags)
      if ((f & kNodeMoved) != 0) return true;
    return false;
  }
  /// Whether an element crosses the seam (has a node at I = 0 drawn at I = nx).
  template <std::size_t K>
  [[nodiscard]] bool crosses_seam(const std::array<NodeId, K>& nodes) const {
    for (const NodeId n : nodes)
      if (unwrapped_i(nodes, n) != node_i[n]) return true;
    return false;
  }
};

}  // namespace aq::mesh

// SPDX-License-Identifier: GPL-3.0-or-later
// The open boundary of a polygon domain moved onto the polygon (README "Regional FE meshes").
//
// The open boundary of a polygon domain runs along the lattice next to the polygon: its edges
// lie between the last pixel inside (centre inside the polygon) and the first outside, so each
// of its nodes is within about half a pixel diagonal of the polygon's boundary, as a staircase
// where the polygon is slanted. snap_open_boundary moves each node of the open segments (their
// end nodes, shared with the land, included) to the nearest point of the polygon's boundary,
// node after node in segment order, and keeps the move only when the mesh stays valid there:
//
//   * every triangle around the node is anticlockwise on the sphere (the geographic formats)
//     and in the lattice plane (λ′ and the plane ordinate: MSH and the preview);
//   * no such triangle gets a smallest angle on the sphere below min(min_angle_deg, its smallest
//     angle before) or a largest angle above max(max_angle_deg, its largest before). 20° is
//     what a whole run moved by the full half pixel gives at worst (a pixel square halved in
//     height: atan(1/2) = 26.6°), so straight stretches move; the staircase's steps, whose two
//     nodes project close together on a slanted edge (a sliver with the node inside), stay.
//     120° is where the model formats' warning starts (README "Meshes for the models");
//   * the node's boundary edges cross or touch no other boundary edge (the open segment stays
//     simple and does not touch itself or the land);
//   * a node that was wet (elevation ≤ wet_max_elevation_m) is wet at its new position.
//
// Nearest point: the edges are straight in lon/lat (as the domain's inside test takes them);
// distances in the local plane (λ·cos φ, φ) of the node. A node within 1e-9° of the polygon is
// already on it and does not move (a polygon equal to a box moves nothing: its files are the
// box's). A kept node stays on its lattice vertex. A moved node gets kNodeMoved, its new lon/lat,
// rlon/rlat (the lattice frame, rotated when the lattice is) and the elevation sampled there;
// (I, J) and the topology do not change. Deterministic: no threads, fixed order; two passes (a
// node refused in the first may move once its neighbours have).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/domain.hpp"
#include "mesh/mesh.hpp"

namespace aq::mesh {

struct OpenSnapOptions {
  double min_angle_deg = 20.0;
  double max_angle_deg = 120.0;
  double wet_max_elevation_m = 0.0;  ///< −mask.min_depth_m
};

struct OpenSnapResult {
  std::int64_t open_nodes = 0;  ///< distinct nodes of the open segments
  std::int64_t on_polygon = 0;  ///< already within 1e-9° of the polygon
  std::int64_t moved = 0;
  std::int64_t kept_orientation = 0;  ///< a triangle around it would turn over
  std::int64_t kept_angle = 0;        ///< an angle would leave the bounds
  std::int64_t kept_crossing = 0;     ///< a boundary edge would cross or touch another
  std::int64_t kept_dry = 0;          ///< the new position is dry
  double max_move_km = 0.0;
  double max_move_lon_deg = 0.0, max_move_lat_deg = 0.0;  ///< where (the node's old position)
  double mean_move_km = 0.0;                              ///< over the moved nodes
  double min_angle_deg = 0.0, max_angle_deg = 0.0;        ///< the bounds used

  [[nodiscard]] std::int64_t kept() const { return kept_orientation + kept_angle + kept_crossing + kept_dry; }
  /// One log line.
  [[nodiscard]] std::string describe() const;
  /// The report's "open_boundary_snap" section.
  [[nodiscard]] Json json() const;
};

/// Geographic elevation (m, negative below sea level) at (lon, lat) in degrees.
using PointElevation = std::function<double(double lon_deg, double lat_deg)>;

/// Moves the open-boundary nodes of the typed mesh `m` onto `rings` (see the top of this file).
/// `rot`: the lattice's rotation (identity without). Needs triangles; squares are not checked
/// (the caller snaps only meshes whose files hold triangles alone).
OpenSnapResult snap_open_boundary(Mesh& m, const std::vector<mask::PolygonRing>& rings, const PoleRotation& rot,
                                  const PointElevation& elevation, const OpenSnapOptions& options);

}  // namespace aq::mesh

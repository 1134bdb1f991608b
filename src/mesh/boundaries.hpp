// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary typing of regional meshes (README "Regional FE meshes"): every boundary edge is
// open, mainland or island, and the loops are cut into the segments the model formats write.
//
//   * An edge is open when the caller's predicate says so; for a regional domain
//     (type_domain_boundaries) when the pixel on its right, outside the wet area, is open water:
//     wet at the datum outside the domain (mask::WetArea::open), so the floodplain of a surge
//     mesh meets the domain edge with land. An open edge is a river (inflow) edge when the second
//     predicate says so (app: that pixel is in the corridor of a mask.channels line). River runs
//     are kept whatever their length (a river's mouth on the domain edge may be a few edges); a
//     short open run next to one joins it; short land gaps merge only open runs.
//   * A land gap shorter than kMinSegmentEdges edges between two open runs becomes open (the two
//     segments merge); then an open run shorter than kMinSegmentEdges becomes land. A loop that
//     is open all round is split into two open segments (SCHISM refuses a looped open segment).
//     Each change is logged with its position.
//   * Land on a loop with open segments is mainland (it touches the domain edge); a loop without
//     open edges is mainland when it is the outer loop or runs anticlockwise in the lattice plane
//     (the outer coast of a separate part of the mesh, e.g. a second seed's sea), else an island.
//   * Segments: every open segment (loop order, each starting where its run starts), then the
//     land pieces and closed loops (loop order). An open segment and its land neighbours share
//     their end nodes (ADCIRC's and SCHISM's convention).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/bitmap.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "mask/lattice_coords.hpp"
#include "mesh/mesh.hpp"

namespace aq::mesh {

inline constexpr std::int64_t kMinSegmentEdges = 3;

struct BoundaryCounts {
  std::int64_t open_segments = 0, open_nodes = 0, open_edges = 0;
  std::int64_t river_segments = 0, river_nodes = 0, river_edges = 0;
  std::int64_t mainland_segments = 0, mainland_edges = 0;
  std::int64_t islands = 0, island_edges = 0;
  std::int64_t merged = 0;  ///< short pieces retyped
};

/// Types every boundary edge of `m` (boundary_edge_type, segments, typed = true). `is_open(a, b)`
/// tells whether the edge a -> b (wet on the left) is on the open boundary, `is_river(a, b)` (when
/// given) whether such an open edge is a river inflow. Logs each merge when `log` is given.
BoundaryCounts type_boundaries(Mesh& m, const std::function<bool(NodeId, NodeId)>& is_open, const Logger* log,
                               const std::function<bool(NodeId, NodeId)>& is_river = {});

/// The pixel on the right of the first lattice step of boundary edge a -> b (wet on the left: the
/// pixel outside the wet area) in `px`; false for a diagonal (after the model cleaning) or
/// degenerate edge and for rows beyond the lattice.
bool edge_right_pixel(const Mesh& m, NodeId a, NodeId b, mask::PixelIJ& px);

/// type_boundaries() for the mesh of a regional domain: the edge a -> b is open when it has a
/// right pixel (edge_right_pixel) for which `open_water(px)` holds: water at the datum outside the
/// domain (mask::WetArea::open for the dense engine, the forest's answers for the forest);
/// everything else is land. Such an open edge is a river inflow when `river(px)` (when given) holds.
BoundaryCounts type_domain_boundaries(Mesh& m, const std::function<bool(const mask::PixelIJ&)>& open_water,
                                      const Logger* log, const std::function<bool(const mask::PixelIJ&)>& river = {});

/// Counts of a typed mesh.
BoundaryCounts boundary_counts(const Mesh& m);

/// One log line: "N open segments (M nodes), K mainland pieces, I islands" (and the river inflows).
std::string describe(const BoundaryCounts& c);

/// The report's "boundaries" section.
Json boundaries_json(const Mesh& m, const BoundaryCounts& c);

/// Types `derived`, a mesh made from the typed mesh `typed` with other node ids (the model
/// cleaning, the geographic mesh's pole cap or merge): an edge is open (a river) when its two
/// lattice vertices ((I, J) -> (I, J)) are those of an open (river) edge of `typed` (new nodes off
/// the lattice, I = J = -1, are never open); the rest is typed as type_boundaries does. No log.
BoundaryCounts type_like(Mesh& derived, const Mesh& typed);

}  // namespace aq::mesh

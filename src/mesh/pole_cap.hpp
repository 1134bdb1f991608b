// SPDX-License-Identifier: GPL-3.0-or-later
// The pole cap: a well-shaped triangulation of the disc around a pole of the lattice system
// (ARCHITECTURE §4.5; issue 11). Without rotation the Arctic is wet up to φ = 90°, and the
// lattice mesh closes it with a row of nodes on φ = 90° (one physical point) and triangles with
// two nodes there (zero area on the Earth). Models cannot run that: ADCIRC blows up on it, and a
// merge of the row into one node leaves a node of valence ~135 (3.7× slower in ADCIRC). The cap
// replaces every element between a full lattice row φ_c and the pole by concentric rings:
//
//   ring 0   o---o---o---o---o---o---o---o     the existing mesh nodes of row φ_c (kept, so the
//            |\ / \ /|\ / \ / \ /|\ / \ /|     rest of the mesh is untouched and conforming)
//   ring 1   o---o-----o---o----o----o---o     n_k ≈ 2π sin(r_k) / s_k nodes at colatitude r_k,
//             \ / \   / \ / \  / \  / \ /      equally spaced in λ; rings s_k·√3/2 apart, so
//   ...           ...                          the triangles are nearly equilateral. The size
//   ring K-1    o---o---o---o---o              s grows from h (the mean spacing of ring 0) by
//                                              0.25 per unit distance towards the pole (about
//   pole        (island: land)                 1.2× per ring), so the cap stays small.
//
// Adjacent rings are joined by merge-by-angle ("zipper"): walking round both rings, add the
// shorter of the two possible next edges (a Delaunay-like choice). The last ring, one step
// from the pole, bounds a polar island: no node sits on the pole. A node there has infinite
// metric factors (1/cos φ) in every model that works in λ–φ coordinates: ADCIRC with ICS = 22
// blows up at the first step on a cap with a pole node, as it did on the lattice mesh's pole row.
//
// Angles are unwrapped from ring 0's first node, so the seam λ0 needs no special case; the
// triangles are anticlockwise in the lattice (λ, φ) plane like every other triangle of the mesh.
// The cap works in the lattice system (rotated coordinates with a rotated pole); geographic
// coordinates and depths are the caller's business (io/geographic_mesh.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace aq::mesh {

struct PoleCap {
  /// New nodes (inner rings from the outside in), lattice-system degrees.
  std::vector<double> rlon_deg, rlat_deg;
  /// Triangles in cap ids: 0..n0-1 are the ring-0 nodes in the order given, n0 + k new node k.
  std::vector<std::array<NodeId, 3>> triangles;
  /// The polar island: the last ring in cap ids, in boundary order (wet area on the left).
  /// Ring 0 itself when the ring is too small for inner rings (then there are no triangles).
  std::vector<NodeId> island;
  double island_radius_deg = 0.0;  ///< colatitude of the last ring (distance to the pole)
  int rings = 0;                   ///< inner rings (without ring 0)
};

/// Triangulates the cap between ring 0 (nodes at lattice longitudes `ring_rlon_deg`, strictly
/// ascending and spanning less than 360°, all at lattice latitude `ring_rlat_deg`) and the
/// island round the pole (`north`: φ = +90°, else −90°). Precondition: at least 3 ring nodes and 0 < |ring_rlat_deg| <
/// 90 on the side of the pole. Throws InternalError when they do not hold.
PoleCap make_pole_cap(const std::vector<double>& ring_rlon_deg, double ring_rlat_deg, bool north);

}  // namespace aq::mesh

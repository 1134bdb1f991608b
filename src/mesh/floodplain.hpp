// SPDX-License-Identifier: GPL-3.0-or-later
// The floodplain of a storm-surge mesh (mask.min_depth_m = −z < 0; README "A storm-surge mesh"):
// the part of the mesh above the datum, as a model sees it. A model interpolates the node depths
// linearly over each triangle (ADCIRC, SCHISM: P1), so the floodplain is where that surface is
// above 0 m:
//
//           1  (z1 > 0)             a triangle with one node above the datum keeps the corner
//          / `.                     1-a-b cut off by the 0 m line a-b, found on edges 1-2 and
//   ~~~~~~a~~~~b~~~~~~ 0 m          1-3 at t = z1 / (z1 − zk) of the way from node 1 (linear);
//        /       `.                 with two nodes above, the triangle less the other corner
//       2 --------- 3  (z2, z3 <= 0)
//
// Areas are geodesic on WGS84 (GeographicLib::PolygonArea) of the cut polygons with straight
// edges in lon/lat. Nodes at exactly 0 m are at the datum, not above it.
#pragma once

#include <cstdint>

#include "core/report.hpp"
#include "mesh/mesh.hpp"

namespace aq::mesh {

struct Floodplain {
  double top_m = 0.0;                          ///< z: the mesh reaches land up to this elevation (−mask.min_depth_m)
  std::int64_t nodes = 0;                      ///< nodes above the datum (elevation > 0): dry at rest, may flood
  std::int64_t triangles = 0;                  ///< triangles with a node above the datum
  double area_km2 = 0.0;                       ///< WGS84 area where the linear surface of node elevations is above 0 m
  double highest_node_m = 0.0;                 ///< the highest node's elevation (<= top_m up to interpolation)
  std::int64_t land_boundary_nodes = 0;        ///< nodes on land (non-open) boundary edges
  std::int64_t land_boundary_nodes_above = 0;  ///< of those, above the datum: the coast on the floodplain
};

/// The floodplain of `mesh` (triangles; geographic node coordinates, elevations in depth_m) for
/// a floodplain up to `top_m` > 0. Parallel over triangles, summed in triangle order: the same
/// for any thread count.
Floodplain floodplain(const Mesh& mesh, double top_m);

/// The report's "floodplain" section.
Json floodplain_json(const Floodplain& f);

}  // namespace aq::mesh

// SPDX-License-Identifier: GPL-3.0-or-later
// The explicit barotropic time step a mesh allows (ARCHITECTURE §4.10): for every triangle the
// shortest edge (great circle on the sphere of radius 6371.0088 km, from the nodes' geographic
// coordinates) over the gravity-wave speed √(g·H), H the deepest of its three nodes (depth
// positive down, at least min_depth_m). The mesh's largest stable step is the minimum over the
// triangles (edges under 1 mm, the lattice's pole row, are skipped); with a time step Δt the Courant number of a
// triangle is √(g·H)·Δt / edge.
//
// With wetting and drying (a floodplain mesh, mask.min_depth_m = −z < 0; README "A storm-surge
// mesh") the water the mesh is built for reaches z above the datum, the top of its floodplain:
// every node then holds H = z − elevation (the ocean's depth plus z; on the floodplain the flood
// depth, at most z), at least min_depth_m, and the step is the same minimum with that H. It is the
// step for the highest water the mesh can hold; at rest (above) a floodplain node is dry and takes
// min_depth_m.
#pragma once

#include <cstdint>
#include <vector>

#include "core/report.hpp"
#include "mesh/mesh.hpp"

namespace aq::mesh {

struct TimeStep {
  double max_stable_dt_s = 0.0;  ///< min over triangles of edge/√(gH)
  std::int64_t limiting_triangle = -1;
  double limiting_edge_m = 0.0, limiting_depth_m = 0.0;
  double limiting_lon_deg = 0.0, limiting_lat_deg = 0.0;  ///< its first node
  double min_depth_m = 0.0;                               ///< the floor of H
  double dt_s = 0.0;                                      ///< the Δt the Courant numbers are for (0: none)
  double courant_max = 0.0;                               ///< Cr_max the counts below compare with
  std::vector<double> courant_percentiles;                ///< Cr at 0, 50, 90, 99, 100 %
  std::int64_t above_courant_max = 0;                     ///< triangles with Cr > Cr_max
  std::vector<std::int64_t> above_by_level;               ///< of those, per quadtree level of their square
  std::int64_t above_touching_coast = 0;                  ///< of those, with a node on a boundary edge
  std::int64_t triangles = 0;
  /// With wetting and drying (flood_level_m > 0): the step with H = max(flood_level_m − elevation,
  /// min_depth_m) at every node, and its limiting triangle.
  struct WettingDrying {
    double flood_level_m = 0.0;  ///< z: water up to this many metres above the datum (−mask.min_depth_m)
    double max_stable_dt_s = 0.0;
    std::int64_t limiting_triangle = -1;
    double limiting_edge_m = 0.0, limiting_depth_m = 0.0;
    double limiting_lon_deg = 0.0, limiting_lat_deg = 0.0;
    double limiting_elevation_m = 0.0;  ///< the highest node of the limiting triangle (at rest)
  };
  WettingDrying wetting_drying;  ///< flood_level_m = 0: none (no floodplain)
};

/// dt per triangle (s): shortest edge / √(g·max(H, min_depth_m)) with H = max node depth.
std::vector<double> triangle_time_steps(const std::vector<double>& lon_deg, const std::vector<double>& lat_deg,
                                        const std::vector<double>& depth_m,
                                        const std::vector<std::array<NodeId, 3>>& triangles, double min_depth_m);

/// The smallest entry of triangle_time_steps (s) and the first triangle holding it (-1 without
/// triangles): the same result, but a triangle's edges are measured only when lower bounds of
/// their lengths (no trigonometry) allow a dt at most the smallest found so far (parallel; the
/// same for any thread count).
struct SmallestTimeStep {
  double dt_s = 0.0;
  std::int64_t triangle = -1;
};
SmallestTimeStep smallest_time_step(const std::vector<double>& lon_deg, const std::vector<double>& lat_deg,
                                    const std::vector<double>& depth_m,
                                    const std::vector<std::array<NodeId, 3>>& triangles, double min_depth_m);

/// The time step of `mesh` (geographic node coordinates, depths = -elevation); `dt_s` > 0 adds
/// the Courant distribution for that step and `courant_max`; `flood_level_m` > 0 (a floodplain up
/// to that elevation) the step with wetting and drying. Parallel; the same for any thread count.
TimeStep time_step(const Mesh& mesh, double min_depth_m, double dt_s, double courant_max, double flood_level_m = 0.0);

Json time_step_json(const TimeStep& t);

}  // namespace aq::mesh

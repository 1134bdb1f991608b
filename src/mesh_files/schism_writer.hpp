// SPDX-License-Identifier: GPL-3.0-or-later
// SCHISM horizontal grid files hgrid.gr3 and hgrid.ll (schism-dev.github.io, "Horizontal grid";
// the reader is aquire_hgrid in SCHISM's src/Hydro/grid_subs.F90). A global mesh is in
// longitude/latitude, which SCHISM runs with ics = 2 (coordinates on the sphere); with ics = 2
// hgrid.gr3 itself holds degrees too, so both files are written with the same content:
//
//   title                              one line
//   NE NP                              triangles, nodes
//   id lon lat depth                   NP lines: 1-based, degrees (λ in [-180, 180)), depth below
//                                      the datum in metres, positive down (negative on a
//                                      floodplain above it: SCHISM wets and dries them itself)
//   id 3 n1 n2 n3                      NE lines: 1-based, anticlockwise seen from outside the sphere
//   0 = number of open boundaries      a global mesh is closed (NOPE = 0, NETA = 0)
//   0 = total number of open boundary nodes
//   NLAND, NVEL                        land boundaries, their total node count
//   nvel ibtype, then nvel node ids    per boundary loop: ibtype 0 land (the outer loop), 1 island
//
// This is the layout of ADCIRC's fort.14, and the file is made by the fort.14 writer
// (fort14_writer.hpp) with SCHISM's names in the comments: each land boundary is one boundary
// loop of the mesh, in loop order (wet area on the left), closed by repeating its first node.
// SCHISM needs every boundary node to start exactly one boundary stretch: a pinch vertex (the
// wet area touching itself at one node) stops it with "Illegal bnd node" (mask.remove_pinches
// = true removes them; mesh_outputs warns). With ics = 2 SCHISM projects the nodes
// stereographically from the South pole for partitioning and rejects a node on that pole; the
// geographic mesh keeps every node off the poles (geographic_mesh.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/fort14_writer.hpp"

namespace aq::io {

struct SchismOptions {
  std::string title = "aquatoria global ocean mesh";  ///< first line (cut to 80 characters)
};

/// The time steps SCHISM runs a mesh with, from the nodes' sizes and depths. SCHISM is
/// semi-implicit (no upper Courant limit for gravity waves) but wants the inverse condition
/// C = √(g·H)·Δt/Δx ≥ 0.4 with momentum advection on (its Eulerian–Lagrangian backtracking is
/// inaccurate for shorter steps; with advection on, the default mesh at C ≈ 0.03–0.05 on the
/// shelves grew spurious elevations of 6–40 m). Per wet node (elevation below 0): H its depth,
/// Δx its shortest edge on the authalic sphere. Δt at which C reaches 0.4 at a share of the wet
/// nodes:
struct SchismTimeStep {
  std::int64_t wet_nodes = 0;
  double dt_half_s = 0.0;  ///< at half of them: the lower bound with advection off (nadv = 0)
  double dt_p95_s = 0.0;   ///< at 95 %: the lower bound with advection on (nadv = 1)
  double dt_all_s = 0.0;   ///< at every one
  /// The upper bound, for either: 1/50 of the M2 period (7.2° of tidal phase a step).
  static constexpr double kMaxDtS = 894.0;

  /// One log line with both ranges (an empty range: advection on is not advised).
  [[nodiscard]] std::string describe() const;
};
SchismTimeStep schism_time_step(const mesh::Mesh& mesh);

/// Writes the triangles of `mesh` in SCHISM's hgrid layout to `path` (used for both hgrid.gr3
/// and hgrid.ll); river inflows are open boundaries there (in the segments' order). Throws like
/// write_fort14. WriteStats::boundary_edges counts the land boundary edges.
/// A `bctides.in` skeleton for a regional mesh (Mesh::typed): no tidal potential, M2 (frequency
/// 1.405189025e-4 rad/s, nodal factor 1, argument 0) on every open segment of the hgrid, in its
/// order, with amplitude 0 and phase 0 at each node (iettype 3, ifltype 0: fill in the
/// amplitudes and phases, or add constituents); a river inflow's boundary is iettype 0, ifltype 2
/// (constant discharge) with a discharge of 0 to fill in. Throws InternalError for a mesh without
/// open segments.
WriteStats write_schism_bctides(const mesh::Mesh& mesh, const std::filesystem::path& path, const std::string& title);

WriteStats write_schism_hgrid(const mesh::Mesh& mesh, const std::filesystem::path& path,
                              const SchismOptions& options = {});
/// The fort.14 writer's options write_schism_hgrid writes with: SCHISM's names (NLAND) and land
/// flags (0 land, 1 island); fort14_boundaries() with them gives the file's boundary lists.
Fort14Options schism_hgrid_layout(const SchismOptions& options = {});

}  // namespace aq::io

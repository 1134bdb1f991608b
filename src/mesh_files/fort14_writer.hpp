// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC grid and boundary information file (fort.14), as described in the ADCIRC technical
// reference (adcirc.github.io/adcirc/technical_reference/input_files/fort14.html):
//
//   AGRID                              title line
//   NE NP                              triangles, nodes
//   JN X Y DP                          NP lines: 1-based id, longitude, latitude (degrees),
//                                      depth below the datum in metres (positive down; negative
//                                      on a floodplain above the datum, mask.min_depth_m < 0:
//                                      ADCIRC with NOLIFA = 2 starts such nodes dry)
//   JE 3 NM1 NM2 NM3                   NE lines: 1-based triangle, anticlockwise
//   NOPE = 0, NETA = 0                 no open boundaries (a global mesh is closed)
//   NBOU, NVEL                         land boundaries, their total node count
//   NVELL IBTYPE, then NVELL node ids  per boundary loop
//
// Choices:
// - Land boundaries: one per boundary loop of the mesh, in loop order (wet area on the left,
//   i.e. anticlockwise around the water), closed by repeating the first node at the end (a
//   convention ADCIRC mesh checkers accept for closed boundaries). IBTYPE 0 (mainland) for the
//   outer loop (Mesh::loops[k].outer, the loop of largest extent), IBTYPE 1 (island) for every
//   other loop, including the pole line φ = 90° of an unrotated mesh, which is a wall at the
//   pole singularity.
// - Longitudes are written wrapped into [-180, 180). Elements at the seam/antimeridian are kept
//   as they are and join nodes near +180 to nodes near -180: that is how global ADCIRC meshes
//   are stored (ADCIRC's global mode, adcirc/adcirc PR #171, corrects the element geometry
//   across the ±180° overlap; OceanMesh2D global meshes use the same layout). No nodes are
//   duplicated, so the mesh stays topologically closed across the seam.
// - Regional meshes (Mesh::typed, README "Regional FE meshes"): NOPE open segments (NETA nodes,
//   each "NVDLL 0" then its nodes in loop order, water on the left), then the land boundaries:
//   mainland pieces between open segments (IBTYPE 20, from the last node of one open segment to
//   the first node of the next: the end nodes are in both lists), closed mainland loops (20) and
//   islands (21), each closed loop with its first node repeated at the end.
// - Pole-row nodes are kept (distinct nodes at latitude 90°); only triangles are written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"

namespace aq::io {

struct Fort14Options {
  std::string title = "aquatoria global ocean mesh";  ///< AGRID (cut to 80 characters, one line)
  /// Names in the comments of the boundary header lines (SCHISM's hgrid.gr3 has the same layout
  /// and calls the land boundary count NLAND: mesh_files/schism_writer.hpp).
  std::string land_count_name = "NBOU";
  /// Regional meshes (Mesh::typed): the land boundary types of mainland pieces and islands
  /// (ADCIRC IBTYPE 20 / 21; SCHISM's land flag 0 / 1).
  int mainland_type = 20, island_type = 21;
  /// River inflows (mesh::BoundaryType::kRiver): in the land list with this IBTYPE (ADCIRC 22:
  /// specified normal flux, essential, free tangential slip; fort.15 then needs NFFR and a flux per
  /// node), or, with rivers_open, in the open list (SCHISM: a flow boundary is an open boundary,
  /// its ifltype set in bctides.in).
  int river_type = 22;
  bool rivers_open = false;
};

/// One boundary list of the file (an open segment, a land boundary), as the file lists it.
struct Fort14Boundary {
  mesh::BoundaryType type = mesh::BoundaryType::kMainland;
  /// Land: IBTYPE (fort.14; Fort14Options::mainland_type / island_type / river_type on a typed mesh, 0 for the
  /// outer loop and 1 for the others on an untyped one); open: 0, written after the node count.
  int flag = 0;
  bool closed = false;        ///< a whole loop: the first node is listed again at the end
  std::vector<NodeId> nodes;  ///< 0-based node ids in the file's order (the closing repeat included)
  std::string comment;        ///< the text after "!" on the list's header line
};

/// The boundary lists of `mesh` in the file's order: the open segments (NOPE of them), then the
/// land boundaries (NBOU). write_fort14 writes exactly these (its NETA and NVEL are their node
/// counts). An untyped mesh: no open segment, one land boundary per non-empty loop.
struct Fort14Boundaries {
  std::vector<Fort14Boundary> open, land;
};
Fort14Boundaries fort14_boundaries(const mesh::Mesh& mesh, const Fort14Options& options = {});

/// Writes the triangles of `mesh` to `path` (a temporary path of an OutputSet). Throws
/// OutputError naming the path on any write failure, InternalError when the mesh has no
/// triangles or inconsistent arrays. WriteStats::boundary_edges counts the land boundary edges.
WriteStats write_fort14(const mesh::Mesh& mesh, const std::filesystem::path& path, const Fort14Options& options = {});

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Gmsh MSH 4.1 writer (ASCII "4.1 0 8" or binary "4.1 1 8", little-endian, size_t = 8 bytes),
// as specified in the Gmsh reference manual, section "MSH file format".
//
// What is written:
//   $MeshFormat, $PhysicalNames (1 1 "coast", 2 2 "ocean", and 2 3 "ocean_squares" when both
//   triangles and squares are written), $Entities, $Nodes, $Elements, [$Periodic],
//   $NodeData "depth_m" (metres, positive down; negative on a floodplain), $ElementData "level" (quadtree level of
//   every triangle/quad), and with a rotated pole $NodeData "lon_deg" / "lat_deg" (geographic).
//
// Entities (all discrete, no parametric coordinates):
//   surface 1  physical "ocean": triangles (type 2), or quads (type 3) for squares only
//   surface 2  physical "ocean_squares": the quads when both kinds are written
//   curve 1    physical "coast": every boundary edge as a 2-node line (type 1)
//   curve 2    the seam λ = λ0: the I = 0 nodes that have a duplicate (plane only)
//   curve 3    the seam copy λ = λ0 + 360: the duplicates (plane only)
//
// Coordinates:
//   kPlane  x = λ, y = φ (degrees; lattice coordinates, i.e. rotated ones with a rotated pole; on
//           the Mercator lattice y is the Mercator ordinate ln tan(π/4 + φ/2) in degrees),
//           z = 0. Elements east of the last column use duplicates of the I = 0 nodes at
//           λ0 + 360 (io/seam_nodes.hpp); $Periodic links curve 3 to curve 2 with the affine
//           translation x + 360 and lists every (duplicate, original) node pair. Pole-row nodes
//           are kept as distinct nodes (they are distinct points of the plane).
//   kSphere x, y, z on the unit sphere from the geographic λ, φ; no duplicates; pole rows are
//           merged into one node per pole and degenerate elements dropped (io/pole_merge.hpp).
//
// Node tags are 1-based: mesh node n has tag n + 1 (compacted after pole merging), duplicate k
// has tag N + 1 + k. Element tags are 1-based: triangles, then quads, then coast lines.
#pragma once

#include <filesystem>

#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/element_kinds.hpp"

namespace aq::io {

enum class MshCoordinates { kPlane, kSphere };

struct MshOptions {
  bool binary = false;
  MshCoordinates coordinates = MshCoordinates::kPlane;
  ElementKinds elements = ElementKinds::kTriangles;
};

/// Writes `mesh` to `path` (a temporary path of an OutputSet). Throws OutputError naming the path
/// on any write failure (including a full disk), InternalError on an inconsistent mesh.
WriteStats write_msh(const mesh::Mesh& mesh, const std::filesystem::path& path, const MshOptions& options = {});

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// FESOM2 mesh files (the reader is read_mesh in FESOM2's src/oce_mesh.F90; its partitioner reads
// the same three files). All are whitespace-separated text read with Fortran list-directed input:
//
//   nod2d.out    n2d                        node count
//                id lon lat flag            n2d lines: 1-based id, geographic degrees
//                                           (λ in [-180, 180)), flag 1 on a boundary (coast or
//                                           the polar island), 0 inside
//   elem2d.out   e2d                        triangle count
//                n1 n2 n3                   e2d lines: 1-based node ids, clockwise seen from
//                                           outside the sphere: the sense FESOM's test_tri
//                                           establishes (it swaps n2 and n3 of every triangle
//                                           that is anticlockwise in its lon–lat plane)
//   aux3d.out    nl                         number of depth levels (≥ 5: FESOM raises every
//                                           depth shallower than level 5 to it)
//                z_1 .. z_nl                one a line, metres, negative below the surface,
//                                           z_1 = 0 (FESOM's zbar; it negates positive lists)
//                depth                      n2d lines: the node's bottom, metres, negative
//                                           (FESOM's sign; it negates positive values, so a node
//                                           with elevation ≥ 0 is written as 0, not as a depth;
//                                           FESOM2 has no wetting and drying, so a floodplain's
//                                           nodes above the datum become water: the app warns)
//
// Rotation: FESOM reads geographic coordinates and rotates them itself into its model frame when
// namelist.config has force_rotation = .true., with Euler angles alphaEuler, betaEuler,
// gammaEuler (degrees; z, then the new x, then the new z: FESOM's gen_modules_rotate_grid.F90).
// fesom_rotation() gives the angles whose model frame is our rotated (lattice) frame, so FESOM
// works on the same rotated sphere the mesh was built on. Without rotation, fesom_rotation() gives
// FESOM's own standard for geographic meshes (force_rotation = .true., 50, 15, −90: the model pole
// on Greenland at 40°W 75°N), what FESOM's namelist.config ships with. FESOM checks the files
// against the setting: with force_rotation = .true. no node may lie within 2.5° of the model
// pole (else "Your input mesh seems to be rotated"), with .false. some must ("seems to be
// unrotated"); both hold for our meshes (the model poles are on land). force_rotation = .false.
// with angles 0, 0, 0 also runs an unrotated mesh (the model pole on the polar island).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"

namespace aq::io {

/// FESOM's default depth levels, metres, positive down (48 levels, 0 to 6250 m, 5 m near the top).
const std::vector<double>& default_fesom_levels_m();

/// The namelist.config rotation that matches the mesh's rotation.
struct FesomRotation {
  bool force_rotation = false;
  double alpha_deg = 0.0, beta_deg = 0.0, gamma_deg = 0.0;  ///< alphaEuler, betaEuler, gammaEuler
  /// "force_rotation = .true., alphaEuler = …, betaEuler = …, gammaEuler = …".
  [[nodiscard]] std::string namelist() const;
};
FesomRotation fesom_rotation(const mesh::RotationInfo& rotation);

/// nod2d.out's flag of every node: 1 on a boundary edge (coast, open boundary, polar island), 0 inside.
std::vector<std::uint8_t> fesom_boundary_flags(const mesh::Mesh& mesh);
/// The open-boundary file's nodes (0-based): the nodes of the open segments in their order, each
/// once; empty for a mesh without open segments.
std::vector<NodeId> fesom_open_boundary_nodes(const mesh::Mesh& mesh);

/// nod2d.out of the triangles' nodes. WriteStats::boundary_edges counts the nodes flagged 1.
WriteStats write_fesom_nod2d(const mesh::Mesh& mesh, const std::filesystem::path& path);
/// elem2d.out.
/// Regional meshes (Mesh::typed): the open-boundary nodes, "N" then N 1-based node indices of
/// nod2d.out, in the order of the open segments (each node once). Throws InternalError for a
/// mesh without open segments.
WriteStats write_fesom_open_boundary(const mesh::Mesh& mesh, const std::filesystem::path& path);

WriteStats write_fesom_elem2d(const mesh::Mesh& mesh, const std::filesystem::path& path);
/// aux3d.out with `levels_m` (positive down: at least 5, from 0, strictly increasing, as the
/// configuration checks output.fesom_levels; InternalError otherwise).
WriteStats write_fesom_aux3d(const mesh::Mesh& mesh, const std::filesystem::path& path,
                             const std::vector<double>& levels_m);

}  // namespace aq::io

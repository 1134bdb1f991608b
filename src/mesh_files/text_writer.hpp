// SPDX-License-Identifier: GPL-3.0-or-later
// Plain-text mesh, in the spirit of the seed's own output (seed 002: node list with coordinates
// and depth, element list, boundary): self-describing, one record per line, whitespace
// separated, '#' starts a comment line. Format version 1:
//
//   # aquatoria mesh, plain text format 1
//   # lattice lon0_deg=<λ0> step0_deg=<Δ0> levels=<L> nx=<nx> ny=<ny> [kind=mercator y0_deg=<y0>]
//     (Mercator lattice: row J at the Mercator ordinate y0 + J·Δ0/2^L degrees, φ = atan(sinh y))
//   # rotation none | rotation pole_lon_deg=<λp> pole_lat_deg=<φp>
//   [# floodplain: the mesh reaches land up to <z> m above the datum; depth_m is negative there ...]
//     (only for a floodplain mesh, mask.min_depth_m = -z < 0)
//   # ids are 0-based; depth_m is positive down; lon/lat are geographic degrees; i j are the
//   # integer lattice coordinates (rotated system with a rotated pole);
//   # flags: 1 boundary, 2 midside (hanging) node, 4 centre node, 8 pole, 16 seam
//   nodes <N>
//   # id lon_deg lat_deg depth_m flags i j
//   <N lines>
//   triangles <T>                         (when triangles are written)
//   # id level n1 n2 n3                   (anticlockwise)
//   <T lines>
//   squares <S>                           (when squares are written)
//   # id level sw se ne nw mid_s mid_e mid_n mid_w   (midside node of each side or -1)
//   <S lines>
//   loops <K>
//   # id outer pole edges                 (outer, pole: 0/1; edges in the loop)
//   <K lines>
//   boundary_edges <B>
//   # loop a b                            (wet area on the left of a -> b)
//   <B lines>
//
// Numbers are printed in their shortest exact decimal form, so the file round-trips.
#pragma once

#include <filesystem>

#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/element_kinds.hpp"

namespace aq::io {

struct TextOptions {
  ElementKinds elements = ElementKinds::kTriangles;
};

/// Writes `mesh` to `path` (a temporary path of an OutputSet). Throws OutputError naming the path
/// on any write failure, InternalError on an inconsistent mesh.
WriteStats write_text(const mesh::Mesh& mesh, const std::filesystem::path& path, const TextOptions& options = {});

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// VTK XML UnstructuredGrid writer (.vtu, file version 1.0, header_type UInt64, little-endian),
// for ParaView and the VTK readers (vtkXMLUnstructuredGridReader). All arrays are in one
// <AppendedData encoding="raw"> block (each array: a UInt64 byte count, then the values), which
// is VTK's own default layout and the fastest to write and read.
//
// What is written:
//   Points      x, y, z on the unit sphere (default) or WGS84 Earth-centred Earth-fixed metres
//               (GeographicLib::Geocentric, height 0) from the geographic λ, φ: the seam vanishes.
//   Cells       triangles (VTK_TRIANGLE = 5); squares as VTK_QUAD (9), or VTK_POLYGON (7) with
//               their hanging nodes inserted (io/element_kinds.hpp) so the cells are conforming.
//   PointData   depth_m (Float64, positive down; negative on a floodplain), flags (UInt8, mesh::NodeFlag bits),
//               lon_deg, lat_deg (Float64, geographic)
//   CellData    level (UInt8, quadtree level); with both kinds also kind (UInt8: 0 triangle,
//               1 square)
// Poles: the nodes of a pole row are one point in 3-D; they are merged into one node per pole
// and cells that become degenerate are dropped (io/pole_merge.hpp); a square losing a corner
// becomes a triangle. The counts are returned in WriteStats (merged_pole_nodes,
// dropped_elements). Connectivity and offsets are Int64.
#pragma once

#include <filesystem>
#include <string_view>

#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/element_kinds.hpp"

namespace aq::io {

/// output.vtu_coordinates (config/kinds.hpp): the unit sphere or WGS84 ECEF metres.
using config::VtuCoordinates;

struct VtuOptions {
  VtuCoordinates coordinates = VtuCoordinates::kUnitSphere;
  ElementKinds elements = ElementKinds::kTriangles;
};

/// Writes `mesh` to `path` (a temporary path of an OutputSet). Throws OutputError naming the path
/// on any write failure, InternalError on an inconsistent mesh.
WriteStats write_vtu(const mesh::Mesh& mesh, const std::filesystem::path& path, const VtuOptions& options = {});

}  // namespace aq::io

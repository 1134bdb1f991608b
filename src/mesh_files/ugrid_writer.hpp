// SPDX-License-Identifier: GPL-3.0-or-later
// UGRID-1.0 netCDF writer (CF-1.8, "Conventions = CF-1.8 UGRID-1.0"), netCDF-C API. By default
// netCDF-4 (HDF5) with every array chunked (65536 rows of the first dimension, whole rows) and
// compressed (shuffle + deflate at UgridOptions::deflate, output.ugrid_deflate): a global mesh of
// tens of millions of faces is then a fraction of its raw size and still read by ncdump, CDO and
// xarray/uxarray. deflate = 0 writes the classic 64-bit-offset format (uncompressed; netCDF-4 with
// 64-bit indices only when the mesh has more than 2^31-1 nodes or faces) for old readers. The
// file is byte-for-byte reproducible (no dates in `history`; netCDF-4 tracks no object times).
//
// What is written (names for the primary topology "mesh"):
//   mesh                  dummy int, cf_role = "mesh_topology", topology_dimension = 2,
//                         node_coordinates, face_node_connectivity, face_dimension,
//                         edge_node_connectivity, edge_dimension, boundary_node_connectivity,
//                         face_coordinates
//   mesh_node_x/_y        geographic λ, φ of every node (standard_name longitude / latitude)
//   mesh_node_rlon/_rlat  rotated (lattice) coordinates, only with a rotated pole, described by
//                         the grid mapping `rotated_pole` (rotated_latitude_longitude with
//                         north_pole_grid_longitude = 180: core/rotation.hpp puts the geographic
//                         North pole at λ' = 180°)
//   mesh_face_nodes       0-based (start_index = 0) anticlockwise face corners; triangles
//                         (3 columns) or, for squares, polygons with their hanging nodes
//                         (io/element_kinds.hpp, up to 8 columns, padded with _FillValue = -1)
//   mesh_edge_nodes       every unique edge once (0-based), in face order
//   mesh_boundary_nodes   the boundary (coast) edges a -> b, wet area on the left (0-based),
//                         and mesh_boundary_loop: the loop id of each
//   mesh_face_x/_y        face centres, seam-aware: the mean of the corners in the lattice plane
//                         with I unwrapped (Mesh::unwrapped_i), mapped to geographic coordinates
//                         (longitudes in [λ0, λ0 + 360) like the nodes)
//   mesh_face_x_bnds/_y   the corners as CF cell bounds, longitudes unwrapped to within 180° of
//                         the centre (so a face across the antimeridian is continuous), padded by
//                         repeating the last corner; these make CDO see an unstructured grid
//   depth                 on nodes, sea_floor_depth_below_geoid, metres, positive down (no
//                         `positive` attribute: that marks a vertical axis for CF and CDO);
//                         negative on a floodplain above the datum (mask.min_depth_m < 0),
//                         which a `comment` attribute then states with its top elevation
//   node_flags            on nodes, CF flag_masks (boundary midside centre pole seam)
//   level                 on faces, the quadtree level
//   crs                   WGS84 latitude_longitude (EPSG:4326) grid mapping
// With both triangles and squares, a second topology "mesh_squares" (faces = square polygons,
// its own edges, centres, bounds and `level_squares`) shares the node variables.
//
// Faces are given in geographic coordinates, so a face at the seam (or, with a rotated pole,
// anywhere the antimeridian passes) lists nodes with longitudes on both sides of ±180°: that
// is allowed by UGRID (connectivity is topological); draw such faces with the unwrapped
// mesh_face_x_bnds or in 3-D. Pole-row nodes are kept as distinct nodes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "io/dataset.hpp"
#include "io/write_stats.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/element_kinds.hpp"

namespace aq::io {

struct UgridOptions {
  ElementKinds elements = ElementKinds::kTriangles;
  std::string title = "aquatoria global ocean mesh";
  std::string history = "written by aquatoria";  ///< no timestamp: outputs are reproducible
  std::string source = "aquatoria";              ///< e.g. program version and input raster
  int deflate = 1;  ///< 0 = classic 64-bit offset, uncompressed; 1..9 = netCDF-4, shuffle + deflate level
  std::string what = "in memory";  ///< where the dataset goes, for messages (write_ugrid: the path)
};

/// What ugrid_dataset described.
struct UgridCounts {
  std::int64_t nodes = 0, faces = 0, boundary_edges = 0;
};

/// Describes the UGRID dataset of `mesh` into `sink` (io/dataset.hpp): the dimensions, variables,
/// attributes and values write_ugrid puts into its file, in the same order, so a MemoryDataset
/// holds the file's contents (the Python package's to_xarray). Throws InternalError on an empty or
/// inconsistent mesh, Cancelled between blocks of faces when the run is asked to stop
/// (core/cancel.hpp), and what the sink throws.
UgridCounts ugrid_dataset(const mesh::Mesh& mesh, const UgridOptions& options, DatasetSink& sink);

/// Writes `mesh` to `path` (a temporary path of an OutputSet). Throws OutputError naming the path
/// on any netCDF failure (including a full disk), InternalError on an empty or inconsistent mesh.
WriteStats write_ugrid(const mesh::Mesh& mesh, const std::filesystem::path& path, const UgridOptions& options = {});

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// The meshes of a run handed to Python as dicts of numpy arrays (python/aquatoria/_mesh.py wraps
// them): a mesh::Mesh as it is (the lattice mesh, the geographic mesh), a model format's mesh as
// its files hold it (the writers' own functions make the numbers: mesh_files/model_columns.hpp,
// fort14_boundaries, fesom_boundary_flags, ...), and a MemoryDataset (the UGRID file's contents)
// as dimensions, variables and attributes for xarray.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "io/memory_dataset.hpp"
#include "mesh/mesh.hpp"
#include "mesh/model_cleaning.hpp"

namespace aq::python {

namespace py = pybind11;

/// Node columns made once for a mesh (kept by the run, viewed by numpy): longitude and latitude
/// interleaved ((n, 2) rows) and the depth positive down, as the UGRID file stores them.
struct NodeColumns {
  std::vector<double> lonlat, depth;
  explicit NodeColumns(const mesh::Mesh& m);
};

/// Views of `m`'s arrays (owner keeps them alive): "nodes" (n, 2) lon/lat, "lon", "lat", "rlon",
/// "rlat", "node_i", "node_j", "depth" (positive down), "elevation", "node_flags", "triangles"
/// (m, 3), "level", "squares" (s, 4), "square_level", "square_midside" (s, 4), "boundary_edges"
/// (b, 2), "boundary_edge_loop", "boundary_edge_type" (typed meshes), "boundaries" (list of dicts:
/// the typed segments of a regional mesh, else one per loop), "pinch_nodes", "typed".
py::dict mesh_dict(const mesh::Mesh& m, const NodeColumns& columns, py::handle owner);

/// The model formats the arrays can be asked for.
enum class ModelFormat { kFort14, kSchism, kFesom };
/// "fort14" (or "adcirc"), "schism" (or "gr3"), "fesom" (or "fesom2"); ConfigError naming the
/// value and the names otherwise.
ModelFormat parse_model_format(const std::string& name);
const char* model_format_name(ModelFormat f);

/// The mesh `model` (the geographic triangles `geographic` cleaned for the models) as the files of
/// `format` hold it: "nodes" (n, 2) longitude in [-180, 180) and latitude, "depth" (the file's
/// column: fort.14/gr3 positive down, FESOM's aux3d bottom negative), "triangles" (0-based, the
/// file's corner order), "boundaries" (the file's boundary lists in order: dicts with type, flag,
/// closed, nodes (0-based, a closed list repeats its first node), comment), "geographic_node" and
/// "geographic_triangle" (where each node / triangle is in `geographic`); FESOM also
/// "boundary_flag" (nod2d.out's column), "open_nodes" (the open-boundary file's list) and
/// "levels" (aux3d.out's, m, positive down).
py::dict model_dict(const mesh::ModelMesh& model, const mesh::Mesh& geographic, ModelFormat format,
                    const std::vector<double>& fesom_levels_m, py::handle owner);

/// A dataset's contents for xarray: {"dims": [(name, length)], "variables": [(name, dims, array,
/// attrs)], "attrs": {...}}; arrays are views of `dataset`'s buffers (kept alive by the capsule),
/// attributes are str, numpy scalars (one value) or numpy arrays, typed as netCDF4 reads them.
py::dict dataset_dict(std::shared_ptr<io::MemoryDataset> dataset);

}  // namespace aq::python

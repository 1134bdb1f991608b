// SPDX-License-Identifier: GPL-3.0-or-later
// The meshes of a run as numpy arrays (see mesh_arrays.hpp).
#include "mesh_arrays.hpp"

#include <pybind11/stl.h>

#include <fmt/format.h>

#include <cstdint>
#include <utility>

#include "core/error.hpp"
#include "io/depth.hpp"
#include "mesh_files/fesom_writer.hpp"
#include "mesh_files/fort14_writer.hpp"
#include "mesh_files/model_columns.hpp"
#include "mesh_files/schism_writer.hpp"
#include "python_common.hpp"

namespace aq::python {

namespace {

const char* type_name(mesh::BoundaryType t) {
  switch (t) {
    case mesh::BoundaryType::kOpen:
      return "open";
    case mesh::BoundaryType::kIsland:
      return "island";
    case mesh::BoundaryType::kMainland:
      return "mainland";
    case mesh::BoundaryType::kRiver:
      return "river";
  }
  return "mainland";
}

// A numpy array owning a copy of `v`.
template <typename T>
py::array owned(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

template <typename T, std::size_t K>
py::array rows_view(const std::vector<std::array<T, K>>& v, py::handle owner) {
  static_assert(sizeof(std::array<T, K>) == K * sizeof(T));
  return view(v.empty() ? static_cast<const T*>(nullptr) : v.front().data(),
              {static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(K)}, owner);
}

template <typename T>
py::array vec_view(const std::vector<T>& v, py::handle owner) {
  return view(v.empty() ? static_cast<const T*>(nullptr) : v.data(), {static_cast<py::ssize_t>(v.size())}, owner);
}

}  // namespace

NodeColumns::NodeColumns(const mesh::Mesh& m) : lonlat(2 * m.lon_deg.size()), depth(m.depth_m.size()) {
  for (std::size_t k = 0; k < m.lon_deg.size(); ++k) {
    lonlat[2 * k] = m.lon_deg[k];
    lonlat[2 * k + 1] = m.lat_deg[k];
    depth[k] = io::depth_below_datum_m(m.depth_m[k]);
  }
}

py::dict mesh_dict(const mesh::Mesh& m, const NodeColumns& columns, py::handle owner) {
  py::dict d;
  const auto n = static_cast<py::ssize_t>(m.node_count());
  d["nodes"] = view(columns.lonlat.empty() ? nullptr : columns.lonlat.data(), {n, 2}, owner);
  d["depth"] = vec_view(columns.depth, owner);
  d["lon"] = vec_view(m.lon_deg, owner);
  d["lat"] = vec_view(m.lat_deg, owner);
  d["rlon"] = vec_view(m.rlon_deg, owner);
  d["rlat"] = vec_view(m.rlat_deg, owner);
  d["node_i"] = vec_view(m.node_i, owner);
  d["node_j"] = vec_view(m.node_j, owner);
  d["elevation"] = vec_view(m.depth_m, owner);
  d["node_flags"] = vec_view(m.node_flags, owner);
  d["triangles"] = rows_view(m.triangles, owner);
  d["level"] = vec_view(m.triangle_level, owner);
  d["squares"] = rows_view(m.squares, owner);
  d["square_level"] = vec_view(m.square_level, owner);
  d["square_midside"] = rows_view(m.square_midside, owner);
  d["boundary_edges"] = rows_view(m.boundary_edges, owner);
  d["boundary_edge_loop"] = vec_view(m.boundary_edge_loop, owner);
  d["pinch_nodes"] = vec_view(m.pinch_nodes, owner);
  d["typed"] = m.typed;
  d["floodplain_top_m"] = m.floodplain_top_m;
  py::list boundaries;
  if (m.typed) {
    std::vector<std::uint8_t> types(m.boundary_edge_type.size());
    for (std::size_t k = 0; k < types.size(); ++k) types[k] = static_cast<std::uint8_t>(m.boundary_edge_type[k]);
    d["boundary_edge_type"] = owned(types);
    for (const auto& sg : m.segments) {
      py::dict b;
      b["type"] = type_name(sg.type);
      b["nodes"] = vec_view(sg.nodes, owner);
      b["closed"] = sg.closed;
      b["loop"] = sg.loop;
      b["pole"] = m.loops[static_cast<std::size_t>(sg.loop)].pole;
      boundaries.append(b);
    }
  } else {
    for (std::size_t l = 0; l < m.loops.size(); ++l) {
      const auto& loop = m.loops[l];
      py::dict b;
      b["type"] = loop.outer ? "mainland" : "island";
      b["nodes"] = vec_view(loop.nodes, owner);
      b["closed"] = true;
      b["loop"] = static_cast<std::int64_t>(l);
      b["pole"] = loop.pole;
      boundaries.append(b);
    }
  }
  d["boundaries"] = boundaries;
  return d;
}

ModelFormat parse_model_format(const std::string& name) {
  if (name == "fort14" || name == "adcirc") return ModelFormat::kFort14;
  if (name == "schism" || name == "gr3") return ModelFormat::kSchism;
  if (name == "fesom" || name == "fesom2") return ModelFormat::kFesom;
  throw ConfigError(fmt::format(
      "model_mesh: unknown model format \"{}\" (known: fort14 or adcirc, schism or gr3, fesom or fesom2)", name));
}

const char* model_format_name(ModelFormat f) {
  switch (f) {
    case ModelFormat::kFort14:
      return "fort14";
    case ModelFormat::kSchism:
      return "schism";
    case ModelFormat::kFesom:
      return "fesom";
  }
  return "fort14";
}

py::dict model_dict(const mesh::ModelMesh& model, const mesh::Mesh& geographic, ModelFormat format,
                    const std::vector<double>& fesom_levels_m, py::handle owner) {
  const mesh::Mesh& m = model.mesh();
  const auto n = static_cast<std::size_t>(m.node_count());
  const auto nt = m.triangles.size();
  const bool fesom = format == ModelFormat::kFesom;
  py::array_t<double> nodes({static_cast<py::ssize_t>(n), py::ssize_t{2}});
  py::array_t<double> depth(static_cast<py::ssize_t>(n));
  py::array_t<std::int64_t> geo_node(static_cast<py::ssize_t>(n));
  py::array_t<std::int64_t> geo_triangle(static_cast<py::ssize_t>(nt));
  py::array triangles;
  if (fesom) triangles = py::array_t<std::int64_t>({static_cast<py::ssize_t>(nt), py::ssize_t{3}});
  {
    double* xy = nodes.mutable_data();
    double* z = depth.mutable_data();
    std::int64_t* gn = geo_node.mutable_data();
    std::int64_t* gt = geo_triangle.mutable_data();
    auto* ft = fesom ? static_cast<std::int64_t*>(triangles.mutable_data()) : nullptr;
    const py::gil_scoped_release release;
    for (std::size_t k = 0; k < n; ++k) {
      xy[2 * k] = io::model_lon_deg(m.lon_deg[k]);
      xy[2 * k + 1] = m.lat_deg[k];
      z[k] = fesom ? io::fesom_bottom_m(m.depth_m[k]) : io::fort14_depth_m(m.depth_m[k]);
    }
    // Where the nodes and triangles came from: a cleaned triangle keeps its corners' order.
    const auto& src = model.source_triangle();
    for (std::size_t t = 0; t < nt; ++t) {
      const auto s = src.empty() ? t : static_cast<std::size_t>(src[t]);
      gt[t] = static_cast<std::int64_t>(s);
      for (std::size_t c = 0; c < 3; ++c) gn[m.triangles[t][c]] = geographic.triangles[s][c];
      if (ft != nullptr) {
        const auto f = io::fesom_triangle(m.triangles[t]);
        for (std::size_t c = 0; c < 3; ++c) ft[3 * t + c] = f[c];
      }
    }
  }
  if (!fesom) triangles = rows_view(m.triangles, owner);
  triangles.attr("setflags")(py::arg("write") = false);

  py::dict d;
  d["format"] = model_format_name(format);
  d["floodplain_top_m"] = model.mesh().floodplain_top_m;
  d["nodes"] = nodes;
  d["depth"] = depth;
  d["triangles"] = triangles;
  d["geographic_node"] = geo_node;
  d["geographic_triangle"] = geo_triangle;
  const io::Fort14Boundaries lists =
      io::fort14_boundaries(m, format == ModelFormat::kSchism ? io::schism_hgrid_layout() : io::Fort14Options{});
  py::list boundaries;
  for (const auto* group : {&lists.open, &lists.land}) {
    for (const auto& l : *group) {
      py::dict b;
      b["type"] = type_name(l.type);
      b["open"] = group == &lists.open;  // a river is in the open list of hgrid.gr3, the land list of fort.14
      b["flag"] = l.flag;
      b["closed"] = l.closed;
      b["nodes"] = owned(l.nodes);
      b["comment"] = l.comment;
      boundaries.append(b);
    }
  }
  d["boundaries"] = boundaries;
  if (fesom) {
    d["boundary_flag"] = owned(io::fesom_boundary_flags(m));
    d["open_nodes"] = owned(io::fesom_open_boundary_nodes(m));
    d["levels"] = owned(fesom_levels_m.empty() ? io::default_fesom_levels_m() : fesom_levels_m);
  }
  return d;
}

namespace {

py::dtype dtype_of(io::DataType t) {
  switch (t) {
    case io::DataType::kByte:
      return py::dtype::of<std::int8_t>();
    case io::DataType::kShort:
      return py::dtype::of<std::int16_t>();
    case io::DataType::kInt:
      return py::dtype::of<std::int32_t>();
    case io::DataType::kInt64:
      return py::dtype::of<std::int64_t>();
    case io::DataType::kDouble:
      return py::dtype::of<double>();
  }
  return py::dtype::of<double>();
}

// An attribute as netCDF4-python reads it: text as str, one number as a numpy scalar of its type,
// several as a numpy array.
py::object attribute_value(const io::MemoryDataset::Attribute& a) {
  if (a.is_text) return py::str(a.text);
  py::array values = py::array_t<double>(static_cast<py::ssize_t>(a.values.size()), a.values.data());
  values = values.attr("astype")(dtype_of(a.type));
  if (a.values.size() == 1) return values[py::int_(0)];
  return values;
}

py::dict attributes(const std::vector<io::MemoryDataset::Attribute>& list) {
  py::dict d;
  for (const auto& a : list) d[py::str(a.name)] = attribute_value(a);
  return d;
}

}  // namespace

py::dict dataset_dict(std::shared_ptr<io::MemoryDataset> dataset) {
  // The dataset lives as long as some array views it.
  auto* keep = new std::shared_ptr<io::MemoryDataset>(dataset);
  const py::capsule owner(keep, [](void* p) { delete static_cast<std::shared_ptr<io::MemoryDataset>*>(p); });
  const auto& dims = dataset->dimensions();
  py::list dim_list;
  for (const auto& dim : dims) dim_list.append(py::make_tuple(dim.name, dim.length));
  py::list vars;
  for (auto& v : dataset->variables()) {
    std::vector<py::ssize_t> shape, strides;
    py::tuple names(v.dims.size());
    for (std::size_t k = 0; k < v.dims.size(); ++k) {
      const auto& dim = dims[static_cast<std::size_t>(v.dims[k])];
      shape.push_back(static_cast<py::ssize_t>(dim.length));
      names[k] = py::str(dim.name);
    }
    strides.resize(shape.size());
    auto s = static_cast<py::ssize_t>(io::data_type_size(v.type));
    for (std::size_t k = shape.size(); k-- > 0;) {
      strides[k] = s;
      s *= shape[k];
    }
    py::array a(dtype_of(v.type), shape, strides, v.data.empty() ? nullptr : v.data.data(), owner);
    vars.append(py::make_tuple(v.name, names, a, attributes(v.attributes)));
  }
  py::dict d;
  d["dims"] = dim_list;
  d["variables"] = vars;
  d["attrs"] = attributes(dataset->global_attributes());
  return d;
}

}  // namespace aq::python

// SPDX-License-Identifier: GPL-3.0-or-later
// Nesting data netCDF writer and reader; schema in nesting_netcdf.hpp. Every nc_* status is
// checked; errors name the path and carry nc_strerror.
#include "grid_files/nesting_netcdf.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <cmath>
#include <limits>
#include <string_view>

#include "core/error.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace {

namespace fs = std::filesystem;

struct NestingVarSpec {
  const char* name;
  nc_type type;
  bool per_vertex;
  const char* long_name;
  const char* units;  // nullptr: none
};

constexpr NestingVarSpec kNestingVars[] = {
    {"point_type", NC_BYTE, false, "C-grid point type of the boundary point", nullptr},
    {"boundary", NC_BYTE, false, "ROMS open boundary of the point", nullptr},
    {"xi_index", NC_INT, false, "0-based xi index into the point type's ROMS array", nullptr},
    {"eta_index", NC_INT, false, "0-based eta index into the point type's ROMS array", nullptr},
    {"lon", NC_DOUBLE, false, "longitude of the boundary point", "degrees_east"},
    {"lat", NC_DOUBLE, false, "latitude of the boundary point", "degrees_north"},
    {"x", NC_DOUBLE, false, "x of the boundary point in the regional projection plane", "1"},
    {"y", NC_DOUBLE, false, "y of the boundary point in the regional projection plane", "1"},
    {"element", NC_INT64, false, "0-based global mesh triangle containing the point (-1: outside the wet mesh)",
     nullptr},
    {"element_nodes", NC_INT64, true, "0-based global mesh nodes of the triangle (anticlockwise)", nullptr},
    {"weights", NC_DOUBLE, true, "barycentric weights of element_nodes in the global lattice plane", "1"},
    {"element_level", NC_BYTE, false, "quadtree level of the global element (-1: outside)", nullptr},
    {"global_element_size", NC_DOUBLE, false, "leg length of the global element", "m"},
    {"regional_cell_size", NC_DOUBLE, false, "regional grid cell size at the point", "m"},
    {"refinement_ratio", NC_DOUBLE, false, "global_element_size / regional_cell_size", "1"},
};

}  // namespace

void write_nesting(const fs::path& path, const NestingFile& d) {
  const std::size_t n = d.size();
  const bool ok = d.boundary.size() == n && d.element_level.size() == n && d.xi_index.size() == n &&
                  d.eta_index.size() == n && d.lon.size() == n && d.lat.size() == n && d.x.size() == n &&
                  d.y.size() == n && d.element.size() == n && d.element_nodes.size() == n && d.weights.size() == n &&
                  d.global_element_size_m.size() == n && d.regional_cell_size_m.size() == n &&
                  d.refinement_ratio.size() == n;
  if (!ok) throw InternalError(fmt::format("write_nesting {}: per-point arrays differ in length", path.string()));

  NcFile nc;
  nc_check<OutputError>(nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4, nc.out()), path, "create");
  const int id = nc.id();
  int dim_p = -1, dim_v = -1;
  nc_check<OutputError>(nc_def_dim(id, "point", n, &dim_p), path, "dimension point");  // 0: unlimited, empty
  nc_check<OutputError>(nc_def_dim(id, "vertex", 3, &dim_v), path, "dimension vertex");
  std::vector<int> vars;
  for (const NestingVarSpec& v : kNestingVars) {
    int var = -1;
    const int dims[2] = {dim_p, dim_v};
    nc_check<OutputError>(nc_def_var(id, v.name, v.type, v.per_vertex ? 2 : 1, dims, &var), path,
                          fmt::format("define variable {}", v.name));
    put_text(id, var, "long_name", v.long_name, path);
    if (v.units != nullptr) put_text(id, var, "units", v.units, path);
    vars.push_back(var);
  }
  {
    const signed char fv[3] = {0, 1, 2};
    nc_check<OutputError>(nc_put_att_schar(id, vars[0], "flag_values", NC_BYTE, 3, fv), path, "flag_values");
    put_text(id, vars[0], "flag_meanings", "rho u v", path);
    const signed char bv[4] = {1, 2, 3, 4};
    nc_check<OutputError>(nc_put_att_schar(id, vars[1], "flag_values", NC_BYTE, 4, bv), path, "flag_values");
    put_text(id, vars[1], "flag_meanings", "west south east north", path);
    // The points outside the wet global mesh hold -1 and NaN: declared fill values, so CF readers
    // (xarray, CDO, ncview) mask them instead of taking them for data.
    const long long no_element = -1;
    for (const int v : {vars[8], vars[9]})
      nc_check<OutputError>(nc_put_att_longlong(id, v, "_FillValue", NC_INT64, 1, &no_element), path, "_FillValue");
    const signed char no_level = -1;
    nc_check<OutputError>(nc_put_att_schar(id, vars[11], "_FillValue", NC_BYTE, 1, &no_level), path, "_FillValue");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const int v : {vars[12], vars[14]})
      nc_check<OutputError>(nc_put_att_double(id, v, "_FillValue", NC_DOUBLE, 1, &nan), path, "_FillValue");
    put_text(id, vars[4], "standard_name", "longitude", path);
    put_text(id, vars[5], "standard_name", "latitude", path);
  }
  put_text(id, NC_GLOBAL, "Conventions", "CF-1.8", path);
  put_text(id, NC_GLOBAL, "title", d.title, path);
  if (!d.history.empty()) put_text(id, NC_GLOBAL, "history", d.history, path);
  put_attributes(id, NC_GLOBAL, d.attributes, path);
  nc_check<OutputError>(nc_enddef(id), path, "end of definitions");
  if (n > 0) {
    std::vector<long long> nodes(3 * n);
    std::vector<double> w(3 * n);
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t q = 0; q < 3; ++q) {
        nodes[3 * k + q] = d.element_nodes[k][q];
        w[3 * k + q] = d.weights[k][q];
      }
    }
    std::vector<long long> element(d.element.begin(), d.element.end());
    nc_check<OutputError>(nc_put_var_schar(id, vars[0], d.point_type.data()), path, "point_type");
    nc_check<OutputError>(nc_put_var_schar(id, vars[1], d.boundary.data()), path, "boundary");
    nc_check<OutputError>(nc_put_var_int(id, vars[2], d.xi_index.data()), path, "xi_index");
    nc_check<OutputError>(nc_put_var_int(id, vars[3], d.eta_index.data()), path, "eta_index");
    nc_check<OutputError>(nc_put_var_double(id, vars[4], d.lon.data()), path, "lon");
    nc_check<OutputError>(nc_put_var_double(id, vars[5], d.lat.data()), path, "lat");
    nc_check<OutputError>(nc_put_var_double(id, vars[6], d.x.data()), path, "x");
    nc_check<OutputError>(nc_put_var_double(id, vars[7], d.y.data()), path, "y");
    nc_check<OutputError>(nc_put_var_longlong(id, vars[8], element.data()), path, "element");
    nc_check<OutputError>(nc_put_var_longlong(id, vars[9], nodes.data()), path, "element_nodes");
    nc_check<OutputError>(nc_put_var_double(id, vars[10], w.data()), path, "weights");
    nc_check<OutputError>(nc_put_var_schar(id, vars[11], d.element_level.data()), path, "element_level");
    nc_check<OutputError>(nc_put_var_double(id, vars[12], d.global_element_size_m.data()), path, "global_element_size");
    nc_check<OutputError>(nc_put_var_double(id, vars[13], d.regional_cell_size_m.data()), path, "regional_cell_size");
    nc_check<OutputError>(nc_put_var_double(id, vars[14], d.refinement_ratio.data()), path, "refinement_ratio");
  }
  nc_check<OutputError>(nc.close(), path, "close");
}

NestingFile read_nesting(const fs::path& path) {
  NcFile nc;
  open_for_reading(path, nc);
  const int id = nc.id();
  int dim_p = -1;
  std::size_t n = 0;
  nc_check<InputError>(nc_inq_dimid(id, "point", &dim_p), path, "dimension point");
  nc_check<InputError>(nc_inq_dimlen(id, dim_p, &n), path, "dimension point");
  check_declared_size(path, 20.0 * static_cast<double>(n), fmt::format("{} nesting points", n));
  // A per-point variable: (point) or (point, 3) as write_nesting makes it; any other shape would
  // make nc_get_var write past the buffers sized for n points.
  const auto var = [&](const char* name) {
    int v = -1;
    nc_check<InputError>(nc_inq_varid(id, name, &v), path, fmt::format("variable {}", name));
    int ndims = 0;
    int dims[NC_MAX_VAR_DIMS];
    nc_check<InputError>(nc_inq_var(id, v, nullptr, nullptr, &ndims, dims, nullptr), path, name);
    bool ok = false, per_vertex = false;
    for (const NestingVarSpec& spec : kNestingVars) {
      if (std::string_view(spec.name) != name) continue;
      per_vertex = spec.per_vertex;
      ok = ndims == (per_vertex ? 2 : 1) && dims[0] == dim_p;
      if (ok && per_vertex) {
        std::size_t len = 0;
        ok = nc_inq_dimlen(id, dims[1], &len) == NC_NOERR && len == 3;
      }
    }
    if (!ok)
      throw InputError(fmt::format("{}: variable {} is not of shape ({}) as in a nesting file", path.string(), name,
                                   per_vertex ? "point, 3" : "point"));
    return v;
  };
  if (n > 0)  // every variable's shape first: n then is the length of data that is in the file
    for (const NestingVarSpec& spec : kNestingVars) (void)var(spec.name);
  NestingFile d;
  d.point_type.resize(n);
  d.boundary.resize(n);
  d.element_level.resize(n);
  d.xi_index.resize(n);
  d.eta_index.resize(n);
  d.lon.resize(n);
  d.lat.resize(n);
  d.x.resize(n);
  d.y.resize(n);
  d.element.resize(n);
  d.element_nodes.resize(n);
  d.weights.resize(n);
  d.global_element_size_m.resize(n);
  d.regional_cell_size_m.resize(n);
  d.refinement_ratio.resize(n);
  if (n > 0) {
    std::vector<long long> element(n), nodes(3 * n);
    std::vector<double> w(3 * n);
    nc_check<InputError>(nc_get_var_schar(id, var("point_type"), d.point_type.data()), path, "point_type");
    nc_check<InputError>(nc_get_var_schar(id, var("boundary"), d.boundary.data()), path, "boundary");
    nc_check<InputError>(nc_get_var_int(id, var("xi_index"), d.xi_index.data()), path, "xi_index");
    nc_check<InputError>(nc_get_var_int(id, var("eta_index"), d.eta_index.data()), path, "eta_index");
    nc_check<InputError>(nc_get_var_double(id, var("lon"), d.lon.data()), path, "lon");
    nc_check<InputError>(nc_get_var_double(id, var("lat"), d.lat.data()), path, "lat");
    nc_check<InputError>(nc_get_var_double(id, var("x"), d.x.data()), path, "x");
    nc_check<InputError>(nc_get_var_double(id, var("y"), d.y.data()), path, "y");
    nc_check<InputError>(nc_get_var_longlong(id, var("element"), element.data()), path, "element");
    nc_check<InputError>(nc_get_var_longlong(id, var("element_nodes"), nodes.data()), path, "element_nodes");
    nc_check<InputError>(nc_get_var_double(id, var("weights"), w.data()), path, "weights");
    nc_check<InputError>(nc_get_var_schar(id, var("element_level"), d.element_level.data()), path, "element_level");
    nc_check<InputError>(nc_get_var_double(id, var("global_element_size"), d.global_element_size_m.data()), path,
                         "global_element_size");
    nc_check<InputError>(nc_get_var_double(id, var("regional_cell_size"), d.regional_cell_size_m.data()), path,
                         "regional_cell_size");
    nc_check<InputError>(nc_get_var_double(id, var("refinement_ratio"), d.refinement_ratio.data()), path,
                         "refinement_ratio");
    for (std::size_t k = 0; k < n; ++k) {
      d.element[k] = element[k];
      for (std::size_t q = 0; q < 3; ++q) {
        d.element_nodes[k][q] = nodes[3 * k + q];
        d.weights[k][q] = w[3 * k + q];
      }
    }
  }
  d.title = global_text(id, "title");
  d.history = global_text(id, "history");
  int natts = 0;
  nc_check<InputError>(nc_inq_natts(id, &natts), path, "attributes");
  for (int a = 0; a < natts; ++a) {
    char name[NC_MAX_NAME + 1] = {};
    nc_check<InputError>(nc_inq_attname(id, NC_GLOBAL, a, name), path, "attribute name");
    const std::string key = name;
    if (key == "Conventions" || key == "title" || key == "history") continue;
    nc_type type = NC_NAT;
    std::size_t len = 0;
    nc_check<InputError>(nc_inq_att(id, NC_GLOBAL, name, &type, &len), path, key);
    if (type == NC_CHAR) {
      d.attributes.emplace_back(key, global_text(id, name));
    } else if (type == NC_DOUBLE || type == NC_FLOAT) {
      double v = 0.0;
      nc_check<InputError>(nc_get_att_double(id, NC_GLOBAL, name, &v), path, key);
      d.attributes.emplace_back(key, v);
    } else {
      long long v = 0;
      nc_check<InputError>(nc_get_att_longlong(id, NC_GLOBAL, name, &v), path, key);
      d.attributes.emplace_back(key, static_cast<std::int64_t>(v));
    }
  }
  return d;
}

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Planar grid netCDF ("xygrid") writer and reader; schema in xygrid_netcdf.hpp. Every nc_* return
// code is checked; errors name the path and carry nc_strerror.
#include "grid_files/xygrid_netcdf.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <array>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace {

namespace fs = std::filesystem;

constexpr const char* kDefaultTitle = "aquatoria planar orthogonal curvilinear grid (xygrid)";
constexpr std::array<const char*, 6> kXygridReserved = {"Conventions",    "title", "history",
                                                        "aquatoria_file", "dxi",   "deta"};

bool is_reserved(const std::string& key) {
  for (const char* r : kXygridReserved) {
    if (key == r) return true;
  }
  return false;
}

void put_double(int nc, int var, const char* name, double value, const fs::path& path) {
  nc_check<OutputError>(nc_put_att_double(nc, var, name, NC_DOUBLE, 1, &value), path,
                        fmt::format("attribute {}", name));
}

int def_xygrid_var(int nc, const char* name, const std::vector<int>& dims, const fs::path& path) {
  int var = -1;
  nc_check<OutputError>(nc_def_var(nc, name, NC_DOUBLE, static_cast<int>(dims.size()), dims.data(), &var), path,
                        fmt::format("define variable {}", name));
  return var;
}

void put_var(int nc, int var, const std::vector<double>& data, const char* name, const fs::path& path) {
  nc_check<OutputError>(nc_put_var_double(nc, var, data.data()), path, fmt::format("write variable {}", name));
}

/// A global attribute as an AttributeValue; numeric arrays become space-separated text.
AttributeValue read_attribute(int nc, const char* name, const fs::path& path) {
  nc_type type = NC_NAT;
  std::size_t len = 0;
  nc_check<InputError>(nc_inq_att(nc, NC_GLOBAL, name, &type, &len), path, fmt::format("attribute {}", name));
  if (type == NC_CHAR) {
    std::string text(len, '\0');
    if (len > 0) nc_check<InputError>(nc_get_att_text(nc, NC_GLOBAL, name, text.data()), path, name);
    while (!text.empty() && text.back() == '\0') text.pop_back();
    return text;
  }
  if (type == NC_STRING) {
    std::vector<char*> strings(len, nullptr);
    nc_check<InputError>(nc_get_att_string(nc, NC_GLOBAL, name, strings.data()), path, name);
    std::string text;
    for (std::size_t k = 0; k < len; ++k) text += (k ? " " : "") + std::string(strings[k] ? strings[k] : "");
    nc_free_string(len, strings.data());
    return text;
  }
  const bool integer = type == NC_BYTE || type == NC_SHORT || type == NC_INT || type == NC_INT64 || type == NC_UBYTE ||
                       type == NC_USHORT || type == NC_UINT || type == NC_UINT64;
  if (integer) {
    std::vector<long long> v(len);
    nc_check<InputError>(nc_get_att_longlong(nc, NC_GLOBAL, name, v.data()), path, name);
    if (len == 1) return static_cast<std::int64_t>(v[0]);
    std::string text;
    for (std::size_t k = 0; k < len; ++k) text += fmt::format("{}{}", k ? " " : "", v[k]);
    return text;
  }
  std::vector<double> v(len);
  nc_check<InputError>(nc_get_att_double(nc, NC_GLOBAL, name, v.data()), path, name);
  if (len == 1) return v[0];
  std::string text;
  for (std::size_t k = 0; k < len; ++k) text += fmt::format("{}{}", k ? " " : "", v[k]);
  return text;
}

}  // namespace

void write_xygrid(const fs::path& path, const XyGrid& data, const curvilinear::GridQuality* quality) {
  const curvilinear::Grid2D& g = data.grid;
  const std::size_t n_nodes =
      static_cast<std::size_t>(std::max(g.nx_pts, 0)) * static_cast<std::size_t>(std::max(g.ny_pts, 0));
  if (g.nx_pts < 2 || g.ny_pts < 2 || g.x.size() != n_nodes || g.y.size() != n_nodes) {
    throw InternalError(fmt::format("write_xygrid {}: grid {}x{} with {} x and {} y values", path.string(), g.nx_pts,
                                    g.ny_pts, g.x.size(), g.y.size()));
  }
  for (const auto& [key, value] : data.attributes) {
    if (is_reserved(key) || key.empty()) {
      throw InternalError(fmt::format("write_xygrid {}: attribute name '{}' is reserved or empty", path.string(), key));
    }
  }
  if (quality != nullptr && (quality->nx_pts != g.nx_pts || quality->ny_pts != g.ny_pts)) {
    throw InternalError(fmt::format("write_xygrid {}: quality of a {}x{} grid for a {}x{} grid", path.string(),
                                    quality->nx_pts, quality->ny_pts, g.nx_pts, g.ny_pts));
  }

  NcFile nc;
  nc_check<OutputError>(nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4, nc.out()), path, "create");
  const int id = nc.id();
  int dim_xi = -1;
  int dim_eta = -1;
  nc_check<OutputError>(nc_def_dim(id, "xi_s", static_cast<std::size_t>(g.nx_pts), &dim_xi), path, "dimension xi_s");
  nc_check<OutputError>(nc_def_dim(id, "eta_s", static_cast<std::size_t>(g.ny_pts), &dim_eta), path, "dimension eta_s");

  const int var_x = def_xygrid_var(id, "x", {dim_eta, dim_xi}, path);
  put_text(id, var_x, "long_name", "x coordinate of supergrid nodes in the projection plane", path);
  put_text(id, var_x, "standard_name", "projection_x_coordinate", path);
  put_text(id, var_x, "units", data.units, path);
  const int var_y = def_xygrid_var(id, "y", {dim_eta, dim_xi}, path);
  put_text(id, var_y, "long_name", "y coordinate of supergrid nodes in the projection plane", path);
  put_text(id, var_y, "standard_name", "projection_y_coordinate", path);
  put_text(id, var_y, "units", data.units, path);

  int var_hist = -1;
  if (!data.residual_history.empty()) {
    int dim_it = -1;
    nc_check<OutputError>(nc_def_dim(id, "iteration", data.residual_history.size(), &dim_it), path,
                          "dimension iteration");
    var_hist = def_xygrid_var(id, "residual_history", {dim_it}, path);
    put_text(id, var_hist, "long_name",
             "Laplace fill convergence: SOR max |dq|/extent per iteration, or the direct solver's final residual",
             path);
    put_text(id, var_hist, "units", "1", path);
  }

  std::vector<std::pair<int, const curvilinear::QualityField*>> qvars;
  if (quality != nullptr) {
    int dim_xc = -1;
    int dim_yc = -1;
    nc_check<OutputError>(nc_def_dim(id, "xi_c", static_cast<std::size_t>(g.nx_pts - 1), &dim_xc), path,
                          "dimension xi_c");
    nc_check<OutputError>(nc_def_dim(id, "eta_c", static_cast<std::size_t>(g.ny_pts - 1), &dim_yc), path,
                          "dimension eta_c");
    for (const curvilinear::QualityField* f : quality->fields()) {
      const bool cell = f->location == curvilinear::FieldLocation::kCell;
      const std::size_t expect =
          cell ? static_cast<std::size_t>(g.nx_pts - 1) * static_cast<std::size_t>(g.ny_pts - 1) : n_nodes;
      if (f->values.empty()) continue;  // e.g. the spline form of a grid with no interior
      if (f->values.size() != expect) {
        throw InternalError(fmt::format("write_xygrid {}: field {} has {} values, expected {}", path.string(), f->name,
                                        f->values.size(), expect));
      }
      const int var = def_xygrid_var(id, f->name.c_str(),
                                     cell ? std::vector<int>{dim_yc, dim_xc} : std::vector<int>{dim_eta, dim_xi}, path);
      put_text(id, var, "long_name", f->long_name, path);
      put_text(id, var, "units", "1", path);
      put_double(id, var, "_FillValue", std::numeric_limits<double>::quiet_NaN(), path);
      put_text(id, var, "location", cell ? "cell (i+1/2, j+1/2)" : "node", path);
      put_double(id, var, "worst", f->worst, path);
      put_double(id, var, "average", f->average, path);
      if (f->is_error) put_double(id, var, "rms", f->rms, path);
      qvars.emplace_back(var, f);
    }
  }

  put_text(id, NC_GLOBAL, "Conventions", "CF-1.8", path);
  put_text(id, NC_GLOBAL, "title", data.title.empty() ? kDefaultTitle : data.title, path);
  put_text(id, NC_GLOBAL, "history", data.history.empty() ? "created by aquatoria" : data.history, path);
  put_text(id, NC_GLOBAL, "aquatoria_file", "xygrid", path);
  put_double(id, NC_GLOBAL, "dxi", data.dxi, path);
  put_double(id, NC_GLOBAL, "deta", data.deta, path);
  put_attributes(id, NC_GLOBAL, data.attributes, path);
  nc_check<OutputError>(nc_enddef(id), path, "end of definitions");

  put_var(id, var_x, g.x, "x", path);
  put_var(id, var_y, g.y, "y", path);
  if (var_hist >= 0) put_var(id, var_hist, data.residual_history, "residual_history", path);
  for (const auto& [var, f] : qvars) put_var(id, var, f->values, f->name.c_str(), path);
  nc_check<OutputError>(nc.close(), path, "close");
}

XyGrid read_xygrid(const fs::path& path) {
  NcFile nc;
  open_for_reading(path, nc);
  const int id = nc.id();
  XyGrid out;

  int var[2] = {-1, -1};
  int dims[2][NC_MAX_VAR_DIMS];
  const char* names[2] = {"x", "y"};
  std::size_t len[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    if (nc_inq_varid(id, names[k], &var[k]) != NC_NOERR) {
      throw InputError(fmt::format("{}: not a planar grid file: no variable '{}'", path.string(), names[k]));
    }
    int ndims = 0;
    nc_type type = NC_NAT;
    nc_check<InputError>(nc_inq_var(id, var[k], nullptr, &type, &ndims, dims[k], nullptr), path, names[k]);
    if (ndims != 2) {
      throw InputError(fmt::format("{}: variable '{}' has {} dimensions, a planar grid needs 2 (eta, xi)",
                                   path.string(), names[k], ndims));
    }
    if (type == NC_CHAR || type == NC_STRING) {
      throw InputError(fmt::format("{}: variable '{}' is not numeric", path.string(), names[k]));
    }
  }
  for (int d = 0; d < 2; ++d) {
    nc_check<InputError>(nc_inq_dimlen(id, dims[0][d], &len[d]), path, "dimension of x");
    std::size_t ylen = 0;
    nc_check<InputError>(nc_inq_dimlen(id, dims[1][d], &ylen), path, "dimension of y");
    if (ylen != len[d]) {
      throw InputError(fmt::format("{}: variables 'x' and 'y' have different shapes", path.string()));
    }
  }
  if (len[0] < 2 || len[1] < 2 || len[0] > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      len[1] > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(fmt::format("{}: grid of {}x{} nodes: need at least 2x2", path.string(), len[1], len[0]));
  }
  check_declared_size(path, 2.0 * static_cast<double>(len[0]) * static_cast<double>(len[1]),
                      fmt::format("a grid of {} x {} nodes", len[1], len[0]));
  out.grid = curvilinear::Grid2D(static_cast<int>(len[1]), static_cast<int>(len[0]));
  nc_check<InputError>(nc_get_var_double(id, var[0], out.grid.x.data()), path, "read x");
  nc_check<InputError>(nc_get_var_double(id, var[1], out.grid.y.data()), path, "read y");
  for (std::size_t p = 0; p < out.grid.x.size(); ++p) {
    if (!std::isfinite(out.grid.x[p]) || !std::isfinite(out.grid.y[p])) {
      const std::size_t nx = len[1];
      throw InputError(fmt::format("{}: node (i={}, j={}) is not finite: ({}, {})", path.string(), p % nx, p / nx,
                                   out.grid.x[p], out.grid.y[p]));
    }
  }

  std::size_t ulen = 0;
  nc_type utype = NC_NAT;
  if (nc_inq_att(id, var[0], "units", &utype, &ulen) == NC_NOERR && utype == NC_CHAR) {
    std::string units(ulen, '\0');
    nc_check<InputError>(nc_get_att_text(id, var[0], "units", units.data()), path, "x units");
    while (!units.empty() && units.back() == '\0') units.pop_back();
    out.units = units;
  } else {
    out.units.clear();
  }

  const double dxi = global_number(id, "dxi");
  const double deta = global_number(id, "deta");
  out.has_steps = dxi > 0.0 && deta > 0.0 && std::isfinite(dxi) && std::isfinite(deta);
  out.dxi = out.has_steps ? dxi : 1.0;
  out.deta = out.has_steps ? deta : 1.0;
  out.title = global_text(id, "title");
  out.history = global_text(id, "history");

  int natts = 0;
  nc_check<InputError>(nc_inq_natts(id, &natts), path, "global attributes");
  for (int a = 0; a < natts; ++a) {
    char name[NC_MAX_NAME + 1] = {};
    nc_check<InputError>(nc_inq_attname(id, NC_GLOBAL, a, name), path, "global attribute name");
    if (is_reserved(name)) continue;
    out.attributes.emplace(name, read_attribute(id, name, path));
  }

  int var_hist = -1;
  if (nc_inq_varid(id, "residual_history", &var_hist) == NC_NOERR) {
    int ndims = 0;
    int hdim[NC_MAX_VAR_DIMS];
    nc_check<InputError>(nc_inq_var(id, var_hist, nullptr, nullptr, &ndims, hdim, nullptr), path, "residual_history");
    if (ndims != 1) {
      throw InputError(
          fmt::format("{}: variable 'residual_history' has {} dimensions, expected 1", path.string(), ndims));
    }
    std::size_t n = 0;
    nc_check<InputError>(nc_inq_dimlen(id, hdim[0], &n), path, "residual_history length");
    out.residual_history.resize(n);
    if (n > 0) {
      nc_check<InputError>(nc_get_var_double(id, var_hist, out.residual_history.data()), path, "read residual_history");
    }
  }
  return out;
}

}  // namespace aq::io

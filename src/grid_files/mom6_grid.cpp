// SPDX-License-Identifier: GPL-3.0-or-later
// MOM6 supergrid, topography and mask files (see mom6_grid.hpp). Every nc_* return code is
// checked; errors name the path and carry nc_strerror.
#include "grid_files/mom6_grid.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <array>
#include <cmath>
#include <cstddef>

#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace fs = std::filesystem;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::array<double, 3> unit_vector(double lon_deg, double lat_deg) {
  const double l = lon_deg * kDeg, p = lat_deg * kDeg;
  return {std::cos(p) * std::cos(l), std::cos(p) * std::sin(l), std::sin(p)};
}

// Solid angle of the spherical triangle a, b, c (Van Oosterom & Strackee 1983).
double triangle_solid_angle(const std::array<double, 3>& a, const std::array<double, 3>& b,
                            const std::array<double, 3>& c) {
  const double triple = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                        a[2] * (b[0] * c[1] - b[1] * c[0]);
  const auto dot = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  return 2.0 * std::fabs(std::atan2(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a)));
}

int def_dim(int nc, const char* name, std::size_t len, const fs::path& path) {
  int id = -1;
  nc_check<OutputError>(nc_def_dim(nc, name, len, &id), path, fmt::format("define dimension {}", name));
  return id;
}

int def_var(int nc, const char* name, std::array<int, 2> dims, const char* units, const char* long_name,
            const fs::path& path) {
  int var = -1;
  nc_check<OutputError>(nc_def_var(nc, name, NC_DOUBLE, 2, dims.data(), &var), path,
                        fmt::format("define variable {}", name));
  put_text(nc, var, "standard_name", long_name, path);
  if (units != nullptr) put_text(nc, var, "units", units, path);
  return var;
}

void put(int nc, int var, const std::vector<double>& v, const char* name, const fs::path& path) {
  nc_check<OutputError>(nc_put_var_double(nc, var, v.data()), path, fmt::format("write variable {}", name));
}

void finish(NcFile& f, const fs::path& path) { nc_check<OutputError>(f.close(), path, "close"); }

std::vector<double> read_var(int nc, const char* name, std::size_t rows, std::size_t cols, const fs::path& path) {
  int var = -1;
  if (nc_inq_varid(nc, name, &var) != NC_NOERR)
    throw InputError(fmt::format("{}: not a MOM6 grid file: no variable '{}'", path.string(), name));
  int nd = 0;
  nc_check<InputError>(nc_inq_varndims(nc, var, &nd), path, name);
  std::array<int, 2> dims{};
  if (nd != 2) throw InputError(fmt::format("{}: variable '{}' has {} dimensions, not 2", path.string(), name, nd));
  nc_check<InputError>(nc_inq_vardimid(nc, var, dims.data()), path, name);
  std::size_t r = 0, c = 0;
  nc_check<InputError>(nc_inq_dimlen(nc, dims[0], &r), path, name);
  nc_check<InputError>(nc_inq_dimlen(nc, dims[1], &c), path, name);
  if (r != rows || c != cols)
    throw InputError(fmt::format("{}: variable '{}' is {} x {}, expected {} x {}", path.string(), name, r, c, rows, cols));
  std::vector<double> v(rows * cols);
  nc_check<InputError>(nc_get_var_double(nc, var, v.data()), path, fmt::format("read variable {}", name));
  return v;
}

std::size_t dim_length(int nc, const char* name, const fs::path& path) {
  int id = -1;
  if (nc_inq_dimid(nc, name, &id) != NC_NOERR)
    throw InputError(fmt::format("{}: not a MOM6 grid file: no dimension '{}'", path.string(), name));
  std::size_t n = 0;
  nc_check<InputError>(nc_inq_dimlen(nc, id, &n), path, name);
  return n;
}

}  // namespace

Mom6Grid mom6_grid(const curvilinear::Grid2D& g, const curvilinear::Projection& projection,
                   const std::vector<double>& h, const std::vector<double>& mask_rho, double radius_m) {
  if (g.nx_pts < 5 || g.ny_pts < 5 || g.nx_pts % 2 == 0 || g.ny_pts % 2 == 0)
    throw InputError(fmt::format("MOM6 grid: the supergrid is {} x {} points; it needs odd sizes of at least 5",
                                 g.nx_pts, g.ny_pts));
  const int L = (g.nx_pts - 1) / 2, M = (g.ny_pts - 1) / 2;
  const auto nr = static_cast<std::size_t>(L + 1) * static_cast<std::size_t>(M + 1);
  if (h.size() != nr || mask_rho.size() != nr || g.x.size() != g.at(0, g.ny_pts))
    throw InternalError(fmt::format("MOM6 grid: {} h and {} mask values for {} rho points", h.size(), mask_rho.size(), nr));
  Mom6Grid m;
  m.nx = L - 1;
  m.ny = M - 1;
  m.radius_m = radius_m;
  const int nxp = m.nxp(), nyp = m.nyp();
  const auto at = [](int i, int j, int ni) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  };
  m.x.resize(at(0, nyp, nxp));
  m.y.resize(m.x.size());
  for (int J = 0; J < nyp; ++J)
    for (int I = 0; I < nxp; ++I) {
      const std::size_t src = g.at(I + 1, J + 1);
      const curvilinear::GeoPoint q = projection.inverse(g.x[src], g.y[src]);
      if (!std::isfinite(q.lon_deg) || !std::isfinite(q.lat_deg))
        throw InputError(fmt::format("MOM6 grid: supergrid point ({}, {}) has no finite longitude/latitude", I + 1, J + 1));
      m.x[at(I, J, nxp)] = q.lon_deg;
      m.y[at(I, J, nxp)] = q.lat_deg;
    }
  const auto dist = [&](std::size_t a, std::size_t b) {
    return curvilinear::great_circle_m(m.x[a], m.y[a], m.x[b], m.y[b], radius_m);
  };
  m.dx.resize(at(0, nyp, nxp - 1));
  for (int J = 0; J < nyp; ++J)
    for (int I = 0; I + 1 < nxp; ++I) m.dx[at(I, J, nxp - 1)] = dist(at(I, J, nxp), at(I + 1, J, nxp));
  m.dy.resize(at(0, nyp - 1, nxp));
  for (int J = 0; J + 1 < nyp; ++J)
    for (int I = 0; I < nxp; ++I) m.dy[at(I, J, nxp)] = dist(at(I, J, nxp), at(I, J + 1, nxp));
  m.area.resize(at(0, nyp - 1, nxp - 1));
  for (int J = 0; J + 1 < nyp; ++J)
    for (int I = 0; I + 1 < nxp; ++I) {
      const auto p = [&](int i, int j) { return unit_vector(m.x[at(i, j, nxp)], m.y[at(i, j, nxp)]); };
      const auto a = p(I, J), b = p(I + 1, J), c = p(I + 1, J + 1), d = p(I, J + 1);
      m.area[at(I, J, nxp - 1)] = radius_m * radius_m * (triangle_solid_angle(a, b, c) + triangle_solid_angle(a, c, d));
    }
  // angle_dx: direction of increasing I, counter-clockwise from east, centred (one-sided at the ends).
  m.angle_dx.resize(m.x.size());
  for (int J = 0; J < nyp; ++J)
    for (int I = 0; I < nxp; ++I) {
      const int i0 = I > 0 ? I - 1 : I, i1 = I + 1 < nxp ? I + 1 : I;
      const std::size_t a = at(i0, J, nxp), b = at(i1, J, nxp);
      double dlon = m.x[b] - m.x[a];
      while (dlon > 180.0) dlon -= 360.0;
      while (dlon < -180.0) dlon += 360.0;
      const double dlat = m.y[b] - m.y[a];
      m.angle_dx[at(I, J, nxp)] = std::atan2(dlat, dlon * std::cos(m.y[at(I, J, nxp)] * kDeg)) / kDeg;
    }
  m.depth.resize(static_cast<std::size_t>(m.nx) * static_cast<std::size_t>(m.ny));
  m.mask.resize(m.depth.size());
  for (int j = 0; j < m.ny; ++j)
    for (int i = 0; i < m.nx; ++i) {
      const std::size_t r = at(i + 1, j + 1, L + 1), k = at(i, j, m.nx);
      m.mask[k] = mask_rho[r] != 0.0 ? 1.0 : 0.0;
      m.depth[k] = mask_rho[r] != 0.0 ? h[r] : 0.0;
    }
  return m;
}

void write_mom6_files(const Mom6Grid& g, const fs::path& hgrid, const fs::path& topog, const fs::path& mask,
                      const std::string& history) {
  const auto sz = [](int n) { return static_cast<std::size_t>(n); };
  {
    NcFile f;
    nc_check<OutputError>(nc_create(hgrid.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, f.out()), hgrid, "create");
    const int nc = f.id();
    const int dnx = def_dim(nc, "nx", sz(2 * g.nx), hgrid), dny = def_dim(nc, "ny", sz(2 * g.ny), hgrid);
    const int dnxp = def_dim(nc, "nxp", sz(g.nxp()), hgrid), dnyp = def_dim(nc, "nyp", sz(g.nyp()), hgrid);
    const int dstr = def_dim(nc, "string", 255, hgrid);
    int tile = -1;
    nc_check<OutputError>(nc_def_var(nc, "tile", NC_CHAR, 1, &dstr, &tile), hgrid, "define variable tile");
    put_text(nc, tile, "standard_name", "grid_tile_spec", hgrid);
    put_text(nc, tile, "geometry", "spherical", hgrid);
    put_text(nc, tile, "north_pole", "0.0 90.0", hgrid);
    put_text(nc, tile, "projection", "none", hgrid);
    put_text(nc, tile, "discretization", "logically_rectangular", hgrid);
    put_text(nc, tile, "conformal", "true", hgrid);
    const int vx = def_var(nc, "x", {dnyp, dnxp}, "degree_east", "geographic_longitude", hgrid);
    const int vy = def_var(nc, "y", {dnyp, dnxp}, "degree_north", "geographic_latitude", hgrid);
    const int vdx = def_var(nc, "dx", {dnyp, dnx}, "meters", "grid_edge_x_distance", hgrid);
    const int vdy = def_var(nc, "dy", {dny, dnxp}, "meters", "grid_edge_y_distance", hgrid);
    const int var = def_var(nc, "area", {dny, dnx}, "m2", "grid_cell_area", hgrid);
    const int vang = def_var(nc, "angle_dx", {dnyp, dnxp}, "degrees_east", "grid_vertex_x_angle_WRT_geographic_east",
                             hgrid);
    put_text(nc, NC_GLOBAL, "title", "MOM6 supergrid (FMS mosaic grid spec) of an aquatoria regional grid", hgrid);
    put_text(nc, NC_GLOBAL, "history", history, hgrid);
    put_text(nc, NC_GLOBAL, "grid_version", "0.2", hgrid);
    put_text(nc, NC_GLOBAL, "metrics",
             fmt::format("dx, dy: great circles on a sphere of radius {} m; area: spherical quadrilaterals (two "
                         "triangles) on it; angle_dx: centred difference along i, one-sided at the ends",
                         g.radius_m),
             hgrid);
    nc_check<OutputError>(nc_enddef(nc), hgrid, "end of definitions");
    std::string name = "tile1";
    name.resize(255, '\0');
    nc_check<OutputError>(nc_put_var_text(nc, tile, name.c_str()), hgrid, "write variable tile");
    put(nc, vx, g.x, "x", hgrid);
    put(nc, vy, g.y, "y", hgrid);
    put(nc, vdx, g.dx, "dx", hgrid);
    put(nc, vdy, g.dy, "dy", hgrid);
    put(nc, var, g.area, "area", hgrid);
    put(nc, vang, g.angle_dx, "angle_dx", hgrid);
    finish(f, hgrid);
  }
  const auto cell_file = [&](const fs::path& path, const char* name, const std::vector<double>& v, const char* units,
                             const char* long_name) {
    NcFile f;
    nc_check<OutputError>(nc_create(path.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, f.out()), path, "create");
    const int nc = f.id();
    const int dnx = def_dim(nc, "nx", sz(g.nx), path), dny = def_dim(nc, "ny", sz(g.ny), path);
    const int ntiles = def_dim(nc, "ntiles", 1, path);
    (void)ntiles;
    const int var = def_var(nc, name, {dny, dnx}, units, long_name, path);
    put_text(nc, NC_GLOBAL, "history", history, path);
    put_text(nc, NC_GLOBAL, "grid", "ocean_hgrid.nc: cell (i, j) is the supergrid cell with corners (2i..2i+2, 2j..2j+2)", path);
    nc_check<OutputError>(nc_enddef(nc), path, "end of definitions");
    put(nc, var, v, name, path);
    finish(f, path);
  };
  cell_file(topog, "depth", g.depth, "meters", "topographic depth at T-cell centers, positive down, 0 on land");
  cell_file(mask, "mask", g.mask, nullptr, "ocean mask at T-cell centers: 1 ocean, 0 land");
}

Mom6Grid read_mom6_hgrid(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: no such MOM6 grid file", path.string()));
  NcFile f;
  open_for_reading(path, f);
  const int nc = f.id();
  const std::size_t nx2 = dim_length(nc, "nx", path), ny2 = dim_length(nc, "ny", path);
  const std::size_t nxp = dim_length(nc, "nxp", path), nyp = dim_length(nc, "nyp", path);
  if (nxp != nx2 + 1 || nyp != ny2 + 1 || nx2 % 2 != 0 || ny2 % 2 != 0 || nx2 == 0 || ny2 == 0)
    throw InputError(fmt::format("{}: supergrid dimensions nx = {}, ny = {}, nxp = {}, nyp = {} do not fit (nxp = nx + "
                                 "1, nyp = ny + 1, nx and ny even)",
                                 path.string(), nx2, ny2, nxp, nyp));
  Mom6Grid g;
  g.nx = static_cast<int>(nx2 / 2);
  g.ny = static_cast<int>(ny2 / 2);
  g.x = read_var(nc, "x", nyp, nxp, path);
  g.y = read_var(nc, "y", nyp, nxp, path);
  g.dx = read_var(nc, "dx", nyp, nx2, path);
  g.dy = read_var(nc, "dy", ny2, nxp, path);
  g.area = read_var(nc, "area", ny2, nx2, path);
  g.angle_dx = read_var(nc, "angle_dx", nyp, nxp, path);
  return g;
}

std::vector<double> read_mom6_field(const fs::path& path, const char* variable, int& nx, int& ny) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: no such MOM6 file", path.string()));
  NcFile f;
  open_for_reading(path, f);
  const std::size_t cx = dim_length(f.id(), "nx", path), cy = dim_length(f.id(), "ny", path);
  nx = static_cast<int>(cx);
  ny = static_cast<int>(cy);
  return read_var(f.id(), variable, cy, cx, path);
}

}  // namespace aq::io

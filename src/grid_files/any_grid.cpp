// SPDX-License-Identifier: GPL-3.0-or-later
// Any aquatoria grid file as a planar grid (see any_grid.hpp).
#include "grid_files/any_grid.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <cmath>

#include "core/error.hpp"
#include "curvilinear/common/projection.hpp"
#include "grid_files/contact_netcdf.hpp"
#include "grid_files/mom6_grid.hpp"
#include "io/netcdf_file.hpp"

namespace aq::io {

namespace fs = std::filesystem;

namespace {

// Stereographic plane (metres) centred on the mean position of the points.
curvilinear::Grid2D to_plane(int nx, int ny, const std::vector<double>& lon, const std::vector<double>& lat) {
  double sx = 0.0, sy = 0.0, sz = 0.0;
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  for (std::size_t k = 0; k < lon.size(); ++k) {
    sx += std::cos(lat[k] * kDeg) * std::cos(lon[k] * kDeg);
    sy += std::cos(lat[k] * kDeg) * std::sin(lon[k] * kDeg);
    sz += std::sin(lat[k] * kDeg);
  }
  curvilinear::ProjectionParams p;
  p.kind = curvilinear::ProjectionKind::kStereographic;
  p.rlat_deg = std::atan2(sz, std::hypot(sx, sy)) / kDeg;
  p.rlon_deg = std::atan2(sy, sx) / kDeg;
  p.uscale = 1.0 / p.radius_m;  // plane units = metres
  const curvilinear::Projection proj(p);
  curvilinear::Grid2D g;
  g.nx_pts = nx;
  g.ny_pts = ny;
  g.x.resize(lon.size());
  g.y.resize(lon.size());
  for (std::size_t k = 0; k < lon.size(); ++k) {
    const auto q = proj.forward(lon[k], lat[k]);
    g.x[k] = q.x;
    g.y[k] = q.y;
  }
  return g;
}

bool has_var(int nc, const char* name) {
  int v = -1;
  return nc_inq_varid(nc, name, &v) == NC_NOERR;
}

}  // namespace

AnyGrid read_any_grid(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: no such grid file", path.string()));
  bool mom6 = false, roms = false;
  {
    NcFile f;
    open_for_reading(path, f);
    int d = -1;
    mom6 = nc_inq_dimid(f.id(), "nxp", &d) == NC_NOERR && has_var(f.id(), "angle_dx");
    roms = has_var(f.id(), "lon_psi") && has_var(f.id(), "pm");
  }
  AnyGrid out;
  if (mom6) {
    const Mom6Grid m = read_mom6_hgrid(path);
    out.kind = GridFileKind::kMom6;
    out.xy.grid = to_plane(m.nxp(), m.nyp(), m.x, m.y);
    out.xy.units = "m";
    out.xy.has_steps = false;
    out.xy.title = "MOM6 supergrid " + path.filename().string();
    return out;
  }
  if (roms) {
    const RomsGridFields r = read_roms_grid_fields(path);
    const int nI = 2 * r.L + 1, nJ = 2 * r.M + 1;
    std::vector<double> lon(static_cast<std::size_t>(nI) * static_cast<std::size_t>(nJ)), lat(lon.size());
    const auto put = [&](const std::vector<double>& lo, const std::vector<double>& la, int ni, int nj, int di, int dj) {
      for (int b = 0; b < nj; ++b)
        for (int a = 0; a < ni; ++a) {
          const std::size_t src = static_cast<std::size_t>(b) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(a);
          const std::size_t dst = static_cast<std::size_t>(2 * b + dj) * static_cast<std::size_t>(nI) +
                                  static_cast<std::size_t>(2 * a + di);
          lon[dst] = lo[src];
          lat[dst] = la[src];
        }
    };
    put(r.lon_rho, r.lat_rho, r.L + 1, r.M + 1, 0, 0);
    put(r.lon_u, r.lat_u, r.L, r.M + 1, 1, 0);
    put(r.lon_v, r.lat_v, r.L + 1, r.M, 0, 1);
    put(r.lon_psi, r.lat_psi, r.L, r.M, 1, 1);
    out.kind = GridFileKind::kRoms;
    out.xy.grid = to_plane(nI, nJ, lon, lat);
    out.xy.units = "m";
    // The izogrid step ratio when the file names it (aquatoria's grids), else estimated by check.
    if (std::isfinite(r.aspect_ratio) && r.aspect_ratio > 0.0) {
      out.xy.dxi = r.aspect_ratio / (nI - 1);
      out.xy.deta = 1.0 / (nJ - 1);
    } else {
      out.xy.has_steps = false;
    }
    out.xy.title = "ROMS grid " + path.filename().string();
    return out;
  }
  out.kind = GridFileKind::kXygrid;
  try {
    out.xy = read_xygrid(path);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}; it is neither an aquatoria planar grid (x, y), a ROMS grid (lon_rho .. lon_psi, "
                                 "pm) nor a MOM6 supergrid (nxp, x, y, angle_dx)",
                                 e.what()));
  }
  return out;
}

}  // namespace aq::io

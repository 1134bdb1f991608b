// SPDX-License-Identifier: GPL-3.0-or-later
// The ROMS grid file (myroms/roms Data/ROMS/CDL/grd_spherical.cdl; field.md D3; ARCHITECTURE §5
// stage 5): every variable of grd_spherical.cdl with its attributes, written with the netCDF-C API
// as netCDF classic 64-bit offset (read by every ROMS/CROCO build, with or without netCDF-4; the
// bytes depend only on the data: no time stamps).
//
//   dimensions: xi_rho = L+1, eta_rho = M+1, xi_u = L, eta_u = M+1, xi_v = L+1, eta_v = M,
//               xi_psi = L, eta_psi = M, bath = UNLIMITED (1 record: the raw depth)
//   variables:  char spherical = 'T'; double xl, el (m)
//               double hraw(bath, eta_rho, xi_rho), h, f, pm, pn, dndx, dmde, angle,
//                      x_rho, y_rho, lon_rho, lat_rho, mask_rho     (eta_rho, xi_rho)
//               double x_u, y_u, lon_u, lat_u, mask_u               (eta_u, xi_u)
//               double x_v, y_v, lon_v, lat_v, mask_v               (eta_v, xi_v)
//               double x_psi, y_psi, lon_psi, lat_psi, mask_psi     (eta_psi, xi_psi)
//   global:     type = "ROMS GRID file", Conventions = "CF-1.8", title, history, source, then
//               the generation parameters.
//
// Attributes follow the CDL (long_name, units, coordinates, flag_values/flag_meanings), plus CF
// standard_name where CF has one (longitude, latitude, sea_floor_depth_below_mean_sea_level,
// coriolis_parameter, angle_of_rotation_from_east_to_x). Two deliberate departures from the CDL:
// the masks carry no `_FillValue = 1.` (CF readers such as CDO and xarray would hide every water
// point), and mask_psi's coordinates are "lon_psi lat_psi" (the CDL's "lon_rho lat_rho" has other
// dimensions).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "curvilinear/common/cgrid.hpp"
#include "grid_files/xygrid_netcdf.hpp"

namespace aq::io {

struct RomsGridData {
  const curvilinear::CGrid* grid = nullptr;                      ///< geometry and metrics (required)
  std::vector<double> h;                                         ///< model depth at ρ, m, positive down
  std::vector<double> hraw;                                      ///< raw depth at ρ, m, positive down
  std::vector<std::uint8_t> mask_rho, mask_u, mask_v, mask_psi;  ///< 0 land, 1 water
  std::string title;                                             ///< empty: a default title
  std::string history;  ///< e.g. "aquatoria regional configs/black_sea.toml" (no time stamp)
  std::string source;   ///< e.g. "aquatoria 0.1.0"
  /// Generation parameters as global attributes (names must not clash with type, Conventions,
  /// title, history, source).
  AttributeMap attributes;
};

/// Writes `data` to `path` (callers pass OutputSet::temp_path), replacing it. Throws OutputError
/// naming the path and the netCDF error; InternalError for sizes that do not match the grid or a
/// reserved attribute name.
void write_roms_grid(const std::filesystem::path& path, const RomsGridData& data);

/// New depth and masks for an existing ROMS grid file (e.g. the parent of a refinement made
/// consistent with it). Arrays in the file's layout; an empty array leaves its variable alone.
struct RomsGridUpdate {
  std::vector<double> h, mask_rho, mask_u, mask_v, mask_psi;
  AttributeMap attributes;     ///< global attributes added or replaced (not type/Conventions/title/source)
  std::string history_append;  ///< appended to the history attribute on a new line
};

/// Copies the ROMS grid file `source` to `path` (callers pass OutputSet::temp_path; `path` must not
/// be `source`) and writes `update` into the copy; every other variable and attribute stays as in
/// `source`. Throws InputError naming `source` when it cannot be read or lacks a variable that is
/// updated or has another size, OutputError naming `path` on a write failure.
void write_updated_roms_grid(const std::filesystem::path& source, const std::filesystem::path& path,
                             const RomsGridUpdate& update);

/// The variable names of grd_spherical.cdl, in the order they are written.
const std::vector<std::string>& roms_grid_variables();

}  // namespace aq::io

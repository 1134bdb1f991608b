// SPDX-License-Identifier: GPL-3.0-or-later
// The planar grid file ("xygrid", izogrid's mode-4 output; digest izogrid.md §9 [S]): the
// supergrid's nodes x(eta_s, xi_s), y(eta_s, xi_s) in the projection plane, the computational
// steps, the generation parameters as global attributes, the Laplace solver's convergence
// history and, optionally, the per-cell and per-node quality fields of `aquatoria check`
// (seed 000 eqs. (46)–(52), seed 004 f1–f4). netCDF-4, CF-1.8.
//
//   dimensions: xi_s = nx_pts, eta_s = ny_pts          (supergrid nodes)
//               xi_c = nx_pts-1, eta_c = ny_pts-1      (cells; only with quality fields)
//               iteration = number of history entries  (only if there is a history)
//   variables:  double x(eta_s, xi_s), y(eta_s, xi_s)  units as given, standard_name
//                                                      projection_x/y_coordinate
//               double residual_history(iteration)
//               double ortho_err_46(eta_c, xi_c), ortho_err_50, isotropy_51, f1..f4 (cells)
//               double ortho_err_52(eta_s, xi_s), laplace_residual(eta_s, xi_s)    (nodes)
//   global:     Conventions = "CF-1.8", title, history, aquatoria_file = "xygrid",
//               dxi, deta (computational steps), then the caller's parameters.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "io/attribute_value.hpp"

namespace aq::io {

/// Global attributes by name (io/attribute_value.hpp: text, a real number, an integer).
using AttributeMap = std::map<std::string, AttributeValue>;

struct XyGrid {
  curvilinear::Grid2D grid;
  std::string units = "m";  ///< units of x and y
  /// Steps of the uniform computational grid (e.g. W/(nx_pts−1), H/(ny_pts−1) of the conformal
  /// rectangle); `check` uses their ratio. Stored as global attributes dxi, deta.
  double dxi = 1.0;
  double deta = 1.0;
  bool has_steps = true;  ///< false when read from a file without dxi/deta
  std::string title;      ///< empty: a default title is written
  std::string history;    ///< e.g. "aquatoria regional blacksea.toml"; empty: "created by aquatoria"
  /// Generation parameters (projection, rlat, rlon, nx, ny, W/H, spline type, ...). Keys must not
  /// be one of the reserved names above.
  AttributeMap attributes;
  std::vector<double> residual_history;  ///< Laplace solver convergence (may be empty)
};

/// Writes `grid` (and `quality`, if given, computed on the same grid) to `path`, replacing it.
/// Callers pass OutputSet::temp_path. Throws OutputError naming the path and the netCDF error;
/// InternalError for inconsistent sizes or a reserved attribute key.
void write_xygrid(const std::filesystem::path& path, const XyGrid& grid,
                  const curvilinear::GridQuality* quality = nullptr);

/// Reads a planar grid: any netCDF file with 2-D double-convertible variables x and y of the same
/// shape (≥ 2×2, finite). Global attributes other than the reserved ones go to `attributes`
/// (text, double, or int64 for integer types; numeric arrays are kept as space-separated text).
/// Throws InputError naming the file and what is missing or wrong.
XyGrid read_xygrid(const std::filesystem::path& path);

}  // namespace aq::io

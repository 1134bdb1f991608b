// SPDX-License-Identifier: GPL-3.0-or-later
// Coordinate-variable check of netCDF rasters (see the header).
#include "raster/netcdf_coordinates.hpp"

#include <fmt/format.h>
#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "io/netcdf_file.hpp"

namespace aq::raster {
namespace {

// Checks coordinate vector `c` (n values) against centres first + k·step (k = 0..n-1), in
// either order: a tolerance of 1 % of a step allows float32 coordinates.
void check_axis(const std::string& path, const std::string& name, const std::vector<double>& c, double first,
                double step, bool longitude) {
  const auto n = static_cast<std::int64_t>(c.size());
  if (n < 2) return;
  const bool ascending = c[1] > c[0];
  const double tol = 0.01 * std::abs(step);
  for (std::int64_t k = 1; k < n; ++k) {
    const double d = c[static_cast<std::size_t>(k)] - c[static_cast<std::size_t>(k - 1)];
    if (!std::isfinite(c[static_cast<std::size_t>(k)]) || !(ascending ? d > 0.0 : d < 0.0))
      throw InputError(fmt::format("{}: coordinate variable {} is not strictly monotonic: value {} is {}, after {}",
                                   path, name, k, c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>(k - 1)]));
  }
  for (std::int64_t k = 0; k < n; ++k) {
    const double want =
        ascending ? first + static_cast<double>(k) * step : first + static_cast<double>(n - 1 - k) * step;
    const double got = c[static_cast<std::size_t>(k)];
    // Longitudes (the x axis) may differ from the geotransform by whole turns.
    double diff = got - want;
    if (longitude) diff -= 360.0 * std::round(diff / 360.0);
    if (std::abs(diff) > tol)
      throw InputError(
          fmt::format("{}: coordinate variable {} is not evenly spaced: value {} is {}, the regular grid puts {} there",
                      path, name, k, got, want));
  }
}

}  // namespace

void check_netcdf_coordinates(const std::string& path, const std::string& variable, const std::array<double, 6>& gt,
                              std::int64_t width, std::int64_t height) {
  io::NcFile nc;
  io::open_for_reading(path, nc);
  int var = -1;
  if (nc_inq_varid(nc.id(), variable.c_str(), &var) != NC_NOERR) return;  // GDAL's name for it differs
  int ndims = 0;
  if (nc_inq_varndims(nc.id(), var, &ndims) != NC_NOERR || ndims < 2 || ndims > NC_MAX_VAR_DIMS) return;
  std::vector<int> dims(static_cast<std::size_t>(ndims));
  if (nc_inq_vardimid(nc.id(), var, dims.data()) != NC_NOERR) return;
  for (int axis = 0; axis < 2; ++axis) {  // 0: x (the last dimension), 1: y
    const int dim = dims[static_cast<std::size_t>(ndims - 1 - axis)];
    char name[NC_MAX_NAME + 1] = {};
    std::size_t len = 0;
    if (nc_inq_dim(nc.id(), dim, name, &len) != NC_NOERR) return;
    int cv = -1, cv_dims = 0, cv_dim = -1;
    if (nc_inq_varid(nc.id(), name, &cv) != NC_NOERR || nc_inq_varndims(nc.id(), cv, &cv_dims) != NC_NOERR ||
        cv_dims != 1 || nc_inq_vardimid(nc.id(), cv, &cv_dim) != NC_NOERR || cv_dim != dim)
      continue;
    if (static_cast<std::int64_t>(len) != (axis == 0 ? width : height)) continue;  // not the raster's axis
    std::vector<double> c(len);
    if (len == 0 || nc_get_var_double(nc.id(), cv, c.data()) != NC_NOERR) continue;
    // Centres of the geotransform's columns (ascending) or rows (ascending from the bottom).
    const double step = axis == 0 ? gt[1] : std::abs(gt[5]);
    const double first =
        axis == 0 ? gt[0] + 0.5 * gt[1]
                  : (gt[5] < 0.0 ? gt[3] + (static_cast<double>(height) - 0.5) * gt[5] : gt[3] + 0.5 * gt[5]);
    check_axis(path, name, c, first, step, axis == 0);
  }
}

}  // namespace aq::raster

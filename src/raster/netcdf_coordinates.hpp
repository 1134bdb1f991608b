// SPDX-License-Identifier: GPL-3.0-or-later
// A netCDF raster's coordinate variables checked against the geotransform GDAL derived from them
// (issue 23). GDAL's netCDF driver looks at the spacing of a coordinate variable only at a few
// places, so a latitude vector with two values swapped, or one repeated, got a regular
// geotransform and the data were sampled at the wrong latitudes. Here every value is checked:
// strictly monotonic, evenly spaced, and where the geotransform puts it.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace aq::raster {

/// Checks the coordinate variables (variables named like the dimensions) of the last two
/// dimensions of netCDF variable `variable` in `path`: x against the geotransform's columns
/// (width values), y against its rows (height values, either order). Variables without such
/// coordinate variables pass. Throws InputError naming the file, the variable and the first bad
/// value. `path` must be a netCDF file (classic or netCDF-4).
void check_netcdf_coordinates(const std::string& path, const std::string& variable, const std::array<double, 6>& gt,
                              std::int64_t width, std::int64_t height);

}  // namespace aq::raster

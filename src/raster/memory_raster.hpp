// SPDX-License-Identifier: GPL-3.0-or-later
// A bathymetry raster held in memory by the caller (the Python interface: a numpy array with its
// longitude and latitude vectors, or an xarray DataArray) made readable through the one raster
// path every input takes: it is written once as a GeoTIFF in GDAL's in-memory file system
// (/vsimem/), so the pipeline opens it by name exactly as it opens the same data written to a
// GeoTIFF on disk (same normalisation, same sampling, the same mesh). Only this folder includes
// GDAL.
//
// Georeferencing: the values are at the points (lon[i], lat[j]) (cell centres, as GDAL reads a
// CF lon/lat netCDF file), equally spaced; the file is EPSG:4326, north-up (rows are reversed
// when lat is ascending), floating point values with NaN as "no data".
#pragma once

#include <cstdint>
#include <string>

namespace aq::raster {

/// The element type of the caller's array.
enum class MemoryType { kInt16, kInt32, kFloat32, kFloat64 };

/// An in-memory GeoTIFF; the /vsimem/ file is removed when this object is destroyed.
class MemoryRaster {
 public:
  /// Writes `values` (ny rows of nx values, row j at latitude lat[j], column i at lon[i]; rows
  /// `row_stride` elements apart) as /vsimem/aquatoria/raster_<n>.tif. Throws InputError naming
  /// the problem: fewer than 2 points along an axis, coordinates not finite, not strictly
  /// monotonic or not equally spaced (relative 1e-6), longitudes descending, a longitude span over
  /// 360° + one step, latitudes outside [-90, 90] (with half a step of slack).
  MemoryRaster(const void* values, MemoryType type, std::int64_t nx, std::int64_t ny, std::int64_t row_stride,
               const double* lon, const double* lat);
  ~MemoryRaster();
  MemoryRaster(const MemoryRaster&) = delete;
  MemoryRaster& operator=(const MemoryRaster&) = delete;

  /// The GDAL name to give as input.path.
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace aq::raster

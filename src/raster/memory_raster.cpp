// SPDX-License-Identifier: GPL-3.0-or-later
// An in-memory raster as a /vsimem/ GeoTIFF (see memory_raster.hpp).
#include "raster/memory_raster.hpp"

#include <cpl_vsi.h>
#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "raster/geotiff_writer.hpp"

namespace aq::raster {

namespace {

// The step of equally spaced coordinates (negative when descending); InputError otherwise.
double regular_step(const double* v, std::int64_t n, const char* name) {
  if (n < 2) throw InputError(fmt::format("in-memory raster: {} has {} value(s); at least 2 are needed", name, n));
  for (std::int64_t k = 0; k < n; ++k)
    if (!std::isfinite(v[k]))
      throw InputError(fmt::format("in-memory raster: {}[{}] = {} is not finite", name, k, v[k]));
  const double step = (v[n - 1] - v[0]) / static_cast<double>(n - 1);
  if (step == 0.0) throw InputError(fmt::format("in-memory raster: {} is constant ({})", name, v[0]));
  for (std::int64_t k = 1; k < n; ++k) {
    const double d = v[k] - v[k - 1];
    if (std::abs(d - step) > 1e-6 * std::abs(step))
      throw InputError(
          fmt::format("in-memory raster: {} is not equally spaced ({}[{}] - {}[{}] = {}, the mean step is {})", name,
                      name, k, name, k - 1, d, step));
  }
  return step;
}

}  // namespace

MemoryRaster::MemoryRaster(const void* values, MemoryType type, std::int64_t nx, std::int64_t ny,
                           std::int64_t row_stride, const double* lon, const double* lat) {
  const double dlon = regular_step(lon, nx, "lon");
  const double dlat = regular_step(lat, ny, "lat");
  if (dlon < 0.0) throw InputError("in-memory raster: lon must be ascending");
  if (static_cast<double>(nx - 1) * dlon > 360.0 + dlon * (1.0 + 1e-9))
    throw InputError(fmt::format("in-memory raster: lon spans {}°, more than 360° and one step",
                                 static_cast<double>(nx - 1) * dlon));
  const double lat_lo = std::min(lat[0], lat[ny - 1]), lat_hi = std::max(lat[0], lat[ny - 1]);
  const double ady = std::abs(dlat);
  if (lat_lo < -90.0 - 0.5 * ady * (1.0 + 1e-9) || lat_hi > 90.0 + 0.5 * ady * (1.0 + 1e-9))
    throw InputError(fmt::format("in-memory raster: lat spans [{}, {}], outside [-90, 90]", lat_lo, lat_hi));

  static std::atomic<std::int64_t> counter{0};
  path_ = fmt::format("/vsimem/aquatoria/raster_{}.tif", ++counter);
  GeoTiffSpec spec;
  spec.width = nx;
  spec.height = ny;
  std::size_t bytes = 8;
  switch (type) {
    case MemoryType::kInt16:
      spec.type = GeoTiffType::kInt16;
      bytes = 2;
      break;
    case MemoryType::kInt32:
      spec.type = GeoTiffType::kInt32;
      bytes = 4;
      break;
    case MemoryType::kFloat32:
      spec.type = GeoTiffType::kFloat32;
      bytes = 4;
      break;
    case MemoryType::kFloat64:
      spec.type = GeoTiffType::kFloat64;
      bytes = 8;
      break;
  }
  spec.creation_options = {"BIGTIFF=IF_SAFER"};
  // North-up: row 0 of the file is the northernmost latitude.
  const bool ascending = dlat > 0.0;
  const double north = std::max(lat[0], lat[ny - 1]) + 0.5 * ady;
  spec.geotransform = {lon[0] - 0.5 * dlon, dlon, 0.0, north, 0.0, -ady};
  if (type == MemoryType::kFloat32 || type == MemoryType::kFloat64)
    spec.no_data = std::numeric_limits<double>::quiet_NaN();
  try {
    GeoTiffWriter out(path_, spec);
    const auto* base = static_cast<const unsigned char*>(values);
    for (std::int64_t r = 0; r < ny; ++r) {
      const std::int64_t src = ascending ? ny - 1 - r : r;
      out.write_rows(1, r, 1, base + static_cast<std::size_t>(src * row_stride) * bytes);
    }
    out.close();
  } catch (const OutputError& e) {
    throw InputError(fmt::format("in-memory raster: {}", e.what()));
  }
}

MemoryRaster::~MemoryRaster() { VSIUnlink(path_.c_str()); }

}  // namespace aq::raster

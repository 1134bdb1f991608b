// An in-memory raster as a /vsimem/ GeoTIFF (see memory_raster.hpp).
#include "raster/memory_raster.hpp"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.hpp"
#include "raster/gdal_handles.hpp"

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

  gdal_register();
  static std::atomic<std::int64_t> counter{0};
  path_ = fmt::format("/vsimem/aquatoria/raster_{}.tif", ++counter);
  GDALDataType gt = GDT_Float64;
  std::size_t bytes = 8;
  switch (type) {
    case MemoryType::kInt16:
      gt = GDT_Int16;
      bytes = 2;
      break;
    case MemoryType::kInt32:
      gt = GDT_Int32;
      bytes = 4;
      break;
    case MemoryType::kFloat32:
      gt = GDT_Float32;
      bytes = 4;
      break;
    case MemoryType::kFloat64:
      gt = GDT_Float64;
      bytes = 8;
      break;
  }
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (driver == nullptr) throw InputError("in-memory raster: GDAL has no GTiff driver");
  const char* options[] = {"BIGTIFF=IF_SAFER", nullptr};
  GDALDataset* ds =
      driver->Create(path_.c_str(), static_cast<int>(nx), static_cast<int>(ny), 1, gt, const_cast<char**>(options));
  if (ds == nullptr) throw InputError(fmt::format("in-memory raster: cannot create {}{}", path_, last_gdal_error()));
  // North-up: row 0 of the file is the northernmost latitude.
  const bool ascending = dlat > 0.0;
  const double north = std::max(lat[0], lat[ny - 1]) + 0.5 * ady;
  double transform[6] = {lon[0] - 0.5 * dlon, dlon, 0.0, north, 0.0, -ady};
  ds->SetGeoTransform(transform);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  ds->SetSpatialRef(&srs);
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (type == MemoryType::kFloat32 || type == MemoryType::kFloat64)
    band->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
  CPLErr err = CE_None;
  const auto* base = static_cast<const unsigned char*>(values);
  for (std::int64_t r = 0; r < ny && err == CE_None; ++r) {
    const std::int64_t src = ascending ? ny - 1 - r : r;
    err = band->RasterIO(GF_Write, 0, static_cast<int>(r), static_cast<int>(nx), 1,
                         const_cast<unsigned char*>(base + static_cast<std::size_t>(src * row_stride) * bytes),
                         static_cast<int>(nx), 1, gt, 0, 0);
  }
  GDALClose(GDALDataset::ToHandle(ds));
  if (err != CE_None) {
    VSIUnlink(path_.c_str());
    throw InputError(fmt::format("in-memory raster: cannot write {}{}", path_, last_gdal_error()));
  }
}

MemoryRaster::~MemoryRaster() { VSIUnlink(path_.c_str()); }

}  // namespace aq::raster

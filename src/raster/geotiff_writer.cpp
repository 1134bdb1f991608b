// SPDX-License-Identifier: GPL-3.0-or-later
// The GeoTIFF writer (see geotiff_writer.hpp).
#include "raster/geotiff_writer.hpp"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <fmt/format.h>
#include <ogr_spatialref.h>

#include "core/error.hpp"

namespace aq::raster {

namespace {

GDALDataType gdal_type(GeoTiffType t) {
  switch (t) {
    case GeoTiffType::kByte:
      return GDT_Byte;
    case GeoTiffType::kInt16:
      return GDT_Int16;
    case GeoTiffType::kInt32:
      return GDT_Int32;
    case GeoTiffType::kFloat32:
      return GDT_Float32;
    case GeoTiffType::kFloat64:
      return GDT_Float64;
  }
  return GDT_Unknown;
}

}  // namespace

GeoTiffWriter::GeoTiffWriter(std::string path, const GeoTiffSpec& spec) : path_(std::move(path)), spec_(spec) {
  gdal_init();
  const NoSidecar no_sidecar;
  if (spec_.width <= 0 || spec_.height <= 0 || spec_.bands <= 0 || spec_.width > 2147483647 ||
      spec_.height > 2147483647)
    fail(fmt::format("of {} x {} pixels and {} bands", spec_.width, spec_.height, spec_.bands));
  if (!spec_.band_names.empty() && static_cast<int>(spec_.band_names.size()) != spec_.bands)
    throw InternalError(fmt::format("{}: {} band names for {} bands", path_, spec_.band_names.size(), spec_.bands));
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (driver == nullptr) fail("driver missing in this GDAL");
  std::vector<char*> options;
  for (const std::string& o : spec_.creation_options) options.push_back(const_cast<char*>(o.c_str()));
  options.push_back(nullptr);
  ds_.reset(driver->Create(path_.c_str(), static_cast<int>(spec_.width), static_cast<int>(spec_.height), spec_.bands,
                           gdal_type(spec_.type), options.data()));
  if (!ds_) fail("cannot create");
  std::array<double, 6> gt = spec_.geotransform;
  if (ds_->SetGeoTransform(gt.data()) != CE_None) fail("georeferencing");
  OGRSpatialReference srs;
  if (spec_.proj4.empty()) {
    srs.importFromEPSG(4326);
  } else if (srs.importFromProj4(spec_.proj4.c_str()) != OGRERR_NONE) {
    fail("coordinate system " + spec_.proj4);
  }
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (ds_->SetSpatialRef(&srs) != CE_None) fail("coordinate system");
  for (const auto& [k, v] : spec_.metadata)
    if (ds_->SetMetadataItem(k.c_str(), v.c_str()) != CE_None) fail("metadata " + k);
  for (int b = 0; b < spec_.bands; ++b) {
    GDALRasterBand* band = ds_->GetRasterBand(b + 1);
    if (!spec_.band_names.empty()) band->SetDescription(spec_.band_names[static_cast<std::size_t>(b)].c_str());
    if (spec_.no_data && band->SetNoDataValue(*spec_.no_data) != CE_None) fail("no-data value");
  }
}

GeoTiffWriter::~GeoTiffWriter() {
  if (!ds_) return;
  ds_.reset();
  VSIUnlink(path_.c_str());  // unfinished: not a file anyone should read
}

void GeoTiffWriter::write_rows(int band, std::int64_t row0, std::int64_t rows, const void* data) {
  if (!ds_ || band < 1 || band > spec_.bands || row0 < 0 || rows < 0 || row0 + rows > spec_.height)
    throw InternalError(fmt::format("{}: write band {} rows {}+{} outside the raster", path_, band, row0, rows));
  const NoSidecar no_sidecar;
  if (ds_->GetRasterBand(band)->RasterIO(GF_Write, 0, static_cast<int>(row0), static_cast<int>(spec_.width),
                                         static_cast<int>(rows), const_cast<void*>(data), static_cast<int>(spec_.width),
                                         static_cast<int>(rows), gdal_type(spec_.type), 0, 0, nullptr) != CE_None)
    fail("write rows");
}

void GeoTiffWriter::close() {
  const NoSidecar no_sidecar;
  CPLErrorReset();
  ds_.reset();  // closes: the last tiles are written here
  if (CPLGetLastErrorType() == CE_Failure) {
    VSIUnlink(path_.c_str());
    throw OutputError(fmt::format("{}: GeoTIFF close{}", path_, gdal_message()));
  }
}

void GeoTiffWriter::fail(const std::string& what) {
  const std::string message = fmt::format("{}: GeoTIFF {}{}", path_, what, gdal_message());
  ds_.reset();
  VSIUnlink(path_.c_str());
  throw OutputError(message);
}

}  // namespace aq::raster

// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23, input side: a raster is validated before it is trusted. Each case was accepted before
// (and read wrong): a netCDF-3 file cut to half its bytes (zeros past the cut), complex bands
// (imaginary part dropped), signed-byte GeoTIFFs (read unsigned), latitude coordinates swapped or
// repeated (GDAL looks at a few spacings only), a NaN geotransform, sentinel values of -1e29 m;
// and a regional raster over 280..350°E gave no data at -40°E.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "raster/bathymetry.hpp"
#include "support/temp_dir.hpp"

namespace unit_raster_raster_validation_test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

// A netCDF-3 raster with lat/lon coordinate variables and a float `z` of -1000 m (30 x 20 cells
// of 1°, from 0°E and 0°N unless given).
fs::path write_nc(const fs::path& p, std::vector<double> lat = {}, std::vector<double> lon = {},
                  float value = -1000.0f) {
  if (lat.empty())
    for (int k = 0; k < 20; ++k) lat.push_back(k + 0.5);
  if (lon.empty())
    for (int k = 0; k < 30; ++k) lon.push_back(k + 0.5);
  int nc = -1, dlat = -1, dlon = -1, vlat = -1, vlon = -1, vz = -1;
  EXPECT_EQ(nc_create(p.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_def_dim(nc, "lat", lat.size(), &dlat);
  nc_def_dim(nc, "lon", lon.size(), &dlon);
  nc_def_var(nc, "lat", NC_DOUBLE, 1, &dlat, &vlat);
  nc_def_var(nc, "lon", NC_DOUBLE, 1, &dlon, &vlon);
  nc_put_att_text(nc, vlat, "units", 13, "degrees_north");
  nc_put_att_text(nc, vlon, "units", 12, "degrees_east");
  const int dims[2] = {dlat, dlon};
  nc_def_var(nc, "z", NC_FLOAT, 2, dims, &vz);
  nc_enddef(nc);
  nc_put_var_double(nc, vlat, lat.data());
  nc_put_var_double(nc, vlon, lon.data());
  const std::vector<float> z(lat.size() * lon.size(), value);
  nc_put_var_float(nc, vz, z.data());
  EXPECT_EQ(nc_close(nc), NC_NOERR);
  return p;
}

// A GeoTIFF of w x h cells of `step` degrees from (lon0, lat_top), type `type`, all `value`
// (written as double), with optional creation options.
fs::path write_tif(const fs::path& p, GDALDataType type, double value, double lon0 = 0.0, int w = 30, int h = 20,
                   double step = 1.0, const char* pixeltype = nullptr, const double* gt_in = nullptr) {
  GDALAllRegister();
  char** opts = nullptr;
  if (pixeltype != nullptr) opts = CSLSetNameValue(opts, "PIXELTYPE", pixeltype);
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(p.c_str(), w, h, 1, type, opts);
  CSLDestroy(opts);
  double gt[6] = {lon0, step, 0.0, 50.0, 0.0, -step};
  if (gt_in != nullptr) std::copy(gt_in, gt_in + 6, gt);
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  ds->SetSpatialRef(&srs);
  std::vector<double> buf(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), value);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, buf.data(), w, h, GDT_Float64, 0, 0, nullptr),
            CE_None);
  GDALClose(ds);
  return p;
}

aq::raster::Bathymetry open(const fs::path& p) {
  aq::raster::OpenOptions o;
  o.path = p.string();
  return aq::raster::Bathymetry::open(o);
}

std::string open_error(const fs::path& p) {
  try {
    (void)open(p);
  } catch (const aq::InputError& e) {
    return e.what();
  }
  return "(opened)";
}

}  // namespace

TEST(RasterValidation, AGoodNetcdfRasterOpens) {
  aq::testing::TempDir dir;
  const auto b = open(write_nc(dir / "ok.nc"));
  EXPECT_DOUBLE_EQ(b.sample(10.0, 10.0), -1000.0);
}

TEST(RasterValidation, ATruncatedNetcdf3FileIsRefused) {
  aq::testing::TempDir dir;
  const fs::path p = write_nc(dir / "cut.nc");
  fs::resize_file(p, fs::file_size(p) / 2);
  EXPECT_THAT(open_error(p), HasSubstr("the file is cut short?"));
}

TEST(RasterValidation, NonMonotonicOrRepeatedLatitudesAreRefused) {
  aq::testing::TempDir dir;
  std::vector<double> lat;
  for (int k = 0; k < 20; ++k) lat.push_back(k + 0.5);
  std::vector<double> swapped = lat, repeated = lat, uneven = lat;
  std::swap(swapped[7], swapped[8]);
  repeated[7] = repeated[8];
  uneven[7] += 0.3;
  EXPECT_THAT(open_error(write_nc(dir / "swap.nc", swapped)),
              HasSubstr("coordinate variable lat is not strictly monotonic"));
  EXPECT_THAT(open_error(write_nc(dir / "rep.nc", repeated)),
              HasSubstr("coordinate variable lat is not strictly monotonic"));
  EXPECT_THAT(open_error(write_nc(dir / "uneven.nc", uneven)),
              HasSubstr("coordinate variable lat is not evenly spaced"));
}

TEST(RasterValidation, ComplexBandsAreRefused) {
  aq::testing::TempDir dir;
  EXPECT_THAT(open_error(write_tif(dir / "c.tif", GDT_CFloat32, -1000.0)),
              HasSubstr("holds complex numbers (CFloat32)"));
}

TEST(RasterValidation, SignedBytesAreHonoured) {
  aq::testing::TempDir dir;
  // -85 stored as a signed byte is 171 unsigned: it must read as -85, not +171.
  const auto b = open(write_tif(dir / "s.tif", GDT_Byte, 171.0, 0.0, 30, 20, 1.0, "SIGNEDBYTE"));
  EXPECT_DOUBLE_EQ(b.sample(10.0, 40.0), -85.0);
  EXPECT_EQ(b.info().data_type, "Int8 (signed byte)");
  const auto u = open(write_tif(dir / "u.tif", GDT_Byte, 171.0));
  EXPECT_DOUBLE_EQ(u.sample(10.0, 40.0), 171.0);
}

TEST(RasterValidation, ANonFiniteGeotransformIsRefused) {
  aq::testing::TempDir dir;
  const double gt[6] = {0.0, 1.0, 0.0, std::nan(""), 0.0, -1.0};
  EXPECT_THAT(open_error(write_tif(dir / "nan.tif", GDT_Float32, -1000.0, 0.0, 30, 20, 1.0, nullptr, gt)),
              HasSubstr("geotransform (0, 1, 0, nan, 0, -1) is not finite"));
}

// Issue 33: a geotransform with a pixel of 1e300 degrees was opened (and meshed) as a small
// raster. A lon/lat pixel is between 1e-9° and the globe, and the columns span at most 360°.
TEST(RasterValidation, AnImpossiblePixelSizeIsRefusedNamingTheFile) {
  aq::testing::TempDir dir;
  const auto error = [&](const char* name, double dx, double dy, int w = 30) {
    const double gt[6] = {0.0, dx, 0.0, 50.0, 0.0, -dy};
    return open_error(write_tif(dir / name, GDT_Float32, -1000.0, 0.0, w, 20, 1.0, nullptr, gt));
  };
  const std::string huge = error("huge.tif", 1e300, 1.0);
  EXPECT_THAT(huge, HasSubstr((dir / "huge.tif").string() + ": the geotransform's pixel is 1e+300° × -1°"));
  EXPECT_THAT(huge, HasSubstr("between 1e-09° and 360° × 180°"));
  EXPECT_THAT(error("tall.tif", 1.0, 200.0), HasSubstr("pixel is 1° × -200°"));
  EXPECT_THAT(error("tiny.tif", 1e-300, 1.0), HasSubstr("pixel is 1e-300° × -1°"));
  EXPECT_THAT(error("wide.tif", 13.0, 1.0), HasSubstr("30 columns of 13° span 390° of longitude"));
  EXPECT_EQ(error("fine.tif", 1e-6, 1e-6), "(opened)");                     // 0.1 m pixels
  EXPECT_EQ(error("global.tif", 12.0, 1.0), "(opened)");                    // exactly the globe
  EXPECT_EQ(error("duplicate_column.tif", 360.0 / 29.0, 1.0), "(opened)");  // 0..360 with 360 repeated
}

// Values beyond ±max_abs_elevation_m (12 km by default) are no-data, counted.
TEST(RasterValidation, ImplausibleValuesAreNoData) {
  aq::testing::TempDir dir;
  // Every value a sentinel of -1e29 m: no data at all (it was a sea 1e29 m deep).
  EXPECT_THAT(open_error(write_tif(dir / "sentinel.tif", GDT_Float32, -1e29)), HasSubstr("holds no data"));
}

TEST(RasterValidation, ImplausibleValuesAreCounted) {
  aq::testing::TempDir dir;
  GDALAllRegister();
  const fs::path p = write_tif(dir / "some.tif", GDT_Float32, -3000.0);
  {
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(p.c_str(), GA_Update));
    float bad[2] = {-1e29f, 20000.0f};
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 3, 4, 2, 1, bad, 2, 1, GDT_Float32, 0, 0, nullptr), CE_None);
    GDALClose(ds);
  }
  std::vector<std::string> lines;
  const aq::Logger log([&lines](aq::LogLevel, std::string_view m) { lines.emplace_back(m); });
  aq::raster::OpenOptions o;
  o.path = p.string();
  const auto b = aq::raster::Bathymetry::open(o, log);
  EXPECT_EQ(b.info().implausible_count, 2);
  EXPECT_TRUE(std::isnan(b.value(3, 15)));  // stored row 4 is normalised row 15 (south-up)
  EXPECT_DOUBLE_EQ(b.info().min_m, -3000.0);
  EXPECT_DOUBLE_EQ(b.info().max_m, -3000.0);
  bool said = false;
  for (const auto& l : lines)
    said = said || l.find("beyond ±12000 m treated as no-data (input.max_abs_elevation_m)") != std::string::npos;
  EXPECT_TRUE(said);
}

// Any longitude origin, for a regional raster too: 280..350°E answers at -40°E as at 320°E.
TEST(RasterValidation, RegionalRastersWrapInLongitude) {
  aq::testing::TempDir dir;
  GDALAllRegister();
  const fs::path p = write_tif(dir / "east.tif", GDT_Float32, 0.0, 280.0, 70, 20);
  {
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(p.c_str(), GA_Update));
    std::vector<float> v(70 * 20);
    for (int r = 0; r < 20; ++r)
      for (int c = 0; c < 70; ++c) v[static_cast<std::size_t>(r * 70 + c)] = -100.0f * static_cast<float>(c);
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 70, 20, v.data(), 70, 20, GDT_Float32, 0, 0, nullptr),
              CE_None);
    GDALClose(ds);
  }
  const auto b = open(p);
  const double at320 = b.sample(320.0, 40.0);
  EXPECT_TRUE(std::isfinite(at320));
  EXPECT_DOUBLE_EQ(b.sample(-40.0, 40.0), at320);
  EXPECT_DOUBLE_EQ(b.sample(-40.0 - 720.0, 40.0), at320);
  EXPECT_TRUE(std::isnan(b.sample(0.0, 40.0)));  // outside the raster stays no data
}

}  // namespace unit_raster_raster_validation_test

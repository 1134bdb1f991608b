// SPDX-License-Identifier: GPL-3.0-or-later
// Bathymetry input: synthetic rasters written through GDAL (MEM → GTiff, netCDF) with analytic
// values, in every origin/orientation/registration variant; error paths; and the real ETOPO files.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "core/error.hpp"
#include "raster/bathymetry.hpp"

namespace unit_raster_bathymetry_test {

namespace fs = std::filesystem;
using aq::raster::Bathymetry;
using aq::raster::OpenOptions;
using ::testing::HasSubstr;

namespace {

fs::path tmpdir() {
  const fs::path d = fs::temp_directory_path() / "aq_raster_test";
  fs::create_directories(d);
  return d;
}

struct Layout {
  double lon_first;  // centre of the first stored column
  double lat_top;    // centre of the first stored row
  double step;       // degrees
  int width, height;
  bool north_up = true;
};

// Writes f(lon, lat) sampled at the layout's points. Driver "GTiff" or "netCDF".
fs::path write_raster(const std::string& name, const std::string& driver, const Layout& l,
                      const std::function<double(double, double)>& f, GDALDataType type = GDT_Float32,
                      double scale = 1.0, double offset = 0.0, const char* epsg = "EPSG:4326",
                      std::optional<double> nodata = std::nullopt) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDataset* ds = mem->Create("", l.width, l.height, 1, type, nullptr);
  const double dy = l.north_up ? -l.step : l.step;
  double gt[6] = {l.lon_first - 0.5 * l.step, l.step, 0, l.lat_top - 0.5 * dy, 0, dy};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.SetFromUserInput(epsg);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  ds->SetSpatialRef(&srs);
  std::vector<double> buf(static_cast<std::size_t>(l.width) * l.height);
  for (int r = 0; r < l.height; ++r)
    for (int c = 0; c < l.width; ++c) {
      const double v = f(l.lon_first + c * l.step, l.lat_top + r * dy);
      buf[static_cast<std::size_t>(r) * l.width + c] = std::isnan(v) ? *nodata : (v - offset) / scale;
    }
  GDALRasterBand* b = ds->GetRasterBand(1);
  if (scale != 1.0) b->SetScale(scale);
  if (offset != 0.0) b->SetOffset(offset);
  if (nodata) b->SetNoDataValue(*nodata);
  EXPECT_EQ(b->RasterIO(GF_Write, 0, 0, l.width, l.height, buf.data(), l.width, l.height, GDT_Float64, 0, 0, nullptr),
            CE_None);
  const fs::path p = tmpdir() / name;
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName(driver.c_str());
  GDALDataset* out = drv->CreateCopy(p.c_str(), ds, FALSE, nullptr, nullptr, nullptr);
  GDALClose(out);
  GDALClose(ds);
  return p;
}

Bathymetry open(const fs::path& p, bool positive_down = false, const std::string& var = "") {
  OpenOptions o;
  o.path = p.string();
  o.positive_down = positive_down;
  o.variable = var;
  return Bathymetry::open(o);
}

std::string open_error(const OpenOptions& o) {
  try {
    (void)Bathymetry::open(o);
  } catch (const aq::InputError& e) {
    EXPECT_EQ(e.exit_code(), 1);
    return e.what();
  }
  return "";
}

// A field that is bilinear in (lon, lat) within the region used.
double bilin(double lon, double lat) { return -4000.0 + 3.0 * lon - 7.0 * lat + 0.25 * lon * lat; }

// A global field: linear in lat, and piecewise linear in lon with kinks only at multiples of 2°
// (so bilinear sampling of any 1°/2° grid-registered raster reproduces it exactly).
double global_field(double lon, double lat) {
  double x = std::fmod(lon, 360.0);
  if (x < 0) x += 360.0;
  const double tri = std::abs(std::fmod(x, 60.0) - 30.0);  // kinks at multiples of 30°
  return -3000.0 + 10.0 * lat + 20.0 * tri;
}

}  // namespace

TEST(BathymetryFromGrid, BilinearReproducesBilinearFunctionsExactly) {
  const int nc = 41, nr = 31;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c)
      v[static_cast<std::size_t>(r * nc + c)] = static_cast<float>(bilin(10.0 + c, -20.0 + r));
  // Regional raster: values are small integers' combos exactly representable in float.
  const auto b = Bathymetry::from_grid(v, nc, nr, 10.0, -20.0, 1.0, 1.0);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> ulon(10.0, 50.0), ulat(-20.0, 10.0);
  for (int k = 0; k < 1000; ++k) {
    const double lon = ulon(rng), lat = ulat(rng);
    // Bilinear interpolation of a bilinear function is exact within each cell.
    EXPECT_NEAR(b.sample(lon, lat), bilin(lon, lat), 1e-9 * 5000.0) << lon << "," << lat;
  }
  EXPECT_TRUE(std::isnan(b.sample(5.0, 0.0)));  // outside a regional raster
  EXPECT_TRUE(std::isnan(b.sample(20.0, 30.0)));
}

TEST(BathymetryFromGrid, WrapsAcrossTheSeam) {
  const int nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c)
      v[static_cast<std::size_t>(r * nc + c)] = static_cast<float>(c == 359 ? 100 : c == 0 ? 200 : -1);
  const auto b = Bathymetry::from_grid(v, nc, nr, 0.0, -90.0, 1.0, 1.0);
  EXPECT_TRUE(b.info().global_lon);
  EXPECT_DOUBLE_EQ(b.sample(359.5, 0.0), 150.0);  // between the last and first column
  EXPECT_DOUBLE_EQ(b.sample(-0.5, 0.0), 150.0);
  EXPECT_DOUBLE_EQ(b.sample(719.75, 10.0), 175.0);
  EXPECT_DOUBLE_EQ(b.sample(0.0, 0.0), 200.0);
  EXPECT_DOUBLE_EQ(b.sample(360.0, 0.0), 200.0);
}

TEST(BathymetryFromGrid, GridLinePointsTakeGridValuesExactly) {
  std::vector<float> v = {0.0f, -1.0f, 7.0f, 3.0f};
  const auto b = Bathymetry::from_grid(v, 2, 2, 0.0, 0.0, 0.1, 0.1);
  // 0.3 - 0.2 style rounding: sample at a point computed with rounding error stays on the line.
  EXPECT_EQ(b.sample(0.3 - 0.2, 0.0), -1.0);
  EXPECT_EQ(b.sample(0.0, 0.1 + 1e-13), 7.0);
}

TEST(BathymetryFromGrid, BicubicReproducesSmoothFieldAndGridValues) {
  const int nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  auto f = [](double lon, double lat) {
    return 1000.0 * std::cos(lon * M_PI / 180.0 * 3) * std::cos(lat * M_PI / 180.0);
  };
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c) v[static_cast<std::size_t>(r * nc + c)] = static_cast<float>(f(c, -90.0 + r));
  const auto cub = Bathymetry::from_grid(v, nc, nr, 0.0, -90.0, 1.0, 1.0, aq::raster::Interpolation::kBicubic);
  const auto lin = Bathymetry::from_grid(v, nc, nr, 0.0, -90.0, 1.0, 1.0);
  double err_c = 0, err_l = 0;
  for (double lon = 0.37; lon < 360; lon += 7.3)
    for (double lat = -60.21; lat < 60; lat += 5.7) {
      err_c = std::max(err_c, std::abs(cub.sample(lon, lat) - f(lon, lat)));
      err_l = std::max(err_l, std::abs(lin.sample(lon, lat) - f(lon, lat)));
    }
  EXPECT_LT(err_c, 0.01);        // O(h^4): (3·π/180)^4·1000/384 ≈ 2e-4 plus float rounding
  EXPECT_GT(err_l, 10 * err_c);  // bilinear is O(h^2)
  EXPECT_NEAR(cub.sample(10.0, 20.0), f(10.0, 20.0), 1e-3);  // interpolates the grid values
}

namespace {  // beside Layout (in the namespace above), so the fixture's type has the same linkage

struct VariantCase {
  const char* name;
  const char* driver;
  Layout layout;
};

class OriginVariants : public ::testing::TestWithParam<VariantCase> {};

TEST_P(OriginVariants, SameSamplesAsReference) {
  const auto& vc = GetParam();
  const std::string drv = vc.driver;
  const bool gmt = std::string(vc.name).rfind("gmt", 0) == 0;  // GMT 4+ grd files are netCDF
  const std::string ext = drv == "GTiff" ? ".tif" : drv == "EHdr" ? ".bin" : gmt ? ".grd" : ".nc";
  const fs::path p = write_raster(std::string(vc.name) + ext, vc.driver, vc.layout, global_field);
  const auto b = open(p);
  EXPECT_TRUE(b.info().global_lon) << vc.name;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ulon(-400.0, 400.0), ulat(-80.0, 80.0);
  for (int k = 0; k < 300; ++k) {
    const double lon = ulon(rng), lat = ulat(rng);
    ASSERT_NEAR(b.sample(lon, lat), global_field(lon, lat), 1e-3) << vc.name << " at " << lon << "," << lat;
  }
  EXPECT_NEAR(b.sample(180.0, 0.0), global_field(180.0, 0.0), 1e-9);
  EXPECT_NEAR(b.sample(-180.0, 0.0), global_field(180.0, 0.0), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(
    Raster, OriginVariants,
    ::testing::Values(VariantCase{"origin0_northup_grid", "GTiff", {0.0, 90.0, 1.0, 360, 181, true}},
                      VariantCase{"origin_minus180_southup", "GTiff", {-180.0, -90.0, 1.0, 360, 181, false}},
                      VariantCase{"origin20_duplicate_column", "GTiff", {20.0, 90.0, 1.0, 361, 181, true}},
                      VariantCase{"origin_minus180_duplicate_360", "netCDF", {-180.0, 90.0, 1.0, 361, 181, true}},
                      VariantCase{"lat_pixel_registered_2deg", "netCDF", {0.0, 89.0, 2.0, 180, 90, true}},
                      VariantCase{"netcdf_origin0", "netCDF", {0.0, -90.0, 2.0, 180, 91, false}},
                      // ETOPO2v2-style raw binary with an .hdr header, and a GMT grd (ETOPO1 .grd).
                      VariantCase{"ehdr_raw_binary", "EHdr", {-180.0, 90.0, 1.0, 360, 181, true}},
                      VariantCase{"gmt_grd", "netCDF", {-180.0, 90.0, 1.0, 361, 181, true}}),
    [](const ::testing::TestParamInfo<VariantCase>& i) { return std::string(i.param.name); });

}  // namespace

TEST(Raster, RegistrationIsReported) {
  const auto g = open(write_raster("reg_grid.tif", "GTiff", {0.0, 90.0, 1.0, 360, 181, true}, global_field));
  const auto px = open(write_raster("reg_pixel.tif", "GTiff", {0.5, 89.5, 1.0, 360, 180, true}, global_field));
  EXPECT_EQ(g.info().registration, "grid");
  EXPECT_EQ(px.info().registration, "pixel");
  EXPECT_DOUBLE_EQ(g.info().lat_first, -90.0);
  EXPECT_DOUBLE_EQ(px.info().lat_first, -89.5);
  // Linear in lat, kinks in lon only at multiples of 30°: points away from kinks agree.
  EXPECT_NEAR(g.sample(45.25, 12.3), px.sample(45.25, 12.3), 1e-3);
}

TEST(Raster, ScaleOffsetPositiveDownAndNoData) {
  const Layout l{-10.0, 10.0, 1.0, 21, 21, true};
  auto depth = [](double lon, double lat) { return (lon == 0.0 && lat == 0.0) ? NAN : 1000.0 + 2.0 * lon; };
  const fs::path p = write_raster("scaled.tif", "GTiff", l, depth, GDT_Int16, 0.5, 100.0, "EPSG:4326", -32768.0);
  const auto b = open(p, /*positive_down=*/true);
  EXPECT_DOUBLE_EQ(b.sample(5.0, 5.0), -1010.0);
  EXPECT_TRUE(std::isnan(b.sample(0.0, 0.0)));
  EXPECT_TRUE(std::isnan(b.sample(0.5, 0.0)));  // a corner of the cell is no-data
  EXPECT_EQ(b.info().data_type, "Int16");
  EXPECT_DOUBLE_EQ(b.info().scale, 0.5);
  EXPECT_FALSE(b.info().global_lon);
}

TEST(Raster, NetcdfVariableChoice) {
  const fs::path p = write_raster("var.nc", "netCDF", {0.0, 90.0, 2.0, 180, 91, true}, global_field);
  EXPECT_NO_THROW((void)open(p, false, "Band1"));
  OpenOptions o;
  o.path = p.string();
  o.variable = "elevation";
  EXPECT_THAT(open_error(o), HasSubstr("variable 'elevation' not found"));
}

TEST(Raster, Errors) {
  OpenOptions o;
  o.path = "/nonexistent/etopo.nc";
  EXPECT_THAT(open_error(o), HasSubstr("/nonexistent/etopo.nc: no such file"));

  const fs::path txt = tmpdir() / "not_a_raster.txt";
  std::ofstream(txt) << "hello\n";
  o.path = txt.string();
  EXPECT_THAT(open_error(o), HasSubstr("not a raster"));

  o.path =
      write_raster("merc.tif", "GTiff", {0.0, 90.0, 1.0, 10, 10, true}, global_field, GDT_Float32, 1, 0, "EPSG:3857")
          .string();
  EXPECT_THAT(open_error(o), HasSubstr("Pseudo-Mercator"));

  o.path = write_raster(
               "nodata.tif", "GTiff", {0.0, 10.0, 1.0, 10, 10, true}, [](double, double) { return NAN; }, GDT_Float32,
               1, 0, "EPSG:4326", -9999.0)
               .string();
  EXPECT_THAT(open_error(o), HasSubstr("no data"));

  o.path = write_raster("band.tif", "GTiff", {0.0, 10.0, 1.0, 10, 10, true}, global_field).string();
  o.band = 2;
  EXPECT_THAT(open_error(o), HasSubstr("band 2 not found"));

  o.band = 1;
  o.max_memory_bytes = 100;
  EXPECT_THAT(open_error(o), HasSubstr("input.max_memory_gb"));
}

// ---- Real data (ferret-datasets) ----

namespace {
fs::path etopo(const char* name) { return fs::path(AQ_ETOPO_DIR) / name; }
}  // namespace

TEST(RealEtopo, Etopo5RangeAndLayout) {
  const auto b = open(etopo("etopo5.cdf"));
  const auto& i = b.info();
  EXPECT_EQ(i.width, 4320);
  EXPECT_EQ(i.height, 2161);
  EXPECT_TRUE(i.global_lon);
  EXPECT_DOUBLE_EQ(i.dlon, 1.0 / 12.0);
  EXPECT_DOUBLE_EQ(i.min_m, -10376.0);
  EXPECT_DOUBLE_EQ(i.max_m, 7833.0);
  EXPECT_LT(b.sample(-150.0, 0.0), -3500.0);  // central Pacific
  EXPECT_GT(b.sample(-150.0, 0.0), -5500.0);
}

TEST(RealEtopo, Etopo20And60HaveOverlapAndOrigin20E) {
  const auto b20 = open(etopo("etopo20.cdf"));
  EXPECT_TRUE(b20.info().duplicate_column);
  EXPECT_NEAR(b20.info().lon_first_found, 20.0 + 1.0 / 6.0, 1e-9);
  EXPECT_EQ(b20.info().ncols, 1080);
  const auto b60 = open(etopo("etopo60.cdf"));
  EXPECT_EQ(b60.info().ncols, 360);
  EXPECT_EQ(b60.info().registration, "pixel");
}

// Deep-ocean points far from relief: the coarser file's bilinear sample differs from ETOPO5 by
// the variation of the field within one coarse cell. Abyssal plains vary by well under 300 m over
// 1° (the tolerance); ETOPO20 is 3× finer, so 150 m.
TEST(RealEtopo, Etopo5_20_60AgreeAtOceanPoints) {
  const auto b5 = open(etopo("etopo5.cdf"));
  const auto b20 = open(etopo("etopo20.cdf"));
  const auto b60 = open(etopo("etopo60.cdf"));
  const std::vector<std::pair<double, double>> pts = {{-150.0, 0.0}, {-140.0, -20.0}, {-30.0, 30.0},  {-25.0, -35.0},
                                                      {80.0, -10.0}, {170.0, 30.0},   {-160.0, 40.0}, {60.0, -40.0}};
  for (const auto& [lon, lat] : pts) {
    const double z5 = b5.sample(lon, lat);
    EXPECT_LT(z5, -3000.0) << lon << "," << lat;
    EXPECT_NEAR(b20.sample(lon, lat), z5, 150.0) << lon << "," << lat;
    EXPECT_NEAR(b60.sample(lon, lat), z5, 300.0) << lon << "," << lat;
  }
  // Coastal point (English Channel): all three see shallow water or coast, within 100 m depth.
  EXPECT_NEAR(b5.sample(-1.0, 50.2), b20.sample(-1.0, 50.2), 100.0);
}

}  // namespace unit_raster_bathymetry_test

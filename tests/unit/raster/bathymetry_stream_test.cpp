// SPDX-License-Identifier: GPL-3.0-or-later
// The streamed raster path (issue 9): banded reads must give the whole path's values bit for bit
// for any band height (1, 7, the file's block height, the default) and thread count, on tiled
// and striped GeoTIFFs (north-up and south-up, int16 with scale/offset/no-data; compressed, and
// raw ones read through GDAL's memory map of the file and through GDAL reads), and on netCDF4
// (deflate) files in the GEBCO (pixel-registered `elevation` int16) and SRTM15+
// (grid-registered `z` with a 360° column) layouts, written here.
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "raster/bathymetry.hpp"
#include "support/synthetic_raster.hpp"

namespace unit_raster_bathymetry_stream_test {

namespace fs = std::filesystem;
using aq::raster::Bathymetry;
using aq::raster::OpenOptions;

namespace {

using aq::test::field;
using aq::test::write_tiff;

fs::path tmpdir() { return aq::test::synthetic_dir(); }

Bathymetry open(const fs::path& p, bool streamed, std::int64_t band_rows = 0, const std::string& var = "",
                bool map_file = true) {
  OpenOptions o;
  o.path = p.string();
  o.variable = var;
  o.allow_streaming = streamed;
  o.streaming = streamed ? OpenOptions::Streaming::kAlways : OpenOptions::Streaming::kNever;
  o.band_rows = band_rows;
  o.map_file = map_file;
  return Bathymetry::open(o);
}

// Every row of a lattice (not aligned with the raster) sampled through sample_rows.
std::vector<float> lattice_rows(const Bathymetry& b, double step) {
  const auto nx = static_cast<std::int64_t>(std::lround(360.0 / step));
  const auto nv = static_cast<std::int64_t>(std::lround(180.0 / step)) + 1;
  std::vector<double> lons(static_cast<std::size_t>(nx)), lats(static_cast<std::size_t>(nv));
  for (std::int64_t i = 0; i < nx; ++i) lons[static_cast<std::size_t>(i)] = -180.0 + static_cast<double>(i) * step;
  for (std::int64_t j = 0; j < nv; ++j) lats[static_cast<std::size_t>(j)] = -90.0 + static_cast<double>(j) * step;
  const auto cols = b.prepare_columns(lons.data(), nx);
  std::vector<float> out(static_cast<std::size_t>(nx * nv), -1.0f);
  std::vector<int> seen(static_cast<std::size_t>(nv), 0);
  b.sample_rows(cols, lats.data(), nv, [&](std::int64_t k, const float* v) {
    std::memcpy(out.data() + k * nx, v, static_cast<std::size_t>(nx) * sizeof(float));
    ++seen[static_cast<std::size_t>(k)];
  });
  for (std::int64_t j = 0; j < nv; ++j) EXPECT_EQ(seen[static_cast<std::size_t>(j)], 1) << "row " << j;
  return out;
}

// Random points (and the poles, the seam, grid lines) through sample_points.
std::vector<double> points(const Bathymetry& b) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> lon(-200.0, 200.0), lat(-90.0, 90.0);
  std::vector<double> x{-180.0, 180.0, 0.0, 179.999, -90.0}, y{-90.0, 90.0, 0.0, 45.0, 89.99};
  for (int k = 0; k < 10000; ++k) {
    x.push_back(lon(rng));
    y.push_back(lat(rng));
  }
  std::vector<double> out(x.size());
  b.sample_points(x.data(), y.data(), static_cast<std::int64_t>(x.size()), out.data());
  return out;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same_stats(const Bathymetry& a, const Bathymetry& b) {
  EXPECT_EQ(a.info().valid_count, b.info().valid_count);
  EXPECT_EQ(a.info().min_m, b.info().min_m);
  EXPECT_EQ(a.info().max_m, b.info().max_m);
  EXPECT_EQ(a.info().mean_m, b.info().mean_m);
}

struct FileCase {
  const char* name;
  bool north_up, tiled;
  bool compressed = true;  // raw striped files are mapped (RasterInfo::mapped)
};

class StreamedTiff : public ::testing::TestWithParam<FileCase> {};

TEST_P(StreamedTiff, BandedEqualsWholeBitForBit) {
  const FileCase fc = GetParam();
  const fs::path p = write_tiff(tmpdir() / (std::string(fc.name) + ".tif"), 0.5, fc.north_up, fc.tiled, fc.compressed);
  const Bathymetry whole = open(p, false);
  ASSERT_FALSE(whole.info().streamed);
  const auto rows_w = lattice_rows(whole, 0.4);
  const auto pts_w = points(whole);
  // Band heights 1, 7, the block height (16 rows tiled, 1 striped) and the default; through the
  // file map when GDAL has one (raw striped files), and through GDAL reads.
  for (const std::int64_t band : {std::int64_t{1}, std::int64_t{7}, std::int64_t{16}, std::int64_t{0}}) {
    for (const int threads : {1, 2}) {
      for (const bool map_file : {true, false}) {
        aq::test::set_threads(threads);
        const Bathymetry s = open(p, true, band, "", map_file);
        const std::string what = fmt::format("band {}, threads {}, map_file {}", band, threads, map_file);
        ASSERT_TRUE(s.info().streamed);
        EXPECT_EQ(s.info().mapped, map_file && !fc.tiled && !fc.compressed) << what;
        EXPECT_EQ(s.info().block_rows, fc.tiled ? 16 : 1);
        EXPECT_TRUE(same_bits(lattice_rows(s, 0.4), rows_w)) << what;
        expect_same_stats(s, whole);
        EXPECT_TRUE(same_bits(points(s), pts_w)) << what;
        EXPECT_EQ(s.info().passes, 2);
        // Single values and blocks agree too (pictures, contours).
        EXPECT_EQ(s.sample(12.34, -56.78), whole.sample(12.34, -56.78));
        std::vector<float> va(40 * 9), vb(va.size());
        s.values(700, 40, 300, 9, va.data());  // across the seam
        whole.values(700, 40, 300, 9, vb.data());
        EXPECT_TRUE(same_bits(va, vb)) << what;
      }
    }
  }
  aq::test::set_threads(2);
}

INSTANTIATE_TEST_SUITE_P(Layouts, StreamedTiff,
                         ::testing::Values(FileCase{"tiled_northup", true, true},
                                           FileCase{"striped_northup", true, false},
                                           FileCase{"tiled_southup", false, true},
                                           FileCase{"raw_striped_northup", true, false, false},
                                           FileCase{"raw_striped_southup", false, false, false},
                                           FileCase{"raw_tiled_northup", true, true, false}),
                         [](const auto& i) { return std::string(i.param.name); });

TEST(StreamedRaster, AutoRuleAndNoData) {
  const fs::path p = write_tiff(tmpdir() / "auto.tif", 1.0, true, true);
  OpenOptions o;
  o.path = p.string();
  o.allow_streaming = true;  // small raster: held whole under kAuto
  EXPECT_FALSE(Bathymetry::open(o).info().streamed);
  o.max_memory_bytes = 1000;  // ...unless it would not fit
  EXPECT_TRUE(Bathymetry::open(o).info().streamed);
  EXPECT_TRUE(aq::raster::plan_raster(o).streamed);
  o.allow_streaming = false;
  EXPECT_FALSE(aq::raster::plan_raster(o).streamed);
  const Bathymetry s = open(p, true, 5);
  EXPECT_TRUE(std::isnan(s.sample(11.5, -3.5)));  // the no-data patch
  EXPECT_EQ(s.sample(0.5, 0.5), field(0.5, 0.5));
}

// netCDF4 with deflate, written with the netCDF library: dims (lat, lon), lat ascending.
void check(int status) { ASSERT_EQ(status, NC_NOERR) << nc_strerror(status); }

fs::path write_nc(const std::string& name, const char* var, const std::vector<double>& lon,
                  const std::vector<double>& lat, const std::vector<std::int16_t>& z) {
  const fs::path p = tmpdir() / name;
  int nc = 0, dlat = 0, dlon = 0, vlat = 0, vlon = 0, vz = 0;
  check(nc_create(p.c_str(), NC_NETCDF4 | NC_CLOBBER, &nc));
  check(nc_def_dim(nc, "lat", lat.size(), &dlat));
  check(nc_def_dim(nc, "lon", lon.size(), &dlon));
  check(nc_def_var(nc, "lat", NC_DOUBLE, 1, &dlat, &vlat));
  check(nc_def_var(nc, "lon", NC_DOUBLE, 1, &dlon, &vlon));
  check(nc_put_att_text(nc, vlat, "units", 13, "degrees_north"));
  check(nc_put_att_text(nc, vlon, "units", 12, "degrees_east"));
  const int dims[2] = {dlat, dlon};
  check(nc_def_var(nc, var, NC_SHORT, 2, dims, &vz));
  const std::size_t chunks[2] = {8, lon.size()};
  check(nc_def_var_chunking(nc, vz, NC_CHUNKED, chunks));
  check(nc_def_var_deflate(nc, vz, 1, 1, 4));
  check(nc_put_att_text(nc, vz, "units", 1, "m"));
  check(nc_enddef(nc));
  check(nc_put_var_double(nc, vlat, lat.data()));
  check(nc_put_var_double(nc, vlon, lon.data()));
  check(nc_put_var_short(nc, vz, z.data()));
  check(nc_close(nc));
  return p;
}

std::int16_t ivalue(double lon, double lat) { return static_cast<std::int16_t>(field(lon, lat) / 10.0); }

TEST(StreamedRaster, GebcoLayoutNetcdf4) {
  // GEBCO_2024: pixel-registered, lat ascending from -90 + step/2, lon from -180 + step/2.
  const double step = 0.5;
  std::vector<double> lon(720), lat(360);
  for (std::size_t i = 0; i < lon.size(); ++i) lon[i] = -180.0 + (static_cast<double>(i) + 0.5) * step;
  for (std::size_t j = 0; j < lat.size(); ++j) lat[j] = -90.0 + (static_cast<double>(j) + 0.5) * step;
  std::vector<std::int16_t> z(lon.size() * lat.size());
  for (std::size_t j = 0; j < lat.size(); ++j)
    for (std::size_t i = 0; i < lon.size(); ++i) z[j * lon.size() + i] = ivalue(lon[i], lat[j]);
  const fs::path p = write_nc("gebco_layout.nc", "elevation", lon, lat, z);
  const Bathymetry whole = open(p, false, 0, "elevation");
  const Bathymetry s = open(p, true, 7, "elevation");
  for (const Bathymetry* b : {&whole, &s}) {
    const auto& i = b->info();
    EXPECT_TRUE(i.global_lon);
    EXPECT_FALSE(i.duplicate_column);
    EXPECT_EQ(i.ncols, 720);
    EXPECT_EQ(i.nrows, 360);
    EXPECT_EQ(i.registration, "pixel");
    EXPECT_DOUBLE_EQ(i.lon_first, -179.75);
    EXPECT_DOUBLE_EQ(i.lat_first, -89.75);
    EXPECT_EQ(i.data_type, "Int16");
    // Sample points take the stored values exactly.
    for (const auto& [c, r] : {std::pair{0, 0}, std::pair{719, 359}, std::pair{300, 123}, std::pair{360, 180}})
      EXPECT_EQ(b->sample(lon[c], lat[r]), static_cast<double>(z[static_cast<std::size_t>(r) * 720 + c]))
          << c << " " << r;
  }
  EXPECT_TRUE(same_bits(lattice_rows(s, 0.3), lattice_rows(whole, 0.3)));
  EXPECT_TRUE(same_bits(points(s), points(whole)));
  expect_same_stats(s, whole);
}

TEST(StreamedRaster, Srtm15LayoutNetcdf4) {
  // SRTM15+: grid-registered, lon -180..180 inclusive (a repeated 360° column), lat -90..90, `z`.
  const double step = 1.0;
  std::vector<double> lon(361), lat(181);
  for (std::size_t i = 0; i < lon.size(); ++i) lon[i] = -180.0 + static_cast<double>(i) * step;
  for (std::size_t j = 0; j < lat.size(); ++j) lat[j] = -90.0 + static_cast<double>(j) * step;
  std::vector<std::int16_t> z(lon.size() * lat.size());
  for (std::size_t j = 0; j < lat.size(); ++j)
    for (std::size_t i = 0; i < lon.size(); ++i)
      z[j * lon.size() + i] = ivalue(i == 360 ? lon[0] : lon[i], lat[j]);  // the 360° column repeats the first
  const fs::path p = write_nc("srtm15_layout.nc", "z", lon, lat, z);
  const Bathymetry whole = open(p, false, 0, "z");
  const Bathymetry s = open(p, true, 1, "z");
  for (const Bathymetry* b : {&whole, &s}) {
    const auto& i = b->info();
    EXPECT_TRUE(i.global_lon);
    EXPECT_TRUE(i.duplicate_column);
    EXPECT_EQ(i.ncols, 360);
    EXPECT_EQ(i.nrows, 181);
    EXPECT_EQ(i.registration, "grid");
    EXPECT_DOUBLE_EQ(i.dlon, 1.0);
    EXPECT_EQ(b->sample(10.0, 20.0), static_cast<double>(z[110 * 361 + 190]));
    EXPECT_EQ(b->sample(180.0, -90.0), static_cast<double>(z[0]));  // 180° is -180°
    EXPECT_EQ(b->sample(-180.0, 90.0), static_cast<double>(z[180 * 361]));
    EXPECT_EQ(b->sample(179.5, 0.0), 0.5 * (z[90 * 361 + 359] + z[90 * 361 + 0]));  // across the seam
  }
  EXPECT_TRUE(same_bits(lattice_rows(s, 0.7), lattice_rows(whole, 0.7)));
  EXPECT_TRUE(same_bits(points(s), points(whole)));
  expect_same_stats(s, whole);
}

TEST(StreamedRaster, LatitudeWindowHoldsOnlyItsRows) {
  const fs::path p = write_tiff(tmpdir() / "window.tif", 0.25, true, true);
  const Bathymetry whole = open(p, false);
  OpenOptions o;
  o.path = p.string();
  o.lat_min = 40.0;
  o.lat_max = 45.0;
  const Bathymetry w = Bathymetry::open(o);
  EXPECT_LT(w.info().memory_bytes, whole.info().memory_bytes / 25);
  for (const double lat : {40.0, 41.3, 44.99, 45.0})
    for (const double lon : {-179.9, 0.1, 33.3})
      EXPECT_EQ(w.sample(lon, lat), whole.sample(lon, lat)) << lon << " " << lat;
  EXPECT_TRUE(std::isnan(w.sample(0.0, 30.0)));  // outside the window
}

// A lon/lat window across the seam (170°E..170°W): two pieces read, held as one; samples inside
// equal the whole raster's bit for bit (also the lattice-row path), NaN outside; a window inside
// one piece; both file orientations.
TEST(StreamedRaster, LonLatWindowAcrossTheSeamEqualsTheWholeRasterInside) {
  for (const bool north_up : {true, false}) {
    const fs::path p = write_tiff(tmpdir() / (north_up ? "lonwin_n.tif" : "lonwin_s.tif"), 0.25, north_up, true);
    const Bathymetry whole = open(p, false);
    for (const auto& [lo, hi] : {std::pair{170.0, 190.0}, std::pair{-190.0, -170.0}, std::pair{10.0, 30.0}}) {
      OpenOptions o;
      o.path = p.string();
      o.lat_min = -10.0;
      o.lat_max = 10.0;
      o.lon_min = lo;
      o.lon_max = hi;
      const Bathymetry w = Bathymetry::open(o);
      const auto& i = w.info();
      EXPECT_GE(i.held_cols, 80);
      EXPECT_LE(i.held_cols, 88);
      EXPECT_EQ(i.memory_bytes, i.held_cols * i.held_rows * 4);
      EXPECT_LT(i.memory_bytes, whole.info().memory_bytes / 100);
      std::vector<double> lons;
      for (double x = lo; x <= hi; x += 0.37) lons.push_back(x);
      int finite = 0;
      for (const double lat : {-10.0, -3.3, 0.0, 7.77, 10.0})
        for (const double lon : lons) {
          const double x = w.sample(lon, lat), y = whole.sample(lon, lat);
          finite += std::isfinite(x) ? 1 : 0;
          EXPECT_TRUE(std::memcmp(&x, &y, sizeof x) == 0 || (std::isnan(x) && std::isnan(y))) << lon << " " << lat;
        }
      EXPECT_GT(finite, 100);
      // The lattice-row path (prepare_columns / sample_row) too.
      const auto cw = w.prepare_columns(lons.data(), static_cast<std::int64_t>(lons.size()));
      const auto cf = whole.prepare_columns(lons.data(), static_cast<std::int64_t>(lons.size()));
      std::vector<float> a(lons.size()), b(lons.size());
      w.sample_row(cw, 1.1, a.data());
      whole.sample_row(cf, 1.1, b.data());
      EXPECT_TRUE(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
      EXPECT_TRUE(std::isnan(w.sample(lo - 5.0, 0.0)));
      EXPECT_TRUE(std::isnan(w.sample(hi + 5.0, 0.0)));
      EXPECT_TRUE(std::isnan(w.sample(0.5 * (lo + hi), 20.0)));
      const auto c = static_cast<std::int64_t>(std::floor((lo - i.lon_first) / i.dlon)) + 1;
      const float vw = w.value(c, i.held_row_first + 1), vf = whole.value(c, i.held_row_first + 1);
      EXPECT_TRUE(vw == vf || (std::isnan(vw) && std::isnan(vf)));
    }
  }
}

// sample_rows computes each raster row's interpolation along the row once and reuses it, two
// columns at a time where the lattice's columns step through the raster's one by one: every
// value must still be the float of sample() at that vertex, for lattices as fine as the raster
// (0.5°, the seam column the only irregular one), finer, coarser and unaligned ones.
// A regional raster of `w` columns from lon0 (0.5° pixels, 60°S..60°N): a global lattice's
// columns outside it are NaN, and a narrow one (w < 16) is only short runs of columns.
fs::path write_regional(const fs::path& p, double lon0, int w) {
  GDALAllRegister();
  const double step = 0.5;
  const int h = 240;
  GDALDataset* mem = GetGDALDriverManager()->GetDriverByName("MEM")->Create("", w, h, 1, GDT_Float32, nullptr);
  double gt[6] = {lon0, step, 0.0, 60.0, 0.0, -step};
  mem->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  mem->SetSpatialRef(&srs);
  std::vector<float> v(static_cast<std::size_t>(w) * h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      v[static_cast<std::size_t>(r) * w + c] =
          static_cast<float>(field(lon0 + (c + 0.5) * step, 60.0 - (r + 0.5) * step));
  EXPECT_EQ(mem->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0, nullptr), CE_None);
  GDALClose(
      GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(p.c_str(), mem, FALSE, nullptr, nullptr, nullptr));
  GDALClose(mem);
  return p;
}

TEST(SampledRows, EqualTheSampleOfEveryVertex) {
  const fs::path global = write_tiff(tmpdir() / "rows_vs_sample.tif", 0.5, true, false, false);
  const fs::path wide = write_regional(tmpdir() / "rows_vs_sample_wide.tif", -30.25, 141);
  const fs::path narrow = write_regional(tmpdir() / "rows_vs_sample_narrow.tif", 10.0, 7);
  for (const auto& [p, streamed] :
       {std::pair{global, false}, std::pair{global, true}, std::pair{wide, false}, std::pair{narrow, false}}) {
    const Bathymetry b = open(p, streamed);
    for (const double step : {0.5, 0.25, 1.0, 0.4}) {
      const auto rows = lattice_rows(b, step);
      const auto nx = static_cast<std::int64_t>(std::lround(360.0 / step));
      const auto nv = static_cast<std::int64_t>(std::lround(180.0 / step)) + 1;
      std::int64_t differ = 0;
      for (std::int64_t j = 0; j < nv; ++j)
        for (std::int64_t i = 0; i < nx; ++i) {
          const float want = static_cast<float>(
              b.sample(-180.0 + static_cast<double>(i) * step, -90.0 + static_cast<double>(j) * step));
          const float got = rows[static_cast<std::size_t>(j * nx + i)];
          differ += std::memcmp(&want, &got, sizeof want) != 0 ? 1 : 0;
        }
      EXPECT_EQ(differ, 0) << p.filename() << ", step " << step << ", streamed " << streamed;
    }
  }
}

// Plain integers (int16 without scale or offset: GEBCO, ETOPO) take a shortcut through
// normalisation and row statistics (their sum is exact as an integer); the same values as
// Float32 take the general rule. Both must give the same values and figures bit for bit, with
// no-data cells and values beyond input.max_abs_elevation_m among them.
TEST(StreamedRaster, PlainIntegersGiveTheFiguresOfTheGeneralRule) {
  GDALAllRegister();
  const double step = 0.5;
  const int w = 720, h = 360;
  std::vector<float> v(static_cast<std::size_t>(w) * h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double lon = -180.0 + (c + 0.5) * step, lat = 90.0 - (r + 0.5) * step;
      float x = static_cast<float>(std::lround(field(lon, lat) + 7.0 * std::sin(3.0 * lat)));
      if (lon > 20.0 && lon < 23.0 && lat > 5.0 && lat < 8.0) x = -32768.0f;     // no-data
      if (lon > -50.0 && lon < -48.0 && lat > 30.0 && lat < 31.0) x = 15000.0f;  // implausible
      v[static_cast<std::size_t>(r) * w + c] = x;
    }
  const auto write = [&](const char* name, GDALDataType type) {
    GDALDataset* mem = GetGDALDriverManager()->GetDriverByName("MEM")->Create("", w, h, 1, type, nullptr);
    double gt[6] = {-180.0, step, 0.0, 90.0, 0.0, -step};
    mem->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.importFromEPSG(4326);
    mem->SetSpatialRef(&srs);
    GDALRasterBand* b = mem->GetRasterBand(1);
    b->SetNoDataValue(-32768.0);
    EXPECT_EQ(b->RasterIO(GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0, nullptr), CE_None);
    const fs::path p = tmpdir() / name;
    char** opts = CSLSetNameValue(nullptr, "BLOCKYSIZE", "1");
    GDALClose(
        GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(p.c_str(), mem, FALSE, opts, nullptr, nullptr));
    CSLDestroy(opts);
    GDALClose(mem);
    return p;
  };
  const fs::path pi = write("plain_int16.tif", GDT_Int16), pf = write("plain_float32.tif", GDT_Float32);
  for (const bool streamed : {false, true}) {
    for (const bool map_file : {true, false}) {
      const Bathymetry bi = open(pi, streamed, 7, "", map_file), bf = open(pf, streamed, 7, "", map_file);
      EXPECT_EQ(bi.info().data_type, "Int16");
      EXPECT_EQ(bf.info().data_type, "Float32");
      EXPECT_TRUE(same_bits(lattice_rows(bi, 0.4), lattice_rows(bf, 0.4))) << streamed << map_file;
      EXPECT_TRUE(same_bits(points(bi), points(bf))) << streamed << map_file;
      expect_same_stats(bi, bf);
      EXPECT_GT(bi.info().implausible_count, 0);
      EXPECT_EQ(bi.info().implausible_count, bf.info().implausible_count);
      EXPECT_LT(bi.info().valid_count, std::int64_t{w} * h);
    }
  }
}

// A raster 2^19 columns wide (Int16, raw, striped: mapped): through the file map a band of a
// pass is 4 rows (8 MB of float32, well inside a processor's cache), below the 32-row bands of
// the memory estimate the disk is asked for; each band's first row is carried over from the band
// before. The same rows, points and figures as the raster held whole, bit for bit.
TEST(StreamedRaster, WideRasterInCacheSizedBandsEqualsWhole) {
  GDALAllRegister();
  const int w = 1 << 19, h = 40;
  const double step = 360.0 / w, top = 10.0;
  std::vector<std::int16_t> v(static_cast<std::size_t>(w) * h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double lon = -180.0 + (c + 0.5) * step;
      auto x = static_cast<std::int16_t>(std::lround(3000.0 * std::sin(lon * 0.05)) + (r * 37 + c * 11) % 200 - 100);
      if (c % 997 == 5) x = -32768;  // no-data
      v[static_cast<std::size_t>(r) * w + c] = x;
    }
  GDALDataset* mem = GetGDALDriverManager()->GetDriverByName("MEM")->Create("", w, h, 1, GDT_Int16, nullptr);
  double gt[6] = {-180.0, step, 0.0, top, 0.0, -step};
  mem->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  mem->SetSpatialRef(&srs);
  mem->GetRasterBand(1)->SetNoDataValue(-32768.0);
  ASSERT_EQ(mem->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Int16, 0, 0, nullptr), CE_None);
  const fs::path p = tmpdir() / "wide_int16.tif";
  char** opts = CSLSetNameValue(nullptr, "BLOCKYSIZE", "1");
  GDALClose(
      GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(p.c_str(), mem, FALSE, opts, nullptr, nullptr));
  CSLDestroy(opts);
  GDALClose(mem);
  v = {};

  // Lattice rows across the raster's rows (and beyond its southern edge: NaN), every 4th column.
  const double bottom = top - h * step;
  std::vector<double> lons(static_cast<std::size_t>(w / 4)), lats(30);
  for (std::size_t i = 0; i < lons.size(); ++i) lons[i] = -180.0 + (static_cast<double>(i) * 4.0 + 0.37) * step;
  for (std::size_t j = 0; j < lats.size(); ++j) lats[j] = bottom - 2.0 * step + static_cast<double>(j) * 1.43 * step;
  const auto rows = [&](const Bathymetry& b) {
    const auto cols = b.prepare_columns(lons.data(), static_cast<std::int64_t>(lons.size()));
    std::vector<float> out(lons.size() * lats.size(), -1.0f);
    b.sample_rows(cols, lats.data(), static_cast<std::int64_t>(lats.size()), [&](std::int64_t k, const float* x) {
      std::memcpy(out.data() + k * static_cast<std::int64_t>(lons.size()), x, lons.size() * sizeof(float));
    });
    return out;
  };
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> lon(-180.0, 180.0), lat(bottom, top);
  std::vector<double> px(20000), py(px.size());
  for (std::size_t k = 0; k < px.size(); ++k) {
    px[k] = lon(rng);
    py[k] = lat(rng);
  }
  const auto pts = [&](const Bathymetry& b) {
    std::vector<double> out(px.size());
    b.sample_points(px.data(), py.data(), static_cast<std::int64_t>(px.size()), out.data());
    return out;
  };
  const Bathymetry whole = open(p, false);
  const auto rows_w = rows(whole);
  const auto pts_w = pts(whole);
  for (const int threads : {1, 2}) {
    aq::test::set_threads(threads);
    const Bathymetry s = open(p, true);
    ASSERT_TRUE(s.info().streamed);
    ASSERT_TRUE(s.info().mapped);
    EXPECT_EQ(s.info().band_rows, 32);  // 64 MB of float32 per band of the estimate
    EXPECT_TRUE(same_bits(rows(s), rows_w)) << threads;
    expect_same_stats(s, whole);
    EXPECT_TRUE(same_bits(pts(s), pts_w)) << threads;
  }
  aq::test::set_threads(2);
}

}  // namespace

}  // namespace unit_raster_bathymetry_stream_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Test helpers of the streamed-input tests: small synthetic global rasters written through GDAL,
// and the OpenMP thread count.
#pragma once

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace aq::test {

namespace fs = std::filesystem;

/// OpenMP threads for what follows (1 vs 2 threads must give the same bits).
inline void set_threads(int n) {
#ifdef _OPENMP
  omp_set_num_threads(n);
#else
  (void)n;
#endif
}

/// A per-process scratch folder for the rasters.
inline fs::path synthetic_dir() {
  const fs::path d = fs::temp_directory_path() / ("aq_synthetic_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// A rough global field with land, sea, exact zeros and no-data cells (int16 steps of 0.5 m).
inline double field(double lon, double lat) {
  const double v = -2000.0 + 2500.0 * std::sin(0.11 * lon) * std::cos(0.17 * lat) + 900.0 * std::sin(0.9 * lon + lat);
  return std::round(v / 50.0) * 50.0;
}

// A global int16 GeoTIFF at `step` degrees (pixel-registered, origin -180), scale 0.5, offset
// -100, no-data -32768 in a small patch; tiled with 16-row blocks or striped (1 row per strip);
// deflate-compressed, or raw (what GDAL can map into memory when striped).
inline fs::path write_tiff(const fs::path& p, double step, bool north_up, bool tiled, bool compressed = true) {
  GDALAllRegister();
  const int w = static_cast<int>(std::lround(360.0 / step)), h = static_cast<int>(std::lround(180.0 / step));
  GDALDataset* mem = GetGDALDriverManager()->GetDriverByName("MEM")->Create("", w, h, 1, GDT_Int16, nullptr);
  const double dy = north_up ? -step : step;
  double gt[6] = {-180.0, step, 0.0, north_up ? 90.0 : -90.0, 0.0, dy};
  mem->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  mem->SetSpatialRef(&srs);
  std::vector<std::int16_t> buf(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double lon = -180.0 + (c + 0.5) * step, lat = (north_up ? 90.0 : -90.0) + (r + 0.5) * dy;
      const bool hole = lon > 10.0 && lon < 13.0 && lat > -5.0 && lat < -2.0;
      buf[static_cast<std::size_t>(r) * w + c] =
          hole ? std::int16_t{-32768} : static_cast<std::int16_t>(std::lround((field(lon, lat) + 100.0) / 0.5));
    }
  GDALRasterBand* b = mem->GetRasterBand(1);
  b->SetScale(0.5);
  b->SetOffset(-100.0);
  b->SetNoDataValue(-32768.0);
  EXPECT_EQ(b->RasterIO(GF_Write, 0, 0, w, h, buf.data(), w, h, GDT_Int16, 0, 0, nullptr), CE_None);
  char** opts = nullptr;
  if (compressed) opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
  if (tiled) {
    opts = CSLSetNameValue(opts, "TILED", "YES");
    opts = CSLSetNameValue(opts, "BLOCKXSIZE", "256");
    opts = CSLSetNameValue(opts, "BLOCKYSIZE", "16");
  } else {
    opts = CSLSetNameValue(opts, "BLOCKYSIZE", "1");
  }
  GDALDataset* out =
      GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(p.c_str(), mem, FALSE, opts, nullptr, nullptr);
  CSLDestroy(opts);
  GDALClose(out);
  GDALClose(mem);
  return p;
}

}  // namespace aq::test

// SPDX-License-Identifier: GPL-3.0-or-later
// Streamed input (issue 9) end to end: the pixel classes of a streamed raster equal the whole
// raster's bit for bit on ETOPO5 and on a synthetic fine raster (band heights 1, 7, the block
// height; 1 and 2 threads), and a VRT of 4 tiles cut from ETOPO5 gives the mesh of ETOPO5 itself
// (held whole and streamed).
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/global_run.hpp"
#include "config/load.hpp"
#include "mask/pixel_classes.hpp"
#include "support/synthetic_raster.hpp"

namespace aq::integration_streamed_input_test {
namespace {

namespace fs = std::filesystem;
const std::string kEtopo5 = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";

raster::Bathymetry open(const std::string& path, bool streamed, std::int64_t band_rows = 0) {
  raster::OpenOptions o;
  o.path = path;
  o.allow_streaming = streamed;
  o.streaming = streamed ? raster::OpenOptions::Streaming::kAlways : raster::OpenOptions::Streaming::kNever;
  o.band_rows = band_rows;
  return raster::Bathymetry::open(o);
}

void expect_same_classes(const std::string& path, const Lattice& lat, std::int64_t block_rows) {
  mask::ClassifyOptions co;
  co.min_depth_m = 10.0;
  const mask::PixelClasses whole = mask::classify_pixels(open(path, false), lat, PoleRotation(), co);
  EXPECT_GT(whole.wet_count, 0);
  EXPECT_GT(whole.coastal_count, 0);
  for (const std::int64_t band : {std::int64_t{1}, std::int64_t{7}, block_rows}) {
    for (const int threads : {1, 2}) {
      test::set_threads(threads);
      const raster::Bathymetry s = open(path, true, band);
      ASSERT_TRUE(s.info().streamed);
      const mask::PixelClasses pc = mask::classify_pixels(s, lat, PoleRotation(), co);
      EXPECT_TRUE(pc.wet_vertices == whole.wet_vertices) << "band " << band << ", threads " << threads;
      EXPECT_TRUE(pc.wet == whole.wet) << "band " << band << ", threads " << threads;
      EXPECT_TRUE(pc.coastal == whole.coastal) << "band " << band << ", threads " << threads;
      EXPECT_EQ(pc.wet_count, whole.wet_count);
      EXPECT_EQ(pc.coastal_count, whole.coastal_count);
    }
  }
  test::set_threads(2);
}

TEST(StreamedInput, Etopo5ClassesEqualWholeRaster) {
  if (!fs::exists(kEtopo5)) GTEST_SKIP() << kEtopo5 << " missing";
  // Δ0 = 1°, L = 4: 5760×2880 pixels of 3.75' (finer than the raster, not aligned with it).
  expect_same_classes(kEtopo5, Lattice::make(1.0, 4, -180.0), open(kEtopo5, true).info().block_rows);
}

TEST(StreamedInput, FineSyntheticClassesEqualWholeRaster) {
  const fs::path p = test::write_tiff(test::synthetic_dir() / "fine.tif", 0.1, true, true);  // 3600×1800, 16-row tiles
  expect_same_classes(p.string(), Lattice::make(0.5, 3, -180.0), 16);                        // pixels of 3.75'
}

// ETOPO5 cut into 4 GeoTIFF tiles (2 × 2) and joined by a VRT, as users join ETOPO 2022 tiles.
fs::path four_tile_vrt() {
  GDALAllRegister();
  const fs::path dir = test::synthetic_dir();
  GDALDatasetH src = GDALOpen(kEtopo5.c_str(), GA_ReadOnly);
  EXPECT_NE(src, nullptr);
  const int w = GDALGetRasterXSize(src), h = GDALGetRasterYSize(src);
  std::vector<std::string> tiles;
  for (int ty = 0; ty < 2; ++ty)
    for (int tx = 0; tx < 2; ++tx) {
      const int x0 = tx * (w / 2), y0 = ty * (h / 2);
      const int xs = tx == 0 ? w / 2 : w - w / 2, ys = ty == 0 ? h / 2 : h - h / 2;
      const std::string name = (dir / ("tile_" + std::to_string(ty) + std::to_string(tx) + ".tif")).string();
      const std::vector<std::string> args{"-q",
                                          "-srcwin",
                                          std::to_string(x0),
                                          std::to_string(y0),
                                          std::to_string(xs),
                                          std::to_string(ys),
                                          "-co",
                                          "COMPRESS=DEFLATE",
                                          "-co",
                                          "TILED=YES"};
      std::vector<char*> argv;
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      GDALTranslateOptions* opt = GDALTranslateOptionsNew(argv.data(), nullptr);
      GDALDatasetH t = GDALTranslate(name.c_str(), src, opt, nullptr);
      GDALTranslateOptionsFree(opt);
      EXPECT_NE(t, nullptr);
      GDALClose(t);
      tiles.push_back(name);
    }
  GDALClose(src);
  std::vector<const char*> names;
  for (const auto& t : tiles) names.push_back(t.c_str());
  const fs::path vrt = dir / "etopo5_tiles.vrt";
  int err = 0;
  GDALDatasetH v = GDALBuildVRT(vrt.c_str(), static_cast<int>(names.size()), nullptr, names.data(), nullptr, &err);
  EXPECT_NE(v, nullptr);
  GDALClose(v);
  return vrt;
}

mesh::Mesh mesh_of(const std::string& path, const char* streaming) {
  ::setenv("AQ_RASTER_STREAMING", streaming, 1);
  ::setenv("AQ_RASTER_BAND_ROWS", "7", 1);
  auto c = config::load_global(std::nullopt, {"input.path=\"" + path + "\"", "mask.min_depth_m=10"}).options;
  const app::GlobalSetup setup = app::prepare_global_run(c);
  app::GlobalRun run = app::run_global_pipeline(c, setup, Logger::null(), nullptr, false);
  ::unsetenv("AQ_RASTER_STREAMING");
  ::unsetenv("AQ_RASTER_BAND_ROWS");
  EXPECT_EQ(run.bathy->info().streamed, std::string(streaming) == "always");
  return std::move(run.mesh);
}

TEST(StreamedInput, VrtOfFourTilesGivesTheSameMesh) {
  if (!fs::exists(kEtopo5)) GTEST_SKIP() << kEtopo5 << " missing";
  const fs::path vrt = four_tile_vrt();
  const mesh::Mesh ref = mesh_of(kEtopo5, "never");
  ASSERT_GT(ref.triangle_count(), 50000);
  for (const char* mode : {"never", "always"}) {
    const mesh::Mesh m = mesh_of(vrt.string(), mode);
    EXPECT_EQ(m.node_count(), ref.node_count()) << mode;
    EXPECT_EQ(m.triangles, ref.triangles) << mode;
    EXPECT_EQ(m.lon_deg, ref.lon_deg) << mode;
    EXPECT_EQ(m.lat_deg, ref.lat_deg) << mode;
    // Depths bit for bit (NaN-free: every node is wet or on the coast).
    EXPECT_EQ(m.depth_m, ref.depth_m) << mode;
  }
}

}  // namespace
}  // namespace aq::integration_streamed_input_test

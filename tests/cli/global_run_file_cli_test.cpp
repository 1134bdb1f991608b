// SPDX-License-Identifier: GPL-3.0-or-later
// The global run as a file (issue 9): `aquatoria mesh` writes <name>.tif (Ω_L, pixel classes,
// quadtree levels; a deflate-compressed, tiled, EPSG:4326 GeoTIFF that GDAL opens), and
// `aquatoria blocks` / `aquatoria regional` reuse it instead of the global fill when its inputs
// match (same outputs, a log line says so) and run the fill again, saying why, when they differ.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "raster/byte_geotiff.hpp"
#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_global_run_file_cli_test {

using aq::test::run_aquatoria;
using aq::test::slurp;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

namespace {

// The seed's reference lattice (Δ0 = 4°, L = 3: 720 × 360 pixels) on ETOPO60.
std::string sets(const fs::path& out) {
  return std::string(" --set input.path=") + AQ_ETOPO_DIR +
         "/etopo60.cdf --set quadtree.step_deg=4 --set quadtree.levels=3 --set mask.passages=false "
         "--set output.name=g -o " +
         out.string();
}

}  // namespace

TEST(GlobalRunFileCli, MeshWritesAGeoTiffThatGdalOpens) {
  aq::testing::TempDir dir;
  const auto r = run_aquatoria("mesh" + sets(dir.path()) + " --set 'output.formats=[\"tif\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path tif = dir / "g.tif";
  ASSERT_TRUE(fs::exists(tif));
  EXPECT_EQ(fs::directory_iterator(dir.path()) == fs::directory_iterator(), false);
  EXPECT_FALSE(fs::exists(dir / "g.tif.aux.xml"));

  const auto info = aq::test::run_command("gdalinfo -json " + tif.string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["size"][0].get<int>(), 720);
  EXPECT_EQ(j["size"][1].get<int>(), 360);
  EXPECT_THAT(j["coordinateSystem"]["wkt"].get<std::string>(), HasSubstr("\"EPSG\",4326"));
  EXPECT_EQ(j["geoTransform"][0].get<double>(), -180.0);
  EXPECT_EQ(j["geoTransform"][1].get<double>(), 0.5);
  EXPECT_EQ(j["geoTransform"][3].get<double>(), 90.0);
  EXPECT_EQ(j["metadata"]["IMAGE_STRUCTURE"]["COMPRESSION"].get<std::string>(), "DEFLATE");
  EXPECT_EQ(j["bands"].size(), 2u);
  EXPECT_EQ(j["bands"][0]["block"][0].get<int>(), 512);
  EXPECT_EQ(j["bands"][0]["type"].get<std::string>(), "Byte");
  EXPECT_EQ(j["metadata"][""]["AQ_FRAME"].get<std::string>(), "geographic");
  EXPECT_EQ(j["metadata"][""]["AQ_INPUT_mask.cursor"].get<std::string>(), "2");
  EXPECT_EQ(j["metadata"][""]["AQ_INPUTS_FNV1A64"].get<std::string>().size(), 16u);

  // Band 1 holds Ω_L (flag 1) as the report counts it; band 2 a level 0..3 exactly there.
  const auto report = aq::test::read_report(dir.path(), "g");
  const aq::raster::ByteGeoTiff t(tif);
  std::vector<std::uint8_t> classes(720 * 360), level(720 * 360);
  t.read_rows(1, 0, 360, classes.data());
  t.read_rows(2, 0, 360, level.data());
  std::int64_t filled = 0, mismatched = 0;
  for (std::size_t k = 0; k < classes.size(); ++k) {
    const bool in = (classes[k] & 1) != 0;
    filled += in ? 1 : 0;
    if (in != (level[k] <= 3)) ++mismatched;
  }
  EXPECT_EQ(filled, report["mask"]["fill"]["filled_pixels_final"].get<std::int64_t>());
  EXPECT_EQ(mismatched, 0);
  // North-up: the top row (90°N) is the Arctic, the bottom row (90°S) Antarctica: dry.
  EXPECT_EQ(classes[359 * 720 + 360] & 1, 0);
}

TEST(GlobalRunFileCli, BlocksAndRegionalReuseItWhenTheInputsMatch) {
  aq::testing::TempDir with, without;
  ASSERT_EQ(run_aquatoria("mesh" + sets(with.path()) + " --set 'output.formats=[\"tif\"]'").exit_code, 0);
  const auto a = run_aquatoria("blocks" + sets(with.path()) + " --top 2");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.err, HasSubstr("reused " + (with / "g.tif").string()));
  EXPECT_THAT(a.err, Not(HasSubstr("fill: done")));
  const auto b = run_aquatoria("blocks" + sets(without.path()) + " --top 2");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_THAT(b.err, Not(HasSubstr("reused")));
  EXPECT_THAT(b.err, HasSubstr("fill: done"));
  EXPECT_EQ(a.out, b.out);  // the ranked table
  for (const char* f : {"block_001.izogrid", "block_002.izogrid", "block_001.png", "blocks.png"})
    EXPECT_EQ(slurp(with / "blocks" / f), slurp(without / "blocks" / f)) << f;
}

// The Black Sea ROMS grid with its global run (configs/black_sea_global.toml) first computed, then
// read from the file: the same ROMS file, and the log says which.
TEST(GlobalRunFileCli, RegionalReusesItAndWritesTheSameRomsFile) {
  aq::testing::TempDir dir;
  const std::string configs = std::string(AQ_SOURCE_DIR) + "/configs/";
  std::string global = slurp(configs + "black_sea_global.toml");
  global.replace(global.find("dir = \"out\""), 11, "dir = \"" + (dir / "global").string() + "\"");
  { std::ofstream(dir / "global.toml") << global; }
  const std::string regional =
      "regional -c " + configs + "black_sea.toml --set roms.global_config=" + (dir / "global.toml").string() + " -o ";
  const auto a = run_aquatoria(regional + (dir / "a").string());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.err, Not(HasSubstr("mask reused")));
  const auto m = run_aquatoria("mesh -q -c " + (dir / "global.toml").string() + " --set 'output.formats=[\"tif\"]'");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  ASSERT_TRUE(fs::exists(dir / "global" / "black_sea_global.tif"));
  const auto b = run_aquatoria(regional + (dir / "b").string());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_THAT(b.err, HasSubstr("mask reused from " + (dir / "global" / "black_sea_global.tif").string()));
  EXPECT_EQ(slurp(dir / "a" / "black_sea_grd.nc"), slurp(dir / "b" / "black_sea_grd.nc"));
}

TEST(GlobalRunFileCli, OtherInputsRunTheFillAgainAndSayWhy) {
  aq::testing::TempDir dir;
  ASSERT_EQ(run_aquatoria("mesh" + sets(dir.path()) + " --set 'output.formats=[\"tif\"]'").exit_code, 0);
  const auto r = run_aquatoria("blocks" + sets(dir.path()) + " --top 1 --set mask.cursor=3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("g.tif was made from other inputs (mask.cursor: 2 -> 3)"));
  EXPECT_THAT(r.err, HasSubstr("running the global fill again"));
  EXPECT_THAT(r.err, HasSubstr("fill: done"));
  const auto j = nlohmann::json::parse(std::ifstream(dir / "blocks" / "blocks.json"));
  EXPECT_FALSE(j["mask"].contains("reused_file"));
}

// On the Mercator lattice (issue 12) the rows are equally spaced in y = ln tan(π/4 + φ/2), not in
// φ: the file is a spherical Mercator, so GDAL puts the top edge at the lattice's last row
// (86.5°+ of the rotated frame) and a row's centre at its latitude.
TEST(GlobalRunFileCli, MercatorLatticeFileMapsRowsToTheirLatitudes) {
  aq::testing::TempDir dir;
  const auto r = run_aquatoria(std::string("mesh -c ") + AQ_SOURCE_DIR +
                               "/configs/global_mercator.toml --set mask.passages=false --set output.name=g "
                               "--set 'output.formats=[\"tif\"]' -o " +
                               dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = aq::test::read_report(dir.path(), "g");
  const double lat_max = report["lattice"]["lat_max_deg"].get<double>();
  const auto ny = report["lattice"]["ny"].get<std::int64_t>();
  const auto info = aq::test::run_command("gdalinfo -json " + (dir / "g.tif").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_THAT(j["coordinateSystem"]["wkt"].get<std::string>(), HasSubstr("Mercator"));
  EXPECT_EQ(j["size"][1].get<std::int64_t>(), ny);
  const auto& corner = j["wgs84Extent"]["coordinates"][0];
  double top = -90.0, bottom = 90.0;
  for (const auto& p : corner) {
    top = std::max(top, p[1].get<double>());
    bottom = std::min(bottom, p[1].get<double>());
  }
  EXPECT_NEAR(top, lat_max, 1e-6);
  EXPECT_NEAR(bottom, -lat_max, 1e-6);
  EXPECT_THAT(j["metadata"][""]["AQ_LATTICE"].get<std::string>(), HasSubstr("kind=mercator"));
}

}  // namespace cli_global_run_file_cli_test

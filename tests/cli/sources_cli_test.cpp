// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria mesh` with several bathymetry sources (input.paths, input.blend_km): with blend 0 the
// mesh equals the mesh of one raster merged beforehand (byte for byte); the order matters; the
// report's per-source node counts add up to the mesh's nodes; 1 and 2 threads give the same files;
// bad lists are refused with the key and the value.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"
#include "support/synthetic_raster.hpp"

namespace cli_sources_cli_test {

using aq::test::fresh_dir;
using aq::test::run_aquatoria;
using aq::test::slurp;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

// A Float32 GeoTIFF of grid-registered sample points lon0 + c·step, lat0 + r·step (c < nc, r < nr).
fs::path write_grid(const fs::path& p, double lon0, double lat0, double step, int nc, int nr,
                    const std::function<double(double, double)>& f) {
  GDALAllRegister();
  GDALDataset* mem = GetGDALDriverManager()->GetDriverByName("MEM")->Create("", nc, nr, 1, GDT_Float32, nullptr);
  double gt[6] = {lon0 - 0.5 * step, step, 0.0, lat0 + (nr - 0.5) * step, 0.0, -step};
  mem->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  mem->SetSpatialRef(&srs);
  std::vector<float> buf(static_cast<std::size_t>(nc) * static_cast<std::size_t>(nr));
  for (int r = 0; r < nr; ++r)  // north-up: stored row 0 is the northernmost
    for (int c = 0; c < nc; ++c)
      buf[static_cast<std::size_t>(r) * static_cast<std::size_t>(nc) + static_cast<std::size_t>(c)] =
          static_cast<float>(f(lon0 + c * step, lat0 + (nr - 1 - r) * step));
  GDALRasterBand* b = mem->GetRasterBand(1);
  b->SetNoDataValue(-99999.0);
  EXPECT_EQ(b->RasterIO(GF_Write, 0, 0, nc, nr, buf.data(), nc, nr, GDT_Float32, 0, 0, nullptr), CE_None);
  GDALDataset* out =
      GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(p.c_str(), mem, FALSE, nullptr, nullptr, nullptr);
  GDALClose(out);
  GDALClose(mem);
  return p;
}

// The coarse field (global, 0.5°: on every vertex of the default 0.5° lattice) and the patch
// (0.25° over 0..20°E, 10°S..10°N): the field raised by 400 m, so it has islands where the coarse
// raster has sea, and a no-data hole (4..6°E, 4..6°N) where the coarse one shows through.
double coarse_value(double lon, double lat) { return aq::test::field(lon, lat); }
bool in_hole(double lon, double lat) { return lon >= 4.0 && lon <= 6.0 && lat >= 4.0 && lat <= 6.0; }
double patch_value(double lon, double lat) { return in_hole(lon, lat) ? -99999.0 : aq::test::field(lon, lat) + 400.0; }

struct Rasters {
  fs::path coarse, patch, merged;
};

const Rasters& rasters() {
  static const Rasters r = [] {
    const fs::path d = aq::test::synthetic_dir();
    Rasters x;
    x.coarse = write_grid(d / "coarse.tif", -180.0, -90.0, 0.5, 720, 361, coarse_value);
    x.patch = write_grid(d / "patch.tif", 0.0, -10.0, 0.25, 81, 81, patch_value);
    // What the two sources give at the 0.5° points, merged beforehand: the patch where it has data.
    x.merged = write_grid(d / "merged.tif", -180.0, -90.0, 0.5, 720, 361, [](double lon, double lat) {
      const bool in_patch = lon >= 0.0 && lon <= 20.0 && lat >= -10.0 && lat <= 10.0 && !in_hole(lon, lat);
      return in_patch ? patch_value(lon, lat) : coarse_value(lon, lat);
    });
    return x;
  }();
  return r;
}

std::string paths(const fs::path& a, const fs::path& b) {
  return "--set 'input.paths=[\"" + a.string() + "\", \"" + b.string() + "\"]'";
}

const char* kFormats = " --set 'output.formats=[\"msh\", \"vtu\", \"fort14\", \"text\"]' --set output.name=m";

// The files of two runs are the same byte for byte (fort.14: after its title line, which names
// the rasters the run was made from).
void expect_same_files(const fs::path& a, const fs::path& b) {
  for (const std::string f : {"m.msh", "m.vtu", "m.14", "m.txt"}) {
    ASSERT_TRUE(fs::exists(a / f)) << a / f;
    std::string x = slurp(a / f), y = slurp(b / f);
    if (f == "m.14") {
      x = x.substr(x.find('\n'));
      y = y.substr(y.find('\n'));
    }
    EXPECT_TRUE(x == y) << f << " differs between " << a << " and " << b;
  }
}

}  // namespace

TEST(SourcesCli, BlendZeroEqualsOnePreMergedRaster) {
  const Rasters& r = rasters();
  const fs::path two = fresh_dir("sources", "two"), one = fresh_dir("sources", "merged"),
                 coarse = fresh_dir("sources", "coarse");
  auto a = run_aquatoria("mesh -q -o " + two.string() + " " + paths(r.patch, r.coarse) + kFormats);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  auto b = run_aquatoria("mesh -q -o " + one.string() + " --set input.path=" + r.merged.string() + kFormats);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  expect_same_files(two, one);
  // ...and the patch did change the mesh (the coarse raster alone gives another one).
  auto c = run_aquatoria("mesh -q -o " + coarse.string() + " --set input.path=" + r.coarse.string() + kFormats);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_FALSE(slurp(two / "m.14") == slurp(coarse / "m.14"));
}

TEST(SourcesCli, ReportCountsNodesPerSourceAndOrderMatters) {
  const Rasters& r = rasters();
  const fs::path dir = fresh_dir("sources", "counts"), swapped = fresh_dir("sources", "swapped");
  auto a =
      run_aquatoria("mesh -o " + dir.string() + " " + paths(r.patch, r.coarse) + kFormats + " --set input.blend_km=60");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.err, HasSubstr("read: source 1 (highest priority) " + r.patch.string()));
  EXPECT_THAT(a.err, HasSubstr("sources: " + r.patch.string() + " supplied "));
  const auto rep = aq::test::read_report(dir, "m");
  const auto& in = rep.at("input");
  ASSERT_EQ(in.at("sources").size(), 2u);
  std::int64_t sum = in.at("no_data_nodes").get<std::int64_t>();
  for (const auto& s : in.at("sources"))
    sum += s.at("nodes").get<std::int64_t>() + s.at("blended_nodes").get<std::int64_t>();
  EXPECT_EQ(sum, rep.at("mesh_counts").at("nodes").get<std::int64_t>());
  EXPECT_GT(in.at("sources")[0].at("nodes").get<std::int64_t>(), 50);
  EXPECT_GT(in.at("sources")[0].at("blended_nodes").get<std::int64_t>(), 10);
  EXPECT_EQ(in.at("sources")[1].at("blended_nodes").get<std::int64_t>(), 0);
  EXPECT_EQ(in.at("sources")[0].at("columns").get<std::int64_t>(), 81);
  EXPECT_DOUBLE_EQ(in.at("sources")[0].at("resolution_deg").get<double>(), 0.25);
  // The other order: the global raster has data everywhere, the patch supplies nothing.
  auto b = run_aquatoria("mesh -o " + swapped.string() + " " + paths(r.coarse, r.patch) + kFormats);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto rep2 = aq::test::read_report(swapped, "m");
  EXPECT_EQ(rep2.at("input").at("sources")[1].at("nodes").get<std::int64_t>(), 0);
  EXPECT_FALSE(slurp(dir / "m.14") == slurp(swapped / "m.14"));
}

TEST(SourcesCli, OneAndTwoThreadsGiveTheSameFiles) {
  const Rasters& r = rasters();
  const fs::path t1 = fresh_dir("sources", "t1"), t2 = fresh_dir("sources", "t2");
  const std::string args = paths(r.patch, r.coarse) + kFormats + " --set input.blend_km=80";
  auto a =
      aq::test::run_command("OMP_NUM_THREADS=1 " + std::string(AQ_BINARY) + " mesh -q -o " + t1.string() + " " + args);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  auto b =
      aq::test::run_command("OMP_NUM_THREADS=2 " + std::string(AQ_BINARY) + " mesh -q -o " + t2.string() + " " + args);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  expect_same_files(t1, t2);
}

TEST(SourcesCli, BadListsAreRefusedWithKeyAndValue) {
  const Rasters& r = rasters();
  const fs::path dir = fresh_dir("sources", "bad");
  const std::string o = "mesh -q -o " + dir.string() + " ";
  // A missing file: an input error (exit 1) naming the entry and the file.
  auto a = run_aquatoria(o + paths(r.patch, "/nonexistent/gebco.nc"));
  EXPECT_EQ(a.exit_code, 1) << a.err;
  EXPECT_THAT(a.err, HasSubstr("input.paths[1]"));
  EXPECT_THAT(a.err, HasSubstr("/nonexistent/gebco.nc"));
  // Configuration errors (exit 2): empty, not a list, an element not a string, both keys.
  a = run_aquatoria(o + "--set 'input.paths=[]'");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_THAT(a.err, HasSubstr("input.paths: [] is empty"));
  a = run_aquatoria(o + "--set input.paths=gebco.nc");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_THAT(a.err, HasSubstr("input.paths: expected a list of raster paths"));
  a = run_aquatoria(o + "--set 'input.paths=[\"" + r.patch.string() + "\", 3]'");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_THAT(a.err, HasSubstr("input.paths[1]: expected a string"));
  a = run_aquatoria(o + "--set input.path=" + r.coarse.string() + " " + paths(r.patch, r.coarse));
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_THAT(a.err, HasSubstr("input.path = \"" + r.coarse.string() + "\" and input.paths"));
  a = run_aquatoria(o + "--set input.blend_km=5");
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_THAT(a.err, HasSubstr("input.blend_km = 5"));
  a = run_aquatoria(o + paths(r.patch, r.patch));
  EXPECT_EQ(a.exit_code, 2) << a.err;
  EXPECT_THAT(a.err, HasSubstr("repeats input.paths[0]"));
  EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir));
}

TEST(SourcesCli, StreamedSourcesGiveTheSameFiles) {
  // Every source streamed in bands of 7 rows (the hidden test knobs) against every source held
  // whole: the stack samples each source through the same paths as a single raster.
  const Rasters& r = rasters();
  const fs::path whole = fresh_dir("sources", "whole"), streamed = fresh_dir("sources", "streamed");
  const std::string args = paths(r.patch, r.coarse) + kFormats;
  auto a = aq::test::run_command("AQ_RASTER_STREAMING=never " + std::string(AQ_BINARY) + " mesh -q -o " +
                                 whole.string() + " " + args);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  auto b = aq::test::run_command("AQ_RASTER_STREAMING=always AQ_RASTER_BAND_ROWS=7 " + std::string(AQ_BINARY) +
                                 " mesh -o " + streamed.string() + " " + args);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_THAT(b.err, HasSubstr("streamed"));
  expect_same_files(whole, streamed);
  // A blend needs the sources above the last held whole: refused, naming the key.
  auto c = aq::test::run_command("AQ_RASTER_STREAMING=always " + std::string(AQ_BINARY) + " mesh -q -o " +
                                 streamed.string() + "_blend " + args + " --set input.blend_km=10");
  EXPECT_EQ(c.exit_code, 1) << c.err;
  EXPECT_THAT(c.err, HasSubstr("input.blend_km = 10"));
}

TEST(SourcesCli, CommandLineReplacesTheFilesChoice) {
  // input.path in the file, --set input.paths on the command line: the list is used (and the
  // other way round); both in the file is an error naming both keys.
  const Rasters& r = rasters();
  const fs::path dir = fresh_dir("sources", "layers");
  const fs::path one = dir.string() + "_one.toml", list = dir.string() + "_list.toml",
                 both = dir.string() + "_both.toml";
  std::ofstream(one) << "[input]\npath = \"" << r.coarse.string() << "\"\n";
  std::ofstream(list) << "[input]\npaths = [\"" << r.patch.string() << "\", \"" << r.coarse.string() << "\"]\n";
  std::ofstream(both) << "[input]\npath = \"" << r.coarse.string() << "\"\npaths = [\"" << r.patch.string() << "\", \""
                      << r.coarse.string() << "\"]\n";
  auto a =
      run_aquatoria("mesh -q -c " + one.string() + " -o " + dir.string() + "/a " + paths(r.patch, r.coarse) + kFormats);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(aq::test::read_report(dir / "a", "m").at("input").at("sources").size(), 2u);
  auto b = run_aquatoria("mesh -q -c " + list.string() + " -o " + dir.string() +
                         "/b --set input.path=" + r.coarse.string() + kFormats);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(aq::test::read_report(dir / "b", "m").at("input").at("sources").size(), 1u);
  auto c = run_aquatoria("mesh -q -c " + both.string() + " -o " + dir.string() + "/c" + kFormats);
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_THAT(c.err, HasSubstr("input.path = \"" + r.coarse.string() + "\" and input.paths"));
}

}  // namespace cli_sources_cli_test

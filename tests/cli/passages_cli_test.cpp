// SPDX-License-Identifier: GPL-3.0-or-later
// No sea dropped in silence (README "Passages, channels and rivers") on the real ETOPO5 and the
// shipped configs: global_tides keeps the Mediterranean, Red Sea, Baltic, Black Sea and White
// Sea, with those passages open (carved) in its table; the seed's reference run keeps its bytes
// but warns of the Mediterranean it drops, with its area, and carves it back in with one key;
// north_sea has the Channel and the Irish Sea, open on the west edge; a second seed's closed sea
// is meshed apart with its coast typed mainland; bad names and files fail clearly with no output;
// the carving is the same bytes at 1 and 2 threads.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/fort14_read.hpp"
#include "support/run_command.hpp"

namespace cli_passages_cli_test {

namespace {

namespace fs = std::filesystem;

const std::string kEtopo5 = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";

std::string config(const std::string& name) { return std::string(AQ_SOURCE_DIR) + "/configs/" + name + ".toml"; }

std::string bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

using aq::test::Fort14;
using aq::test::read_fort14;

// Whether a node lies within `r` degrees (λ and φ) of (lon, lat).
bool node_near(const Fort14& f, double lon, double lat, double r) {
  for (std::size_t k = 0; k < f.lon.size(); ++k)
    if (std::abs(f.lon[k] - lon) <= r && std::abs(f.lat[k] - lat) <= r) return true;
  return false;
}

const nlohmann::json* passage(const nlohmann::json& report, const std::string& name) {
  for (const auto& p : report["mask"]["passages"])
    if (p["name"] == name) return &p;
  return nullptr;
}

std::vector<std::string> dropped_names(const nlohmann::json& report) {
  std::vector<std::string> out;
  for (const auto& d : report["mask"]["dropped"]["above_threshold"]) out.push_back(d["name"].get<std::string>());
  return out;
}

// A 0.25° world raster at `tif`: land (+100 m) but where `wet(lon, lat)` (a pixel's centre), at
// `depth_m` below the datum.
fs::path quarter_degree_world(const fs::path& tif, float depth_m, const std::function<bool(double, double)>& wet) {
  GDALAllRegister();
  const int w = 1440, h = 720;
  GDALDataset* ds =
      GetGDALDriverManager()->GetDriverByName("GTiff")->Create(tif.c_str(), w, h, 1, GDT_Float32, nullptr);
  double gt[6] = {-180.0, 0.25, 0.0, 90.0, 0.0, -0.25};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  ds->SetSpatialRef(&srs);
  std::vector<float> buf(static_cast<std::size_t>(w) * h, 100.0F);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (wet(-180.0 + (c + 0.5) * 0.25, 90.0 - (r + 0.5) * 0.25)) buf[static_cast<std::size_t>(r) * w + c] = -depth_m;
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, buf.data(), w, h, GDT_Float32, 0, 0, nullptr),
            CE_None);
  GDALClose(ds);
  return tif;
}

class PassagesCli : public testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kEtopo5)) GTEST_SKIP() << kEtopo5 << " not installed (ferret-datasets)";
  }
};

TEST_F(PassagesCli, GlobalTidesKeepsTheMediterraneanRedSeaBalticBlackAndWhiteSeas) {
  const fs::path dir = aq::test::fresh_dir("passages", "tides");
  const auto r = aq::test::run_aquatoria("mesh -c " + config("global_tides") + " -o " + dir.string() +
                                         " --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Fort14 f = read_fort14(dir / "global_tides.14");
  ASSERT_GT(f.lon.size(), 300000U);
  for (const auto& [name, lon, lat] : {std::tuple{"Ionian Sea", 18.0, 35.0},
                                       {"Levantine Sea", 30.0, 33.5},
                                       {"Red Sea", 38.0, 21.0},
                                       {"Baltic Sea", 19.0, 57.0},
                                       {"Gulf of Bothnia", 20.0, 62.0},
                                       {"Black Sea", 34.0, 43.5},
                                       {"White Sea", 38.5, 65.5},
                                       {"Persian Gulf", 51.0, 27.0}})
    EXPECT_TRUE(node_near(f, lon, lat, 0.3)) << name;
  EXPECT_FALSE(node_near(f, 50.7, 42.0, 0.5));  // the Caspian stays out (a lake)
  const auto rep = aq::test::read_report(dir, "global_tides");
  for (const char* p : {"Gibraltar", "Bab-el-Mandeb", "Danish straits", "Dardanelles", "Bosphorus", "Gorlo"}) {
    const nlohmann::json* j = passage(rep, p);
    ASSERT_NE(j, nullptr) << p;
    EXPECT_EQ((*j)["status"], "open") << p;
    EXPECT_EQ((*j)["carved"], true) << p;
  }
  EXPECT_EQ(rep["carving"].size(), 6U);
  for (const auto& c : rep["carving"]) {
    EXPECT_GT(c["depth_m"].get<double>(), 10.0) << c["name"];  // below h = 10 m
    EXPECT_GT(c["half_width_km"][0].get<double>(), 10.0) << c["name"];
  }
  // What is still dropped: nothing of those seas; the Caspian, lakes and ice-shelf cavities.
  const std::vector<std::string> names = dropped_names(rep);
  for (const char* sea : {"Mediterranean Sea", "Red Sea", "Baltic Sea", "Black Sea", "White Sea"})
    EXPECT_EQ(std::count(names.begin(), names.end(), sea), 0) << sea;
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names[0], "Caspian Sea");  // the largest: named from the list of inland basins
  EXPECT_EQ(rep["mask"]["dropped"]["above_threshold"][0]["inland"], true);
  EXPECT_NE(r.err.find("dropped: Caspian Sea (inland"), std::string::npos);
  double above = 0.0;
  for (const auto& d : rep["mask"]["dropped"]["above_threshold"]) above += d["area_km2"].get<double>();
  EXPECT_LT(above, 0.6e6);  // measured 537 800 km², the Caspian 483 400 of it
  EXPECT_NE(r.err.find("carve: Gibraltar"), std::string::npos);
}

// At L = 3 Hormuz's two sides fall in pieces that the fill leaves out one behind the other: the
// Gulf of Oman's chain to the ocean crosses Hormuz twice. Each passage is named once, in the
// report, the warning and the key it suggests.
TEST_F(PassagesCli, ADroppedSeasChainNamesEachPassageOnce) {
  const fs::path dir = aq::test::fresh_dir("passages", "tides_L3");
  const auto r = aq::test::run_aquatoria("mesh -c " + config("global_tides") + " -o " + dir.string() +
                                         " --set quadtree.levels=3 --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = aq::test::read_report(dir, "global_tides");
  bool oman = false;
  for (const auto& d : rep["mask"]["dropped"]["above_threshold"]) {
    std::vector<std::string> p = d["passages"].get<std::vector<std::string>>();
    std::sort(p.begin(), p.end());
    EXPECT_EQ(std::adjacent_find(p.begin(), p.end()), p.end()) << d.dump();
    if (d["name"] == "Gulf of Oman") {
      oman = true;
      EXPECT_EQ(d["passages"], nlohmann::json::array({"Hormuz"}));
    }
  }
  EXPECT_TRUE(oman) << "the Gulf of Oman is no longer dropped at L = 3: pick another case";
  EXPECT_EQ(r.err.find("Hormuz, Hormuz"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("\"Hormuz\", \"Hormuz\""), std::string::npos) << r.err;
}

TEST_F(PassagesCli, SeedRunKeepsItsBytesButWarnsOfTheMediterraneanAndCarvesItWithOneKey) {
  const fs::path dir = aq::test::fresh_dir("passages", "seed");
  const auto r = aq::test::run_aquatoria("mesh -o " + dir.string() + " --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: dropped: Mediterranean Sea (centre 17.34°E 37.06°N), 2.08 million km²"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("mask.passages_open = [\"Gibraltar\"]"), std::string::npos);
  const auto rep = aq::test::read_report(dir, "seed_4deg_L3");
  const auto& first = rep["mask"]["dropped"]["above_threshold"][0];
  EXPECT_EQ(first["name"], "Mediterranean Sea");
  EXPECT_NEAR(first["area_km2"].get<double>(), 2.08e6, 0.01e6);
  EXPECT_EQ(first["passages"], nlohmann::json::array({"Gibraltar"}));
  EXPECT_EQ(first["cut_by_passage"], true);
  EXPECT_GT(first["land_gap_pixels"].get<int>(), 0);  // ETOPO5 at 0.5°: no wet pixel in the strait
  const Fort14 before = read_fort14(dir / "seed_4deg_L3.14");
  EXPECT_FALSE(node_near(before, 18.0, 35.0, 0.3));
  // One key carves it back in.
  const fs::path dir2 = aq::test::fresh_dir("passages", "seed_gib");
  const auto r2 = aq::test::run_aquatoria(
      "mesh -o " + dir2.string() + " --set 'output.formats=[\"fort14\"]' --set 'mask.passages_open=[\"Gibraltar\"]'");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const Fort14 after = read_fort14(dir2 / "global_4deg_L3.14");
  EXPECT_TRUE(node_near(after, 18.0, 35.0, 0.3));
  const auto rep2 = aq::test::read_report(dir2, "global_4deg_L3");
  EXPECT_EQ((*passage(rep2, "Gibraltar"))["status"], "open");
  EXPECT_EQ((*passage(rep2, "Sicily"))["status"], "open");
  const std::vector<std::string> names = dropped_names(rep2);
  EXPECT_EQ(std::count(names.begin(), names.end(), "Mediterranean Sea"), 0);
}

TEST_F(PassagesCli, NorthSeaHasTheChannelAndTheIrishSeaOpenOnTheWestEdge) {
  const fs::path dir = aq::test::fresh_dir("passages", "north_sea");
  const auto r = aq::test::run_aquatoria("mesh -c " + config("north_sea") + " -o " + dir.string() +
                                         " --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Fort14 f = read_fort14(dir / "north_sea.14");
  EXPECT_TRUE(node_near(f, -2.0, 50.0, 0.2));  // the English Channel
  EXPECT_TRUE(node_near(f, 1.6, 51.1, 0.2));   // the Dover Strait
  EXPECT_TRUE(node_near(f, -4.5, 53.8, 0.2));  // the Irish Sea
  EXPECT_TRUE(node_near(f, -6.0, 51.5, 0.2));  // the Celtic Sea
  // The west edge, 8°W, is open from the Celtic Sea south to 48°N: the Channel's way to the
  // Atlantic, in one segment (its nodes as coarse as the size field there: 1° apart in deep water).
  long segments = 0;
  for (const auto& s : f.open) {
    double lo = 90.0, hi = -90.0;
    for (const long n : s.nodes)
      if (std::abs(f.lon[static_cast<std::size_t>(n)] + 8.0) < 1e-6 && f.lat[static_cast<std::size_t>(n)] < 52.0) {
        lo = std::min(lo, f.lat[static_cast<std::size_t>(n)]);
        hi = std::max(hi, f.lat[static_cast<std::size_t>(n)]);
      }
    if (lo <= 48.0 + 1e-6 && hi >= 51.5 - 1e-6) ++segments;
  }
  EXPECT_EQ(segments, 1);
  // No land on that stretch of the edge.
  for (const auto& [type, nodes] : f.land)
    for (const long n : nodes) {
      const double lat = f.lat[static_cast<std::size_t>(n)];
      EXPECT_FALSE(std::abs(f.lon[static_cast<std::size_t>(n)] + 8.0) < 1e-6 && lat > 48.0 + 1e-6 && lat < 51.5)
          << "land node at 8°W " << lat << "°N";
    }
  const auto rep = aq::test::read_report(dir, "north_sea");
  const nlohmann::json* dover = passage(rep, "Dover");
  ASSERT_NE(dover, nullptr);  // the regional run's table holds the passages inside its box
  EXPECT_EQ((*dover)["status"], "open");
  EXPECT_EQ((*dover)["carved"], true);
  EXPECT_TRUE(dropped_names(rep).empty());
  EXPECT_NE(r.err.find("critical passages inside the domain"), std::string::npos);
  // Without the carving the Channel is left out, and said so.
  const fs::path dir2 = aq::test::fresh_dir("passages", "north_sea_closed");
  const auto r2 = aq::test::run_aquatoria("mesh -c " + config("north_sea") + " -o " + dir2.string() +
                                          " --set 'output.formats=[\"fort14\"]' --set 'mask.passages_open=[]'");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_FALSE(node_near(read_fort14(dir2 / "north_sea.14"), -2.0, 50.0, 0.2));
  EXPECT_NE(r2.err.find("warning: dropped: English Channel"), std::string::npos) << r2.err;
  EXPECT_NE(r2.err.find("mask.passages_open = [\"Dover\"]"), std::string::npos);
  // The Channel meets the domain's west edge: a seed would mesh it with its own open boundary.
  const auto rep2 = aq::test::read_report(dir2, "north_sea");
  ASSERT_FALSE(rep2["mask"]["dropped"]["above_threshold"].empty());
  const auto& channel = rep2["mask"]["dropped"]["above_threshold"][0];
  EXPECT_EQ(channel["name"], "English Channel");
  EXPECT_EQ(channel["reaches_domain_edge"], true);
  EXPECT_EQ(channel["connecting_cursor"], 1);  // wet pixels join it through the Dover Strait
  EXPECT_NE(channel["keep"].get<std::string>().find("its own open boundary"), std::string::npos);
}

TEST_F(PassagesCli, BadNamesAndFilesFailClearlyWithoutOutputs) {
  const fs::path dir = aq::test::fresh_dir("passages", "bad");
  auto r = aq::test::run_aquatoria("mesh -o " + dir.string() + " --set 'mask.passages_open=[\"Gibralter\"]'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("\"Gibralter\" (did you mean \"Gibraltar\"?)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir) && !fs::is_empty(dir));
  r = aq::test::run_aquatoria("mesh -o " + dir.string() + " --set mask.channels=/nonexistent/rivers.geojson");
  EXPECT_EQ(r.exit_code, 1);  // an input error, as a missing raster is
  EXPECT_NE(r.err.find("mask.channels = \"/nonexistent/rivers.geojson\": GDAL/OGR cannot open it"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir) && !fs::is_empty(dir));
  fs::create_directories(dir.parent_path());
  const fs::path bad = dir.string() + "_poly.geojson";
  {
    std::ofstream f(bad);
    f << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "lake"}, )"
      << R"("geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}}]})";
  }
  r = aq::test::run_aquatoria("mesh -o " + dir.string() + " --set mask.transects=" + bad.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("mask.transects = \"" + bad.string() + "\", layer"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("feature 0: the geometry is POLYGON, not a line"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir) && !fs::is_empty(dir));
  fs::remove(bad);
}

// A 0.25° world of two closed lakes in a box, seeded both: two parts, each with its coast
// mainland (IBTYPE 20), and a warning for the second seed.
TEST_F(PassagesCli, ASecondSeedsSeparateSeaIsMeshedApartWithItsCoastMainland) {
  const fs::path dir = aq::test::fresh_dir("passages", "lakes");
  fs::create_directories(dir);
  const fs::path tif = quarter_degree_world(dir.string() + "_lakes.tif", 500.0F, [](double lon, double lat) {
    return (lon > 2.0 && lon < 8.0 && lat > 2.0 && lat < 8.0) || (lon > 12.0 && lon < 18.0 && lat > 2.0 && lat < 8.0);
  });
  const auto r = aq::test::run_aquatoria(
      "mesh -o " + dir.string() + " --set input.path=" + tif.string() +
      " --set 'domain.box=[0.0, 20.0, 0.0, 10.0]' --set quadtree.step_deg=1 --set quadtree.levels=2"
      " --set 'mask.seeds=[[5.0, 5.0], [15.0, 5.0]]' --set output.name=lakes --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("seeds: mask.seeds[1] = (15, 5) fills"), std::string::npos) << r.err;
  const Fort14 f = read_fort14(dir / "lakes.14");
  EXPECT_TRUE(f.open.empty());
  ASSERT_EQ(f.land.size(), 2U);
  for (const auto& [type, nodes] : f.land) EXPECT_EQ(type, 20) << "a lake's coast is mainland, not an island";
  const auto rep = aq::test::read_report(dir, "lakes");
  EXPECT_EQ(rep["warnings"]["seeds_in_separate_parts"].size(), 1U);
  fs::remove(tif);
}

// A 0.25° raster: a basin at 2..28°E × 2..18°N in land (+100 m), a box around it that reaches
// 30°E, and a river drawn from the basin east out of the box: it is burned in, and where it
// crosses the box's edge it is a river inflow, typed so in every format that has the notion.
fs::path basin_with_land_east(const fs::path& where) {
  return quarter_degree_world(where.string() + "_basin.tif", 800.0F, [](double lon, double lat) {
    return lon > 2.0 && lon < 28.0 && lat > 2.0 && lat < 18.0;
  });
}

TEST_F(PassagesCli, ARiverCrossingTheDomainEdgeIsARiverInflowInEveryFormat) {
  const fs::path dir = aq::test::fresh_dir("passages", "river");
  fs::create_directories(dir.parent_path());
  const fs::path tif = basin_with_land_east(dir);
  const fs::path river = dir.string() + "_river.geojson";
  {
    std::ofstream f(river);
    f << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "Test River", )"
      << R"("width_m": 2000, "depth_m": 6}, "geometry": {"type": "LineString", "coordinates": [[25.0, 10.0], [29.0, 10.2], [34.0, 11.0]]}}]})";
  }
  const auto r = aq::test::run_aquatoria(
      "mesh -o " + dir.string() + " --set input.path=" + tif.string() +
      " --set 'domain.box=[0.0, 30.0, 0.0, 20.0]' --set quadtree.step_deg=1 --set quadtree.levels=2"
      " --set 'mask.seeds=[[10.0, 10.0]]' --set mask.channels=" +
      river.string() +
      " --set output.name=river --set 'output.formats=[\"fort14\", \"schism\", \"msh\", \"ugrid\", \"png\"]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 river inflow segment(s)"), std::string::npos) << r.err;
  // fort.14: no elevation boundary; the river a land boundary of IBTYPE 22 on the east edge.
  const Fort14 f = read_fort14(dir / "river.14");
  EXPECT_TRUE(f.open.empty());
  int rivers = 0;
  for (const auto& [type, nodes] : f.land) {
    if (type != 22) continue;
    ++rivers;
    EXPECT_GE(nodes.size(), 3U);
    for (const long n : nodes) {
      EXPECT_NEAR(f.lon[static_cast<std::size_t>(n)], 30.0, 1e-9);
      EXPECT_NEAR(f.lat[static_cast<std::size_t>(n)], 10.3, 1.6);
    }
  }
  EXPECT_EQ(rivers, 1);
  EXPECT_TRUE(node_near(f, 29.0, 10.2, 0.2));  // the river's channel through the land
  // hgrid.gr3: an open (flow) boundary; bctides.in: iettype 0, ifltype 2.
  const Fort14 g = read_fort14(dir / "river.gr3");
  ASSERT_EQ(g.open.size(), 1U);
  for (const long n : g.open[0].nodes) EXPECT_NEAR(g.lon[static_cast<std::size_t>(n)], 30.0, 1e-9);
  const std::string bct = bytes(dir / "river_bctides.in");
  EXPECT_NE(bct.find("1 !nope"), std::string::npos) << bct;
  EXPECT_NE(bct.find(" 0 2 0 0 !open boundary 1"), std::string::npos) << bct;
  EXPECT_NE(bytes(dir / "river.msh").find("1 6 \"river\""), std::string::npos);
  const auto rep = aq::test::read_report(dir, "river");
  EXPECT_EQ(rep["boundaries"]["river_segments"], 1);
  EXPECT_EQ(rep["boundaries"]["open_segments"], 0);
  EXPECT_EQ(rep["carving"][0]["kind"], "channel");
  EXPECT_EQ(rep["carving"][0]["depth_m"], 6.0);
  // Without the river: no boundary but the coast.
  const fs::path dir2 = aq::test::fresh_dir("passages", "no_river");
  const auto r2 = aq::test::run_aquatoria(
      "mesh -o " + dir2.string() + " --set input.path=" + tif.string() +
      " --set 'domain.box=[0.0, 30.0, 0.0, 20.0]' --set quadtree.step_deg=1 --set quadtree.levels=2"
      " --set 'mask.seeds=[[10.0, 10.0]]' --set output.name=river --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const Fort14 f2 = read_fort14(dir2 / "river.14");
  EXPECT_TRUE(f2.open.empty());
  ASSERT_EQ(f2.land.size(), 1U);
  EXPECT_EQ(f2.land[0].type, 20);
  EXPECT_FALSE(node_near(f2, 29.0, 10.2, 0.2));
  fs::remove(tif);
  fs::remove(river);
}

TEST_F(PassagesCli, CarvingIsTheSameBytesAtOneAndTwoThreads) {
  const fs::path lines = aq::test::fresh_dir("passages", "lines.geojson");
  {
    std::ofstream f(lines);
    f << R"({"type": "FeatureCollection", "features": [)"
      << R"({"type": "Feature", "properties": {"kind": "blockage"}, "geometry": {"type": "LineString", "coordinates": [[-80.5, 7.0], [-78.5, 10.5]]}},)"
      << R"({"type": "Feature", "properties": {"name": "Amazon"}, "geometry": {"type": "LineString", "coordinates": [[-49.0, 0.0], [-55.0, -2.0], [-60.0, -3.0]]}}]})";
  }
  std::vector<fs::path> dirs;
  for (int threads : {1, 2}) {
    const fs::path d = aq::test::fresh_dir("passages", "t" + std::to_string(threads));
    const auto r = aq::test::run_command(
        "OMP_NUM_THREADS=" + std::to_string(threads) + " " + std::string(AQ_BINARY) + " mesh -q -o " + d.string() +
        " --set 'mask.passages_open=[\"Gibraltar\", \"Bab-el-Mandeb\", \"Hormuz\"]' --set mask.transects=" +
        lines.string() + " --set mask.channels=" + lines.string() +
        " --set 'output.formats=[\"msh\", \"ugrid\", \"fort14\", \"png\"]'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    dirs.push_back(d);
  }
  for (const char* f : {"global_4deg_L3.msh", "global_4deg_L3.nc", "global_4deg_L3.14", "global_4deg_L3.png"})
    EXPECT_TRUE(bytes(dirs[0] / f) == bytes(dirs[1] / f)) << f;
  const auto rep = aq::test::read_report(dirs[0], "global_4deg_L3");
  EXPECT_EQ(rep["carving"].size(), 3U + 2U + 2U);  // 3 passages; a blockage and a passage; both lines as channels
  fs::remove(lines);
}

}  // namespace
}  // namespace cli_passages_cli_test

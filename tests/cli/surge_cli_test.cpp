// SPDX-License-Identifier: GPL-3.0-or-later
// Storm-surge meshes end to end (README "A storm-surge mesh"): a synthetic coast with a low plain
// behind the shore and a second plain behind a ridge, meshed with mask.min_depth_m = -5. The plain
// below the limit and connected to the sea is meshed, with negative depths in fort.14, hgrid.gr3
// and the text file; the plain behind the higher ridge is not (until the limit tops the ridge);
// the box edges crossing the floodplain are land, the open boundary is in the sea and as coarse as
// the water there; the report's floodplain and time step with wetting and drying; 1 and 2 threads
// give the same bytes; bad values are refused at load naming the key and its range.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/fort14_read.hpp"
#include "support/png_pixels.hpp"
#include "support/run_command.hpp"

namespace cli_surge_cli_test {

namespace {

namespace fs = std::filesystem;

// West to east (elevation, m): the sea deepening westward (-20 m at 8°E, -820 m at 0°), a shelf
// rising to 0 m at 10°E, plain A at +2 m (10-14°E) with a lake at -3 m (11.5-12.5°E, 9-11°N), a
// ridge at +20 m (14-15°E), plain B at +2 m (15-19°E), high land at +50 m beyond.
bool in_lake(double lon, double lat) { return lon > 11.5 && lon < 12.5 && lat > 9.0 && lat < 11.0; }

double coast_elevation(double lon, double lat) {
  if (lon < 8.0) return -20.0 - 100.0 * (8.0 - lon);
  if (lon < 10.0) return -20.0 + 10.0 * (lon - 8.0);
  if (in_lake(lon, lat)) return -3.0;
  if (lon < 14.0) return 2.0;
  if (lon < 15.0) return 20.0;
  if (lon < 19.0) return 2.0;
  return 50.0;
}

// 0.1° cells over -2..22°E, -2..22°N (a regional raster: the rest of the globe has no data).
fs::path coast_raster() {
  static const fs::path p = [] {
    const fs::path dir = aq::test::fresh_dir("surge", "raster");
    fs::create_directories(dir);
    const fs::path f = dir / "plain_ridge.tif";
    GDALAllRegister();
    const double step = 0.1;
    const int n = 240;
    GDALDataset* ds =
        GetGDALDriverManager()->GetDriverByName("GTiff")->Create(f.c_str(), n, n, 1, GDT_Float32, nullptr);
    double gt[6] = {-2.0, step, 0.0, 22.0, 0.0, -step};
    ds->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.importFromEPSG(4326);
    ds->SetSpatialRef(&srs);
    std::vector<float> buf(static_cast<std::size_t>(n) * n);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c)
        buf[static_cast<std::size_t>(r) * n + c] =
            static_cast<float>(coast_elevation(-2.0 + (c + 0.5) * step, 22.0 - (r + 0.5) * step));
    EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, n, n, buf.data(), n, n, GDT_Float32, 0, 0, nullptr),
              CE_None);
    GDALClose(ds);
    return f;
  }();
  return p;
}

const std::string kFormats =
    "--set 'output.formats=[\"fort14\", \"schism\", \"text\", \"ugrid\", \"msh\", \"vtu\", \"png\"]'";

aq::test::CommandResult mesh_coast(const fs::path& dir, double h, int threads = 2, const std::string& more = "") {
  std::ostringstream cmd;
  cmd << "OMP_NUM_THREADS=" << threads << " " << AQ_BINARY << " mesh -q --set input.path=" << coast_raster().string()
      << " --set 'domain.box=[0.0, 20.0, 2.0, 18.0]' --set 'mask.seeds=[[4.0, 10.0]]' --set mask.min_depth_m=" << h
      << " --set quadtree.step_deg=1.0 --set quadtree.levels=2 --set quadtree.coast_band=1"
      << " --set output.name=coast --set output.png_width=600 --set output.png_color=\"elevation\" " << kFormats
      << " -o " << dir.string() << " " << more;
  return aq::test::run_command(cmd.str());
}

struct Node {
  double lon = 0, lat = 0, depth = 0;
};

struct Model {
  std::vector<Node> nodes;
  std::vector<std::vector<long>> open, land;  // 0-based node ids per segment
  bool ok = false;
};

// fort.14 / hgrid.gr3 (aq::test::read_fort14): nodes, and the open and land segments.
Model read_model(const fs::path& p) {
  const aq::test::Fort14 f = aq::test::read_fort14(p);
  Model m;
  for (std::size_t k = 0; k < f.lon.size(); ++k) m.nodes.push_back({f.lon[k], f.lat[k], f.depth[k]});
  for (const auto& seg : f.open) m.open.push_back(seg.nodes);
  for (const auto& seg : f.land) m.land.push_back(seg.nodes);
  m.ok = f.error.empty();
  return m;
}

// Nodes of the text file: (lon, depth).
std::vector<Node> read_text_nodes(const fs::path& p) {
  std::vector<Node> out;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line) && line.rfind("nodes ", 0) != 0) {
  }
  const long n = std::stol(line.substr(6));
  std::getline(in, line);  // column header
  for (long k = 0; k < n && std::getline(in, line); ++k) {
    std::istringstream s(line);
    long id = 0;
    Node node;
    s >> id >> node.lon >> node.lat >> node.depth;
    out.push_back(node);
  }
  return out;
}

long count_if_nodes(const std::vector<Node>& v, double lon_lo, double lon_hi) {
  return std::count_if(v.begin(), v.end(), [&](const Node& n) { return n.lon > lon_lo && n.lon < lon_hi; });
}

TEST(SurgeCli, ThePlainBelowTheLimitIsMeshedThePlainBehindTheRidgeIsNot) {
  const fs::path dir = aq::test::fresh_dir("surge", "h5");
  const auto r = mesh_coast(dir, -5.0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("reached only across the floodplain"), std::string::npos) << r.err;
  for (const char* ext : {".14", ".gr3"}) {
    const Model m = read_model(dir / (std::string("coast") + ext));
    ASSERT_TRUE(m.ok) << ext;
    // Plain A (+2 m) is meshed, its depth -2 in the file; nothing behind the ridge.
    long plain_a = 0;
    for (const Node& n : m.nodes) {
      if (n.lon > 10.4 && n.lon < 13.6 && !(n.lon > 11.2 && n.lon < 12.8 && n.lat > 8.7 && n.lat < 11.3)) {
        ++plain_a;
        EXPECT_DOUBLE_EQ(n.depth, -2.0) << ext << " at " << n.lon << ", " << n.lat;
      }
      EXPECT_LT(n.lon, 14.0) << ext << ": a node behind the ridge";
      EXPECT_GE(n.depth, -5.0) << ext << ": a node above the limit";
    }
    EXPECT_GT(plain_a, 100) << ext;
    // The open boundary is in the sea, west of the shelf; the box edges across plain A are land.
    ASSERT_FALSE(m.open.empty()) << ext;
    for (const auto& seg : m.open)
      for (const long id : seg) {
        EXPECT_LT(m.nodes[static_cast<std::size_t>(id)].lon, 10.0) << ext;
        EXPECT_GT(m.nodes[static_cast<std::size_t>(id)].depth, 0.0) << ext;
      }
    long land_on_plain_edges = 0;
    for (const auto& seg : m.land)
      for (const long id : seg) {
        const Node& n = m.nodes[static_cast<std::size_t>(id)];
        land_on_plain_edges += (n.lat == 2.0 || n.lat == 18.0) && n.lon > 10.4 ? 1 : 0;
      }
    EXPECT_GT(land_on_plain_edges, 20) << ext << ": the floodplain meets the box edges with land";
    // The west edge (820 m deep) is open with level-0 squares (1°) along its middle, not a node on
    // every pixel (65 at 0.25°; the model cleaning may take a corner triangle).
    long west = 0;
    for (const auto& seg : m.open)
      for (const long id : seg) west += m.nodes[static_cast<std::size_t>(id)].lon == 0.0 ? 1 : 0;
    EXPECT_GE(west, 15) << ext;
    EXPECT_LE(west, 30) << ext;
  }
  // The report: the floodplain (nodes as the text file has them, area of plain A within a pixel
  // column either side) and the time step with wetting and drying.
  const auto report = aq::test::read_report(dir, "coast");
  const std::vector<Node> text = read_text_nodes(dir / "coast.txt");
  const long above = std::count_if(text.begin(), text.end(), [](const Node& n) { return n.depth < 0.0; });
  ASSERT_TRUE(report.contains("floodplain")) << report.dump();
  EXPECT_EQ(report["floodplain"]["nodes"].get<long>(), above);
  EXPECT_GT(above, 100);
  EXPECT_DOUBLE_EQ(report["floodplain"]["top_m"].get<double>(), 5.0);
  const double area = report["floodplain"]["area_km2"].get<double>();
  const auto band = [](double dlon_deg) {
    const double radius = 6371.0072, d = std::numbers::pi / 180.0;
    return radius * radius * dlon_deg * d * (std::sin(18.0 * d) - std::sin(2.0 * d));
  };
  EXPECT_GT(area, band(3.45));  // 9.94..13.75°E: the 0 m line on the shelf to the last wet vertex, less the lake
  EXPECT_LT(area, band(4.0));
  EXPECT_GT(report["floodplain"]["land_boundary_nodes_above_datum"].get<long>(), 20);
  EXPECT_GT(report["mask"]["floodplain"]["floodplain_pixels"].get<long>(), 200);
  // The lake below the datum in plain A is reached only across the floodplain: counted and warned.
  // 1° x 2° of 0.25° pixels whose 4 vertices are below 0 m: 3 x 7 (the shore vertices interpolate).
  EXPECT_GE(report["mask"]["floodplain"]["inland_sea_pixels"].get<long>(), 15);
  EXPECT_LE(report["mask"]["floodplain"]["inland_sea_pixels"].get<long>(), 32);
  EXPECT_EQ(report["mask"]["floodplain"]["inland_sea_components"].get<long>(), 1);
  const auto box = report["mask"]["floodplain"]["inland_sea_box_deg"];
  EXPECT_GT(box[0].get<double>(), 11.5);
  EXPECT_LT(box[1].get<double>(), 12.5);
  EXPECT_GT(box[2].get<double>(), 9.0);
  EXPECT_LT(box[3].get<double>(), 11.0);
  ASSERT_TRUE(report["time_step"].contains("wetting_drying"));
  EXPECT_DOUBLE_EQ(report["time_step"]["wetting_drying"]["flood_level_m"].get<double>(), 5.0);
  EXPECT_LE(report["time_step"]["wetting_drying"]["max_stable_dt_s"].get<double>(),
            report["time_step"]["max_stable_dt_s"].get<double>());
  // The picture shows the plain in its class (mean elevation 2 m: "2-5 m", RGB 254 196 79).
  const aq::testing::PngPixels png = aq::testing::load_png_pixels(dir / "coast.png");
  long plain_pixels = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) plain_pixels += png.rgb(x, y) == std::array<int, 3>{254, 196, 79} ? 1 : 0;
  EXPECT_GT(plain_pixels, 1000);
}

TEST(SurgeCli, ALimitAboveTheRidgeReachesThePlainBehindIt) {
  const fs::path dir = aq::test::fresh_dir("surge", "h25");
  ASSERT_EQ(mesh_coast(dir, -25.0).exit_code, 0);
  const std::vector<Node> text = read_text_nodes(dir / "coast.txt");
  EXPECT_GT(count_if_nodes(text, 15.4, 18.6), 100);  // plain B, over the 20 m ridge
  EXPECT_EQ(count_if_nodes(text, 19.1, 25.0), 0);    // not the 50 m land
}

TEST(SurgeCli, AtTheDatumThereIsNoFloodplain) {
  const fs::path dir = aq::test::fresh_dir("surge", "h0");
  const auto r = mesh_coast(dir, 0.0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Model m = read_model(dir / "coast.14");
  ASSERT_TRUE(m.ok);
  for (const Node& n : m.nodes) {
    EXPECT_GE(n.depth, 0.0);
    EXPECT_LT(n.lon, 10.0);
  }
  const auto report = aq::test::read_report(dir, "coast");
  EXPECT_FALSE(report.contains("floodplain"));
  EXPECT_FALSE(report["time_step"].contains("wetting_drying"));
  EXPECT_FALSE(report["mask"].contains("floodplain"));
  // The text file's header line and UGRID's comment only for a floodplain.
  EXPECT_EQ(aq::test::slurp(dir / "coast.txt").find("# floodplain"), std::string::npos);
}

TEST(SurgeCli, OneAndTwoThreadsGiveTheSameBytes) {
  const fs::path one = aq::test::fresh_dir("surge", "t1"), two = aq::test::fresh_dir("surge", "t2");
  ASSERT_EQ(mesh_coast(one, -5.0, 1).exit_code, 0);
  ASSERT_EQ(mesh_coast(two, -5.0, 2).exit_code, 0);
  int files = 0;
  for (const auto& e : fs::directory_iterator(one)) {
    const std::string name = e.path().filename().string();
    if (name.ends_with("_report.json")) continue;
    ++files;
    EXPECT_EQ(aq::test::slurp(e.path()), aq::test::slurp(two / name)) << name;
  }
  EXPECT_EQ(files, 9);  // .14 .gr3 .ll _bctides.in .txt .nc .msh .vtu .png
  // The report's floodplain (summed in triangle order) too.
  EXPECT_EQ(aq::test::read_report(one, "coast")["floodplain"], aq::test::read_report(two, "coast")["floodplain"]);
}

double great_circle_km(const Node& a, const Node& b) {
  const double d = std::numbers::pi / 180.0;
  const double h = std::pow(std::sin((b.lat - a.lat) * d / 2), 2) +
                   std::cos(a.lat * d) * std::cos(b.lat * d) * std::pow(std::sin((b.lon - a.lon) * d / 2), 2);
  return 2.0 * 6371.0088 * std::asin(std::sqrt(h));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// configs/gulf_surge.toml on ETOPO5: the floodplain is there (nodes above the datum, none above the
// +10 m limit), the land boundary runs at the limit (on land above the datum, up to +10 m), the
// open boundary is in the sea and coarser than the coast, the time step is not set at the deep
// edge, and 1 and 2 threads write the same bytes.
TEST(SurgeCli, ShippedGulfSurgeConfig) {
  const fs::path one = aq::test::fresh_dir("surge", "gulf1"), two = aq::test::fresh_dir("surge", "gulf2");
  const std::string config = (fs::path(AQ_SOURCE_DIR) / "configs" / "gulf_surge.toml").string();
  const std::string formats = " --set 'output.formats=[\"fort14\", \"schism\", \"ugrid\", \"png\", \"text\"]'";
  const auto r1 = aq::test::run_command("OMP_NUM_THREADS=1 " + std::string(AQ_BINARY) + " mesh -q -c " + config +
                                        formats + " -o " + one.string());
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const auto r2 = aq::test::run_command("OMP_NUM_THREADS=2 " + std::string(AQ_BINARY) + " mesh -q -c " + config +
                                        formats + " -o " + two.string());
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const auto& e : fs::directory_iterator(one)) {
    const std::string name = e.path().filename().string();
    if (!name.ends_with("_report.json")) {
      EXPECT_EQ(aq::test::slurp(e.path()), aq::test::slurp(two / name)) << name;
    }
  }
  const Model m = read_model(one / "gulf_surge.14");
  ASSERT_TRUE(m.ok);
  long above = 0;
  for (const Node& n : m.nodes) {
    above += n.depth < 0.0 ? 1 : 0;
    EXPECT_GE(n.depth, -10.0) << "a node above the +10 m limit at " << n.lon << ", " << n.lat;
  }
  EXPECT_GT(above, 200);
  // The land boundary at the limit: no node above +10 m, most of them above the datum.
  std::vector<double> land_km, open_km;
  long land_nodes = 0, land_above = 0;
  for (const auto& seg : m.land)
    for (std::size_t k = 0; k < seg.size(); ++k) {
      const Node& n = m.nodes[static_cast<std::size_t>(seg[k])];
      ++land_nodes;
      land_above += n.depth < 0.0 ? 1 : 0;
      if (k + 1 < seg.size()) land_km.push_back(great_circle_km(n, m.nodes[static_cast<std::size_t>(seg[k + 1])]));
    }
  EXPECT_GT(static_cast<double>(land_above), 0.6 * static_cast<double>(land_nodes));
  ASSERT_EQ(m.open.size(), 1u);
  for (std::size_t k = 0; k < m.open[0].size(); ++k) {
    const Node& n = m.nodes[static_cast<std::size_t>(m.open[0][k])];
    EXPECT_GT(n.depth, 0.0) << "an open node on land at " << n.lon << ", " << n.lat;
    if (k + 1 < m.open[0].size())
      open_km.push_back(great_circle_km(n, m.nodes[static_cast<std::size_t>(m.open[0][k + 1])]));
  }
  // The open boundary follows the size field (the deep Gulf: level 0-1), the coast is at the finest level.
  EXPECT_GT(median(open_km), 2.0 * median(land_km))
      << "open " << median(open_km) << " km, land " << median(land_km) << " km";
  const auto report = aq::test::read_report(one, "gulf_surge");
  EXPECT_EQ(report["floodplain"]["top_m"].get<double>(), 10.0);
  EXPECT_GT(report["floodplain"]["nodes"].get<long>(), 200);
  EXPECT_GT(report["floodplain"]["area_km2"].get<double>(), 20000.0);
  EXPECT_LE(report["floodplain"]["highest_node_m"].get<double>(), 10.0);
  const auto& ts = report["time_step"];
  ASSERT_TRUE(ts.contains("wetting_drying"));
  EXPECT_GT(ts["wetting_drying"]["max_stable_dt_s"].get<double>(), 30.0);
  EXPECT_GT(ts["limiting_lat_deg"].get<double>(), 25.5) << "the time step is set at the deep open edge";
  EXPECT_LT(ts["limiting_lon_deg"].get<double>(), -84.5) << "the time step is set at the open edge";
}

TEST(SurgeCli, BadValuesAreRefusedAtLoadWithTheKeyAndTheRange) {
  const fs::path dir = aq::test::fresh_dir("surge", "bad");
  const struct {
    std::string set;
    std::vector<std::string> says;
  } cases[] = {
      {"--set mask.min_depth_m=-150", {"mask.min_depth_m", "-150 is outside [-100, 12000]"}},
      {"--set mask.min_depth_m=nan", {"mask.min_depth_m", "[-100, 12000]"}},
      {"--set mask.min_depth_m=-5 --set size.inland.h0_km=-1", {"size.inland.h0_km", "-1 is outside [0, 100000]"}},
      {"--set mask.min_depth_m=-5 --set size.inland.alpha=11", {"size.inland.alpha", "[0, 10]"}},
      {"--set mask.min_depth_m=-5 --set size.elevation.km_per_m=2000", {"size.elevation.km_per_m", "[0, 1000]"}},
      {"--set mask.min_depth_m=-5 --set size.elevation.h0_km=inf", {"size.elevation.h0_km", "[0, 100000]"}},
      {"--set size.inland.h0_km=5", {"size.inland.h0_km sizes the floodplain", "mask.min_depth_m = 0 >= 0"}},
      {"--set mask.min_depth_m=3 --set size.elevation.h0_km=5", {"size.elevation.h0_km", "mask.min_depth_m = 3"}},
      {"--set output.png_color=\\\"flood\\\"", {"output.png_color", "\"elevation\""}},
  };
  for (const auto& c : cases) {
    const auto r =
        aq::test::run_command(std::string(AQ_BINARY) + " mesh -q --set input.path=" + coast_raster().string() + " -o " +
                              dir.string() + " " + c.set);
    EXPECT_EQ(r.exit_code, 2) << c.set << "\n" << r.err;
    for (const std::string& s : c.says) EXPECT_NE(r.err.find(s), std::string::npos) << c.set << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << c.set << ": nothing is written";
  }
}

TEST(SurgeCli, BlocksRefuseAFloodplain) {
  const auto r =
      aq::test::run_command(std::string(AQ_BINARY) + " blocks -q --set input.path=" + coast_raster().string() +
                            " --set mask.min_depth_m=-5 -o " + aq::test::fresh_dir("surge", "blocks").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // Refused when the configuration is loaded, at the --set that gave it.
  EXPECT_NE(r.err.find("--set mask.min_depth_m=-5: mask.min_depth_m: mask.min_depth_m = -5 meshes a floodplain"),
            std::string::npos)
      << r.err;
}

}  // namespace

}  // namespace cli_surge_cli_test

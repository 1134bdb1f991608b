// Regional domains end to end (README "Regional FE meshes"): a synthetic basin whose box cuts the
// sea along a known edge, read back from fort.14 and hgrid.gr3 (open segment = exactly the mesh
// nodes on that edge, in order; land pieces and islands closed and oriented as ADCIRC and SCHISM
// need); a polygon equal to the box gives the same files; a box across the seam gives the same
// files however its longitudes are written; 1 and 2 threads give the same bytes; the seed's
// global run is unchanged.
#include <gdal_priv.h>
#include <unistd.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/msh_parse.hpp"
#include "support/run_command.hpp"

namespace cli_domain_cli_test {

namespace {

namespace fs = std::filesystem;

// Water (-1000 m) in the basin 2..28°E × 2..18°N with a 2° island at 6..8°E 8..10°N, and in a
// second basin across the seam (172°E..172°W, 30..40°N); land (+100 m) elsewhere. 0.25° cells.
double basin_elevation(double lon, double lat) {
  const bool basin = lon > 2.0 && lon < 28.0 && lat > 2.0 && lat < 18.0;
  const bool island = lon > 6.0 && lon < 8.0 && lat > 8.0 && lat < 10.0;
  const bool seam = (lon > 172.0 || lon < -172.0) && lat > 30.0 && lat < 40.0;
  return ((basin && !island) || seam) ? -1000.0 : 100.0;
}

fs::path basin_raster() {
  static const fs::path p = [] {
    const fs::path dir = aq::test::fresh_dir("domain", "raster");
    fs::create_directories(dir);
    const fs::path f = dir / "basin.tif";
    GDALAllRegister();
    const double step = 0.25;
    const int w = 1440, h = 720;
    GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(f.c_str(), w, h, 1, GDT_Float32, nullptr);
    double gt[6] = {-180.0, step, 0.0, 90.0, 0.0, -step};
    ds->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.importFromEPSG(4326);
    ds->SetSpatialRef(&srs);
    std::vector<float> buf(static_cast<std::size_t>(w) * h);
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c)
        buf[static_cast<std::size_t>(r) * w + c] =
            static_cast<float>(basin_elevation(-180.0 + (c + 0.5) * step, 90.0 - (r + 0.5) * step));
    EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, buf.data(), w, h, GDT_Float32, 0, 0, nullptr),
              CE_None);
    GDALClose(ds);
    return f;
  }();
  return p;
}

struct Segment {
  int type = 0;
  std::vector<long> nodes;
};

struct Fort14 {
  std::vector<double> lon, lat;
  std::vector<std::array<long, 3>> triangles;  // 0-based
  long elements = 0;
  long nope = -1, neta = -1, nbou = -1, nvel = -1;
  std::vector<Segment> open, land;
  std::string error;
};

// Reads a fort.14 / hgrid.gr3 (the same layout).
Fort14 read_fort14(const fs::path& p) {
  Fort14 f;
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  long ne = 0, np = 0;
  in >> ne >> np;
  f.elements = ne;
  for (long k = 0; k < np; ++k) {
    long id = 0;
    double x = 0, y = 0, d = 0;
    in >> id >> x >> y >> d;
    f.lon.push_back(x);
    f.lat.push_back(y);
  }
  for (long k = 0; k < ne; ++k) {
    long id = 0, n = 0, a = 0, b = 0, c = 0;
    in >> id >> n >> a >> b >> c;
    f.triangles.push_back({a - 1, b - 1, c - 1});
  }
  auto count_line = [&](long& v) {
    in >> v;
    std::getline(in, line);
  };
  count_line(f.nope);
  count_line(f.neta);
  for (long s = 0; s < f.nope; ++s) {
    Segment sg;
    long n = 0;
    count_line(n);
    for (long k = 0; k < n; ++k) {
      long id = 0;
      in >> id;
      sg.nodes.push_back(id - 1);
    }
    f.open.push_back(sg);
  }
  count_line(f.nbou);
  count_line(f.nvel);
  for (long s = 0; s < f.nbou; ++s) {
    Segment sg;
    long n = 0;
    in >> n >> sg.type;
    std::getline(in, line);
    for (long k = 0; k < n; ++k) {
      long id = 0;
      in >> id;
      sg.nodes.push_back(id - 1);
    }
    f.land.push_back(sg);
  }
  if (!in) f.error = "file ends early: " + p.string();
  return f;
}

// Every boundary edge of the triangles (an edge of one triangle only) joins two consecutive nodes
// of exactly one open or land segment, and every segment step is a boundary edge: the segments
// cover the boundary, as SCHISM needs ("Incomplete ball").
void expect_segments_cover_the_boundary(const Fort14& f) {
  std::map<std::pair<long, long>, int> count;
  for (const auto& t : f.triangles)
    for (int k = 0; k < 3; ++k) {
      const long a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  std::set<std::pair<long, long>> boundary, listed;
  for (const auto& [e, c] : count)
    if (c == 1) boundary.insert(e);
  for (const auto* list : {&f.open, &f.land})
    for (const Segment& sg : *list)
      for (std::size_t k = 0; k + 1 < sg.nodes.size(); ++k) {
        const std::pair<long, long> e{std::min(sg.nodes[k], sg.nodes[k + 1]), std::max(sg.nodes[k], sg.nodes[k + 1])};
        EXPECT_TRUE(boundary.count(e)) << "segment step " << e.first + 1 << "-" << e.second + 1 << " is no boundary edge";
        EXPECT_TRUE(listed.insert(e).second) << "edge " << e.first + 1 << "-" << e.second + 1 << " listed twice";
      }
  EXPECT_EQ(listed.size(), boundary.size());
}

double signed_area(const Fort14& f, const std::vector<long>& ring) {
  double a = 0.0;
  for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
    const auto i = static_cast<std::size_t>(ring[k]), j = static_cast<std::size_t>(ring[k + 1]);
    a += f.lon[i] * f.lat[j] - f.lon[j] * f.lat[i];
  }
  return 0.5 * a;
}

const std::string kFormats = "--set 'output.formats=[\"fort14\", \"schism\", \"msh\", \"ugrid\", \"fesom\"]'";

aq::test::CommandResult mesh_basin(const fs::path& dir, const std::string& domain, int threads = 2) {
  return aq::test::run_command("OMP_NUM_THREADS=" + std::to_string(threads) + " " + std::string(AQ_BINARY) +
                               " mesh -q --set input.path=" + basin_raster().string() +
                               " --set quadtree.step_deg=2.0 --set quadtree.levels=2 --set output.name=basin " +
                               kFormats + " -o " + dir.string() + " " + domain);
}

std::string bytes(const fs::path& p) { return aq::testing::read_file_bytes(p.string()); }

const std::string kBox = "--set 'domain.box=[0.0, 20.0, 0.0, 20.0]' --set 'mask.seeds=[[12.0, 12.0]]'";

TEST(DomainCli, BasinOpenEdgeIsExactlyTheWetNodesOnTheDomainEdgeInOrder) {
  const fs::path dir = aq::test::fresh_dir("domain", "basin");
  const auto r = mesh_basin(dir, kBox);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* ext : {".14", ".gr3"}) {
    const bool gr3 = std::string(ext) == ".gr3";
    const Fort14 f = read_fort14(dir / (std::string("basin") + ext));
    ASSERT_TRUE(f.error.empty()) << f.error;
    // One open segment: the east edge 20°E from 2°N to 18°N, going north (water on the left).
    ASSERT_EQ(f.nope, 1) << ext;
    expect_segments_cover_the_boundary(f);
    ASSERT_EQ(f.open.size(), 1u);
    std::vector<long> on_edge;
    for (std::size_t n = 0; n < f.lon.size(); ++n)
      if (f.lon[n] == 20.0) on_edge.push_back(static_cast<long>(n));
    std::sort(on_edge.begin(), on_edge.end(),
              [&](long a, long b) { return f.lat[static_cast<std::size_t>(a)] < f.lat[static_cast<std::size_t>(b)]; });
    EXPECT_EQ(f.open[0].nodes, on_edge) << ext;
    EXPECT_EQ(f.neta, static_cast<long>(on_edge.size()));
    ASSERT_FALSE(on_edge.empty());
    // From the south coast to the north coast (the model cleaning may take the corner triangle
    // there, whose two other edges are coast: then the segment ends one pixel inside).
    EXPECT_GE(f.lat[static_cast<std::size_t>(on_edge.front())], 2.0);
    EXPECT_LE(f.lat[static_cast<std::size_t>(on_edge.front())], 2.5);
    EXPECT_GE(f.lat[static_cast<std::size_t>(on_edge.back())], 17.5);
    EXPECT_LE(f.lat[static_cast<std::size_t>(on_edge.back())], 18.0);
    EXPECT_GE(on_edge.size(), 30u);
    // No node east of the domain edge: the water there is not meshed.
    for (const double x : f.lon) EXPECT_LE(x, 20.0);
    // Land: the mainland piece from the open segment's last node back to its first, and the
    // island, closed (first node repeated) and clockwise (water on the left).
    ASSERT_EQ(f.nbou, 2) << ext;
    long nvel = 0;
    for (const Segment& s : f.land) nvel += static_cast<long>(s.nodes.size());
    EXPECT_EQ(f.nvel, nvel);
    const Segment& main = f.land[0];
    const Segment& island = f.land[1];
    EXPECT_EQ(main.type, gr3 ? 0 : 20);
    EXPECT_EQ(island.type, gr3 ? 1 : 21);
    EXPECT_EQ(main.nodes.front(), f.open[0].nodes.back());
    EXPECT_EQ(main.nodes.back(), f.open[0].nodes.front());
    std::vector<long> outer = f.open[0].nodes;
    outer.insert(outer.end(), main.nodes.begin() + 1, main.nodes.end());
    EXPECT_GT(signed_area(f, outer), 0.0) << "the open + mainland loop is anticlockwise";
    ASSERT_GE(island.nodes.size(), 4u);
    EXPECT_EQ(island.nodes.front(), island.nodes.back());
    EXPECT_LT(signed_area(f, island.nodes), 0.0) << "an island is clockwise";
    for (const long n : island.nodes) {
      EXPECT_GE(f.lon[static_cast<std::size_t>(n)], 6.0);
      EXPECT_LE(f.lon[static_cast<std::size_t>(n)], 8.0);
    }
  }
  // bctides.in skeleton: one open boundary with the open segment's node count.
  std::ifstream bc(dir / "basin_bctides.in");
  std::string text((std::istreambuf_iterator<char>(bc)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("1 !nope"), std::string::npos) << text;
  const Fort14 f = read_fort14(dir / "basin.14");
  EXPECT_NE(text.find(std::to_string(f.open[0].nodes.size()) + " 3 0 0 0"), std::string::npos) << text;
  // The report's boundaries section.
  const auto report = aq::test::read_report(dir, "basin");
  EXPECT_EQ(report["boundaries"]["open_segments"], 1);
  EXPECT_EQ(report["boundaries"]["islands"], 1);
}

TEST(DomainCli, PolygonEqualToTheBoxGivesTheSameFiles) {
  const fs::path box = aq::test::fresh_dir("domain", "pbox"), poly = aq::test::fresh_dir("domain", "poly");
  ASSERT_EQ(mesh_basin(box, kBox).exit_code, 0);
  fs::create_directories(poly);
  const fs::path gj = poly.parent_path() / ("aq_domain_box_" + std::to_string(::getpid()) + ".geojson");
  std::ofstream(gj) << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "b"},
    "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [20, 0], [20, 20], [0, 20], [0, 0]]]}}]})";
  const auto r = mesh_basin(poly, "--set domain.polygon=" + gj.string() + " --set 'mask.seeds=[[12.0, 12.0]]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"basin.14", "basin.gr3", "basin.msh", "basin_bctides.in"})
    EXPECT_TRUE(bytes(box / f) == bytes(poly / f)) << f;
  // A polygon file that does not exist: exit 1 naming the key and the file, no outputs.
  const fs::path bad = aq::test::fresh_dir("domain", "badpoly");
  const auto b = mesh_basin(bad, "--set domain.polygon=/nonexistent/region.gpkg");
  EXPECT_EQ(b.exit_code, 1);
  EXPECT_NE(b.err.find("domain.polygon"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(bad / "basin.14"));
}

TEST(DomainCli, BoxAcrossTheSeamEqualsTheSameBoxShiftedBy360) {
  const std::string seed = " --set 'mask.seeds=[[179.0, 35.0]]'";
  const fs::path a = aq::test::fresh_dir("domain", "seam_a"), b = aq::test::fresh_dir("domain", "seam_b"),
                 c = aq::test::fresh_dir("domain", "seam_c");
  const auto ra = mesh_basin(a, "--set 'domain.box=[176.0, -176.0, 28.0, 42.0]'" + seed);
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  ASSERT_EQ(mesh_basin(b, "--set 'domain.box=[176.0, 184.0, 28.0, 42.0]'" + seed).exit_code, 0);
  ASSERT_EQ(mesh_basin(c, "--set 'domain.box=[-184.0, -176.0, 28.0, 42.0]'" + seed).exit_code, 0);
  for (const char* f : {"basin.14", "basin.gr3", "basin.msh"}) {
    EXPECT_TRUE(bytes(a / f) == bytes(b / f)) << f;
    EXPECT_TRUE(bytes(a / f) == bytes(c / f)) << f;
  }
  const Fort14 m = read_fort14(a / "basin.14");
  ASSERT_TRUE(m.error.empty());
  EXPECT_EQ(m.nope, 2);  // the west (176°E) and east (176°W) edges cut the sea
  for (std::size_t n = 0; n < m.lon.size(); ++n) EXPECT_GE(std::abs(m.lon[n]), 176.0) << n;
}

// A regional run reads each raster over the domain's box plus one level-0 square (issue 21): the
// report states the window (about 110 × 110 of the 1440 × 720
// cells at 0.25° around the 20° box: under 2 % of the raster's bytes), and the files equal those of a run on the raster cut to
// that window beforehand with gdal_translate (a raster whose extent is the window). Across the
// seam the window is read in two pieces (BoxAcrossTheSeamEqualsTheSameBoxShiftedBy360).
TEST(DomainCli, RegionalRunReadsOnlyTheDomainWindowAndEqualsAPreCutRaster) {
  const fs::path dir = aq::test::fresh_dir("domain", "window"), cut = aq::test::fresh_dir("domain", "window_cut");
  ASSERT_EQ(mesh_basin(dir, kBox).exit_code, 0);
  const nlohmann::json rep = aq::test::read_report(dir, "basin");
  ASSERT_TRUE(rep.contains("raster_windows")) << rep.dump();
  ASSERT_EQ(rep["raster_windows"].size(), 1U);
  const auto& w = rep["raster_windows"][0];
  const std::int64_t cols = w["columns"], rows = w["rows"], c0 = w["first_column"], r0 = w["first_row"];
  // Box 0..20°E (snapped to 2° squares: 0..20), 0..20°N; margin 2° + 2 pixels (0.5°) + 3/4 cells.
  EXPECT_GE(cols, 104);  // 80 cells of the box and 12 of margin (2° square + 2 pixels) each side
  EXPECT_LE(cols, 114);
  EXPECT_GE(rows, 104);
  EXPECT_LE(rows, 114);
  EXPECT_EQ(w["bytes"].get<std::int64_t>(), cols * rows * 4);
  EXPECT_LT(w["bytes"].get<std::int64_t>(), 1440 * 720 * 4 / 50);
  // The same window cut beforehand (normalised row r0 from the south = stored row 720 - r0 - rows).
  fs::create_directories(cut);
  const fs::path pre = cut / "basin_cut.tif";
  const auto t = aq::test::run_command("gdal_translate -q -srcwin " + std::to_string(c0) + " " +
                                       std::to_string(720 - r0 - rows) + " " + std::to_string(cols) + " " +
                                       std::to_string(rows) + " " + basin_raster().string() + " " + pre.string());
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const auto r = aq::test::run_command(std::string(AQ_BINARY) + " mesh -q --set input.path=" + pre.string() +
                                       " --set quadtree.step_deg=2.0 --set quadtree.levels=2 --set output.name=basin " +
                                       kFormats + " -o " + cut.string() + " " + kBox);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Byte for byte after the first line (fort.14, hgrid.gr3 and bctides.in name the raster there).
  const auto body = [](const std::string& b) { return b.substr(std::min(b.size(), b.find('\n'))); };
  EXPECT_TRUE(bytes(dir / "basin.msh") == bytes(cut / "basin.msh"));
  for (const char* f : {"basin.14", "basin.gr3", "basin_bctides.in"}) {
    EXPECT_GT(bytes(dir / f).size(), 500U) << f;
    EXPECT_TRUE(body(bytes(dir / f)) == body(bytes(cut / f))) << f;
  }
}

TEST(DomainCli, OneAndTwoThreadsGiveTheSameBytes) {
  const fs::path one = aq::test::fresh_dir("domain", "t1"), two = aq::test::fresh_dir("domain", "t2");
  ASSERT_EQ(mesh_basin(one, kBox, 1).exit_code, 0);
  ASSERT_EQ(mesh_basin(two, kBox, 2).exit_code, 0);
  for (const char* f : {"basin.14", "basin.gr3", "basin.msh", "basin.nc", "basin_nod2d.out", "basin_bctides.in"})
    EXPECT_TRUE(bytes(one / f) == bytes(two / f)) << f;
}

TEST(DomainCli, NorthSeaAndGulfConfigsGiveOpenBoundaries) {
  for (const char* name : {"north_sea", "gulf_of_mexico_fe"}) {
    const fs::path dir = aq::test::fresh_dir("domain", name);
    const auto r = aq::test::run_aquatoria("mesh -q -c " + std::string(AQ_SOURCE_DIR) + "/configs/" + name +
                                           ".toml -o " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Fort14 f = read_fort14(dir / (std::string(name) + ".14"));
    ASSERT_TRUE(f.error.empty()) << f.error;
    EXPECT_EQ(f.nope, 2) << name;
    expect_segments_cover_the_boundary(f);
    EXPECT_GT(f.neta, 20) << name;
    EXPECT_LT(f.lon.size(), 5000u) << name;  // small enough for the client runs
    for (const Segment& s : f.land) EXPECT_TRUE(s.type == 20 || s.type == 21) << name;
  }
}

TEST(DomainCli, MercatorLatticeAndRotatedBoxHaveTheOpenEdge) {
  // The Mercator lattice (its caps are wet in this raster: a region does not need them dry) and
  // a rotated lattice (the box is then the pixels whose centre is in it).
  for (const std::string extra : {"--set quadtree.lattice=mercator", "--set rotation.enabled=true"}) {
    const fs::path dir = aq::test::fresh_dir("domain", extra.find("mercator") != std::string::npos ? "merc" : "rot");
    const auto r = mesh_basin(dir, kBox + " " + extra);
    ASSERT_EQ(r.exit_code, 0) << extra << ": " << r.err;
    const Fort14 f = read_fort14(dir / "basin.14");
    ASSERT_TRUE(f.error.empty()) << f.error;
    EXPECT_GE(f.nope, 1) << extra;
    for (const Segment& s : f.open)
      for (const long n : s.nodes) EXPECT_NEAR(f.lon[static_cast<std::size_t>(n)], 20.0, 0.6) << extra;
    for (const double x : f.lon) EXPECT_LE(x, 20.6) << extra;
  }
  // A polygon on a rotated lattice is refused (exit 2) naming the keys.
  const fs::path dir = aq::test::fresh_dir("domain", "rotpoly");
  const auto r = mesh_basin(dir, "--set domain.polygon=x.geojson --set rotation.enabled=true");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("domain.polygon"), std::string::npos) << r.err;
}

TEST(DomainCli, BadDomainKeysAreConfigErrors) {
  const fs::path dir = aq::test::fresh_dir("domain", "bad");
  auto r = mesh_basin(dir, "--set 'domain.box=[0.0, 20.0, 30.0, 20.0]'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("domain.box"), std::string::npos) << r.err;
  r = mesh_basin(dir, "--set domain.kind=polygon");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("domain.kind"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "basin.14"));
}

TEST(DomainCli, GlobalSeedRunIsUnchanged) {
  const fs::path base = "/work/baseline/out";
  if (!fs::exists(base / "seed_4deg_L3.14")) GTEST_SKIP() << "no baseline outputs in " << base;
  const fs::path dir = aq::test::fresh_dir("domain", "seed");
  ASSERT_EQ(aq::test::run_aquatoria("mesh -q -o " + dir.string()).exit_code, 0);
  for (const char* f : {"seed_4deg_L3.14", "seed_4deg_L3.msh", "seed_4deg_L3.nc", "seed_4deg_L3.txt"})
    EXPECT_TRUE(bytes(base / f) == bytes(dir / f)) << f;
}

}  // namespace

}  // namespace cli_domain_cli_test

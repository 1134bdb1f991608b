// SPDX-License-Identifier: GPL-3.0-or-later
// Regional domains end to end (README "Regional FE meshes"): a synthetic basin whose box cuts the
// sea along a known edge, read back from fort.14 and hgrid.gr3 (open segment = exactly the mesh
// nodes on that edge, in order, as coarse as the water's levels there; land pieces and islands closed and oriented as
// ADCIRC and SCHISM need); a polygon equal to the box gives the same files; a box across the seam gives the same files
// however its longitudes are written; 1 and 2 threads give the same bytes; the seed's global run is unchanged.
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
#include "support/fort14_read.hpp"
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

using aq::test::Fort14;
using aq::test::read_fort14;
using Segment = Fort14::Segment;

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

// `env` is prepended to the command (AQ_GLOBAL_LATTICE=1: the regional run on the global lattice).
aq::test::CommandResult mesh_basin(const fs::path& dir, const std::string& domain, int threads = 2,
                                   const std::string& env = "") {
  return aq::test::run_command(env + "OMP_NUM_THREADS=" + std::to_string(threads) + " " + std::string(AQ_BINARY) +
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
    // The open edge is no coast (mask/coast.hpp): it takes the levels of the water there, level-0
    // squares (2°) along the middle of the edge, the coastal band's pixels (0.5°) only near the
    // coasts at its ends (it was 33 nodes, every pixel, while the edge counted as coast).
    EXPECT_LT(on_edge.size(), 20u);
    EXPECT_GE(on_edge.size(), 9u);
    int coarse_steps = 0;
    for (std::size_t k = 0; k + 1 < on_edge.size(); ++k)
      coarse_steps +=
          f.lat[static_cast<std::size_t>(on_edge[k + 1])] - f.lat[static_cast<std::size_t>(on_edge[k])] == 2.0;
    EXPECT_GE(coarse_steps, 4);
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

// The basin cut by a polygon with a slanted east edge, (20°E, 0°N) -> (24°E, 20°N): the open
// boundary next to it is a staircase on the 0.5° lattice.
fs::path slant_polygon() {
  static const fs::path p = [] {
    const fs::path dir = aq::test::fresh_dir("domain", "slant_polygon");
    fs::create_directories(dir);
    const fs::path f = dir / "slant.geojson";
    std::ofstream(f) << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "s"},
      "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [20, 0], [24, 20], [0, 20], [0, 0]]]}}]})";
    return f;
  }();
  return p;
}

// Distance (degrees, in the lon/lat plane) of (x, y) from the slanted edge's segment.
double slant_distance(double x, double y) {
  const double ax = 20.0, ay = 0.0, ux = 4.0, uy = 20.0;
  const double t = std::clamp(((x - ax) * ux + (y - ay) * uy) / (ux * ux + uy * uy), 0.0, 1.0);
  return std::hypot(x - (ax + t * ux), y - (ay + t * uy));
}

bool on_half_degree_lattice(double x, double y) {
  return std::abs(2.0 * x - std::round(2.0 * x)) < 1e-9 && std::abs(2.0 * y - std::round(2.0 * y)) < 1e-9;
}

TEST(DomainCli, OneAndTwoThreadsGiveTheSameBytes) {
  const fs::path one = aq::test::fresh_dir("domain", "t1"), two = aq::test::fresh_dir("domain", "t2");
  ASSERT_EQ(mesh_basin(one, kBox, 1).exit_code, 0);
  ASSERT_EQ(mesh_basin(two, kBox, 2).exit_code, 0);
  for (const char* f : {"basin.14", "basin.gr3", "basin.msh", "basin.nc", "basin_nod2d.out", "basin_bctides.in"})
    EXPECT_TRUE(bytes(one / f) == bytes(two / f)) << f;
}

TEST(DomainCli, PolygonWithMovedOpenNodesOneAndTwoThreadsGiveTheSameBytes) {
  const fs::path one = aq::test::fresh_dir("domain", "pt1"), two = aq::test::fresh_dir("domain", "pt2");
  const std::string poly = "--set domain.polygon=" + slant_polygon().string() + " --set 'mask.seeds=[[12.0, 12.0]]'";
  ASSERT_EQ(mesh_basin(one, poly, 1).exit_code, 0);
  ASSERT_EQ(mesh_basin(two, poly, 2).exit_code, 0);
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
    EXPECT_EQ(f.nope, std::string(name) == "north_sea" ? 3 : 2)
        << name;  // north_sea: Celtic Sea, Atlantic north of Ireland, Skagerrak
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
}

// Open nodes moved onto the polygon (README "Regional FE meshes"): every node of the open
// boundary is on the polygon (moved, or on it already) or on its lattice vertex (kept), with the
// counts the report states; every triangle stays anticlockwise, no angle below the 20° bound;
// MSH (the lattice plane) and fort.14 / hgrid.gr3 (lon/lat) hold the same moved positions.
TEST(DomainCli, PolygonOpenNodesMoveOntoTheSlantedEdgeWhereTrianglesStayValid) {
  const fs::path dir = aq::test::fresh_dir("domain", "slant");
  const auto r = mesh_basin(dir, "--set domain.polygon=" + slant_polygon().string() + " --set 'mask.seeds=[[12.0, 12.0]]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = aq::test::read_report(dir, "basin");
  ASSERT_TRUE(report.contains("open_boundary_snap")) << report.dump();
  const auto& snap = report["open_boundary_snap"];
  const long open_nodes = snap["open_nodes"], moved = snap["moved"], on_polygon = snap["on_polygon"], kept = snap["kept"];
  EXPECT_EQ(open_nodes, moved + on_polygon + kept);
  EXPECT_GE(moved, 15);   // the staircase's nodes off the edge
  EXPECT_GE(kept, 1);     // a step whose two nodes would make a sliver
  EXPECT_GT(snap["max_move_km"].get<double>(), 5.0);
  EXPECT_LT(snap["max_move_km"].get<double>(), 40.0);  // under a pixel diagonal's half (0.35° ≈ 39 km)
  EXPECT_GE(report["quality"]["min_angle_deg"]["p0"].get<double>(), 20.0);
  EXPECT_EQ(report["quality"]["max_angle_above_120_deg_triangles"], 0);

  // MSH: the nodes of the "open" curves (physical group 4), in the λ–φ plane.
  const auto msh = aq::testing::parse_msh(dir / "basin.msh");
  std::set<std::size_t> open_tags;
  for (const auto& e : msh.elements) {
    if (e.dim != 1) continue;
    const auto it = msh.entity_physicals.find({1, e.entity});
    if (it == msh.entity_physicals.end() || std::find(it->second.begin(), it->second.end(), 4) == it->second.end())
      continue;
    open_tags.insert(e.nodes.begin(), e.nodes.end());
  }
  EXPECT_EQ(static_cast<long>(open_tags.size()), open_nodes);
  long on_moved = 0, on_lattice_on_polygon = 0, off = 0;
  std::vector<std::array<double, 2>> moved_xy;
  for (const std::size_t t : open_tags) {
    const auto& x = msh.nodes.at(t);
    const bool on = slant_distance(x[0], x[1]) < 1e-9, lattice = on_half_degree_lattice(x[0], x[1]);
    EXPECT_TRUE(on || lattice) << "open node " << t << " at " << x[0] << ", " << x[1] << " is neither";
    if (on && !lattice) {
      ++on_moved;
      moved_xy.push_back({x[0], x[1]});
    }
    if (on && lattice) ++on_lattice_on_polygon;
    if (!on) ++off;
  }
  EXPECT_EQ(on_moved, moved);
  EXPECT_EQ(on_lattice_on_polygon, on_polygon);
  EXPECT_EQ(off, kept);
  for (const auto& e : msh.elements) {
    if (e.type != 2) continue;
    const auto &a = msh.nodes.at(e.nodes[0]), &b = msh.nodes.at(e.nodes[1]), &c = msh.nodes.at(e.nodes[2]);
    EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0.0) << "MSH triangle " << e.tag;
  }
  // fort.14 and hgrid.gr3: the same moved positions, anticlockwise triangles, open nodes on the
  // polygon or on the lattice.
  for (const char* ext : {".14", ".gr3"}) {
    const Fort14 f = read_fort14(dir / (std::string("basin") + ext));
    ASSERT_TRUE(f.error.empty()) << f.error;
    expect_segments_cover_the_boundary(f);
    for (const auto& t : f.triangles) {
      const auto a = static_cast<std::size_t>(t[0]), b = static_cast<std::size_t>(t[1]), c = static_cast<std::size_t>(t[2]);
      EXPECT_GT((f.lon[b] - f.lon[a]) * (f.lat[c] - f.lat[a]) - (f.lat[b] - f.lat[a]) * (f.lon[c] - f.lon[a]), 0.0) << ext;
    }
    long moved_here = 0;
    for (std::size_t n = 0; n < f.lon.size(); ++n) {
      if (on_half_degree_lattice(f.lon[n], f.lat[n])) continue;
      ++moved_here;
      EXPECT_LT(slant_distance(f.lon[n], f.lat[n]), 1e-9) << ext << " node " << n + 1 << " is off the lattice and off the polygon";
      bool in_msh = false;
      for (const auto& xy : moved_xy)
        in_msh = in_msh || (std::abs(xy[0] - f.lon[n]) < 1e-12 && std::abs(xy[1] - f.lat[n]) < 1e-12);
      EXPECT_TRUE(in_msh) << ext << " node " << n + 1 << " is not where MSH has it";
    }
    EXPECT_GE(moved_here, moved - 2) << ext;  // the model cleaning may take a corner triangle
    for (const Segment& s : f.open)
      for (const long n : s.nodes) {
        const auto p = static_cast<std::size_t>(n);
        EXPECT_TRUE(slant_distance(f.lon[p], f.lat[p]) < 1e-9 || on_half_degree_lattice(f.lon[p], f.lat[p])) << ext;
      }
  }
}

// A polygon on a rotated lattice: the pixels whose centre's geographic position is inside; the
// open boundary runs along the slanted edge (and moves onto it) and nothing lies east of it.
TEST(DomainCli, PolygonOnARotatedLattice) {
  const fs::path dir = aq::test::fresh_dir("domain", "rotpoly");
  const auto r = mesh_basin(dir, "--set domain.polygon=" + slant_polygon().string() +
                                     " --set 'mask.seeds=[[12.0, 12.0]]' --set rotation.enabled=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Fort14 f = read_fort14(dir / "basin.14");
  ASSERT_TRUE(f.error.empty()) << f.error;
  EXPECT_EQ(f.nope, 1);
  expect_segments_cover_the_boundary(f);
  double lat_lo = 90.0, lat_hi = -90.0;
  for (const Segment& s : f.open)
    for (const long n : s.nodes) {
      const auto p = static_cast<std::size_t>(n);
      EXPECT_LT(slant_distance(f.lon[p], f.lat[p]), 0.45) << "open node " << n + 1;
      lat_lo = std::min(lat_lo, f.lat[p]);
      lat_hi = std::max(lat_hi, f.lat[p]);
    }
  EXPECT_LT(lat_lo, 3.5);
  EXPECT_GT(lat_hi, 17.0);
  // Nothing east of the edge by more than a pixel's half diagonal (0.5° rotated pixels).
  for (std::size_t n = 0; n < f.lon.size(); ++n) {
    const double east = (f.lon[n] - (20.0 + f.lat[n] / 5.0)) * std::cos(std::atan(0.2));
    EXPECT_LT(east, 0.45) << "node " << n + 1 << " at " << f.lon[n] << ", " << f.lat[n];
  }
  const auto report = aq::test::read_report(dir, "basin");
  EXPECT_GE(report["open_boundary_snap"]["moved"].get<long>(), 10);
  EXPECT_NE(report["domain"].dump().find("rotated lattice"), std::string::npos) << report["domain"].dump();
}

// A region reaching a pole row (a box up to 90°N in the Arctic): the geographic mesh merges the
// pole row, and its files keep the boundary types (open segments, mainland / island, bctides,
// FESOM's open-boundary nodes).
TEST(DomainCli, RegionReachingAPoleRowKeepsItsBoundaryTypes) {
  const fs::path dir = aq::test::fresh_dir("domain", "arctic");
  const auto r = aq::test::run_command(std::string(AQ_BINARY) + " mesh -q --set input.path=" + AQ_ETOPO_DIR +
                                       "/etopo20.cdf --set quadtree.step_deg=2.0 --set quadtree.levels=2 "
                                       "--set output.name=arc " + kFormats + " -o " + dir.string() +
                                       " --set 'domain.box=[0.0, 60.0, 80.0, 90.0]' --set 'mask.seeds=[[30.0, 85.0]]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* ext : {".14", ".gr3"}) {
    const Fort14 f = read_fort14(dir / (std::string("arc") + ext));
    ASSERT_TRUE(f.error.empty()) << f.error;
    EXPECT_GE(f.nope, 1) << ext;
    EXPECT_GE(f.neta, 40) << ext;
    expect_segments_cover_the_boundary(f);
    const bool gr3 = std::string(ext) == ".gr3";
    for (const Segment& s : f.land) EXPECT_TRUE(gr3 ? (s.type == 0 || s.type == 1) : (s.type == 20 || s.type == 21));
  }
  EXPECT_TRUE(fs::exists(dir / "arc_bctides.in"));
  EXPECT_TRUE(fs::exists(dir / "arc_obn.out"));
}

// The window lattice (README "Regional FE meshes", "What scales with the region"): a regional run
// works on the domain's box and one level-0 square of padding, not on the globe, and writes the
// same mesh files as the same run on the global lattice (AQ_GLOBAL_LATTICE=1), on both lattice
// kinds, for a box and a polygon; the report states the window.
TEST(DomainCli, WindowLatticeGivesTheSameFilesAsTheGlobalLattice) {
  const fs::path gj = aq::test::fresh_dir("domain", "wpoly_file");
  fs::create_directories(gj);
  std::ofstream(gj / "poly.geojson") << R"({"type": "FeatureCollection", "features": [{"type": "Feature",
    "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[[1, 1], [19.3, 3], [17, 19], [3, 15], [1, 1]]]}}]})";
  const std::string poly = "--set domain.polygon=" + (gj / "poly.geojson").string() + " --set 'mask.seeds=[[12.0, 12.0]]'";
  struct Case {
    const char* name;
    std::string args;
  };
  for (const Case& c : {Case{"box", kBox}, Case{"merc", kBox + " --set quadtree.lattice=mercator"}, Case{"poly", poly},
                        Case{"mpoly", poly + " --set quadtree.lattice=mercator"}}) {
    const fs::path w = aq::test::fresh_dir("domain", std::string("wl_") + c.name),
                   g = aq::test::fresh_dir("domain", std::string("gl_") + c.name);
    const std::string args =
        c.args + " --set 'output.formats=[\"fort14\", \"schism\", \"msh\", \"ugrid\", \"fesom\", \"png\"]'";
    const auto rw = mesh_basin(w, args);
    ASSERT_EQ(rw.exit_code, 0) << c.name << ": " << rw.err;
    const auto rg = mesh_basin(g, args, 2, "AQ_GLOBAL_LATTICE=1 ");
    ASSERT_EQ(rg.exit_code, 0) << c.name << ": " << rg.err;
    for (const char* f : {"basin.14", "basin.gr3", "basin.msh", "basin.nc", "basin_nod2d.out", "basin_elem2d.out",
                          "basin_obn.out", "basin_bctides.in", "basin.png"}) {
      EXPECT_GT(bytes(w / f).size(), 0U) << c.name << " " << f;
      EXPECT_TRUE(bytes(w / f) == bytes(g / f)) << c.name << " " << f;
    }
    const nlohmann::json rep = aq::test::read_report(w, "basin");
    ASSERT_TRUE(rep["lattice"].contains("window")) << c.name << ": " << rep["lattice"].dump();
    const auto& win = rep["lattice"]["window"];
    // 2° squares of 0.5° pixels: the box 0..20° (the polygon's bounding box 1..19.3 × 1..19,
    // snapped outward: the same) and one square each side.
    EXPECT_EQ(win["nx"], 48) << c.name;
    EXPECT_EQ(win["first_column"], 356) << c.name;  // (-2 + 180) / 0.5
    EXPECT_EQ(win["lon_min_deg"], -2.0) << c.name;
    EXPECT_EQ(win["lon_max_deg"], 22.0) << c.name;
    EXPECT_EQ(rep["lattice"]["nx"], 720) << c.name;  // the global lattice's
    if (std::string(c.name) == "box" || std::string(c.name) == "poly") {
      EXPECT_EQ(win["ny"], 48) << c.name;
      EXPECT_EQ(win["first_row"], 176) << c.name;  // (-2 + 90) / 0.5
      EXPECT_EQ(win["lat_min_deg"], -2.0) << c.name;
      EXPECT_EQ(win["lat_max_deg"], 22.0) << c.name;
    } else {  // Mercator rows: the box's snapped rows and one 2° square of ordinate each side
      EXPECT_GT(win["ny"].get<int>(), 40) << c.name;
      EXPECT_LE(win["lat_min_deg"].get<double>(), -1.9) << c.name;
      EXPECT_GE(win["lat_max_deg"].get<double>(), 20.5) << c.name;
    }
    EXPECT_EQ(win["pixels"].get<std::int64_t>(), win["nx"].get<std::int64_t>() * win["ny"].get<std::int64_t>());
    EXPECT_LT(rep["memory"]["estimate_lattice_bytes"].get<std::int64_t>(), 20000) << c.name;  // the globe's: ~0.5 MB
    EXPECT_FALSE(aq::test::read_report(g, "basin")["lattice"].contains("window")) << c.name;
  }
}

// Across the seam the window is one contiguous block: the same files as the global lattice whose
// seam (quadtree.lon0_deg) is away from the box.
TEST(DomainCli, WindowLatticeAcrossTheSeamEqualsTheGlobalLatticeWithTheSeamElsewhere) {
  const std::string box = "--set 'domain.box=[176.0, -176.0, 28.0, 42.0]' --set 'mask.seeds=[[179.0, 35.0]]'";
  for (const std::string kind : {"lonlat", "mercator"}) {
    const fs::path w = aq::test::fresh_dir("domain", "wseam_" + kind), g = aq::test::fresh_dir("domain", "gseam_" + kind);
    const std::string args = box + " --set quadtree.lattice=" + kind;
    const auto rw = mesh_basin(w, args);
    ASSERT_EQ(rw.exit_code, 0) << rw.err;
    const auto rg = mesh_basin(g, args + " --set quadtree.lon0_deg=0.0", 2, "AQ_GLOBAL_LATTICE=1 ");
    ASSERT_EQ(rg.exit_code, 0) << rg.err;
    for (const char* f : {"basin.14", "basin.gr3", "basin.msh", "basin_nod2d.out", "basin_elem2d.out"}) {
      EXPECT_GT(bytes(w / f).size(), 500U) << kind << " " << f;
      EXPECT_TRUE(bytes(w / f) == bytes(g / f)) << kind << " " << f;
    }
    const nlohmann::json rep = aq::test::read_report(w, "basin");
    ASSERT_TRUE(rep["lattice"].contains("window")) << rep["lattice"].dump();
    EXPECT_EQ(rep["lattice"]["window"]["nx"], 24);                 // 176..184 and 2° each side
    EXPECT_EQ(rep["lattice"]["window"]["lon_min_deg"], 174.0);     // west of the seam
    EXPECT_EQ(rep["lattice"]["window"]["lon_max_deg"], 186.0);     // contiguous past it
    EXPECT_EQ(rep["lattice"]["window"]["first_column"], 708);      // (174 + 180) / 0.5
  }
}

// A box on a rotated lattice keeps the global lattice (its box is no lattice rectangle) but reads
// the raster only over the geographic box of the rotated region and its margin, and writes the
// same files (the picture too) as when the raster is read whole (AQ_RASTER_WHOLE=1).
TEST(DomainCli, RotatedBoxReadsARasterWindowAndGivesTheSameFiles) {
  const fs::path w = aq::test::fresh_dir("domain", "rotw"), g = aq::test::fresh_dir("domain", "rotg");
  const std::string args =
      kBox + " --set rotation.enabled=true --set 'output.formats=[\"fort14\", \"schism\", \"msh\", \"png\"]'";
  const auto rw = mesh_basin(w, args);
  ASSERT_EQ(rw.exit_code, 0) << rw.err;
  const auto rg = mesh_basin(g, args, 2, "AQ_RASTER_WHOLE=1 ");
  ASSERT_EQ(rg.exit_code, 0) << rg.err;
  for (const char* f : {"basin.14", "basin.gr3", "basin.msh", "basin_bctides.in", "basin.png"}) {
    EXPECT_GT(bytes(w / f).size(), 100U) << f;
    EXPECT_TRUE(bytes(w / f) == bytes(g / f)) << f;
  }
  const nlohmann::json rep = aq::test::read_report(w, "basin");
  ASSERT_TRUE(rep.contains("raster_windows")) << rep.dump();
  EXPECT_LT(rep["raster_windows"][0]["bytes"].get<std::int64_t>(), 1440 * 720 * 4 / 10);
  EXPECT_EQ(rep["lattice"]["global_because"], "rotation.enabled = true: the rotated lattice's box is no lon/lat box");
  EXPECT_FALSE(aq::test::read_report(g, "basin").contains("raster_windows"));
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

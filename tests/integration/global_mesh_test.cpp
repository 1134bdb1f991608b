// SPDX-License-Identifier: GPL-3.0-or-later
// The global discretizer end to end on the real ETOPO5 (ferret-datasets), through the
// `aquatoria mesh` command as a user runs it: counts against the seed and an independent
// implementation, whole-mesh invariants from the report, determinism across 1 and 2 threads,
// the rotated pole, and real clients (gmsh, VTK, ncdump, CDO) reading the real files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <netcdf.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>
#include <vector>

#include "support/run_command.hpp"
#include "support/ugrid_read.hpp"

namespace integration_global_mesh_test {

namespace fs = std::filesystem;
using aq::test::run_command;
using nlohmann::json;

namespace {

struct Run {
  fs::path dir;
  json report;
};

// Runs `aquatoria mesh` once per distinct argument string (cached across tests).
const Run& mesh_run(const std::string& args, int threads = 2) {
  static std::map<std::string, Run> cache;
  const std::string key = args + "#" + std::to_string(threads);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const fs::path dir =
      fs::temp_directory_path() / ("aq_global_" + std::to_string(cache.size()) + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto r = run_command("OMP_NUM_THREADS=" + std::to_string(threads) + " " + AQ_BINARY + " mesh -q -o " +
                             dir.string() + " " + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  Run run;
  run.dir = dir;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().string().ends_with("_report.json")) run.report = json::parse(std::ifstream(e.path()));
  return cache.emplace(key, run).first->second;
}

std::map<std::string, std::string> checksums(const json& report) {
  std::map<std::string, std::string> m;
  for (const auto& o : report.at("outputs")) m[o.at("file")] = o.at("checksum_xxh64");
  return m;
}

void expect_invariants(const json& r) {
  const auto& s = r.at("statistics");
  EXPECT_TRUE(s.at("euler").at("ok").get<bool>()) << s.at("euler");
  EXPECT_EQ(s.at("euler").at("v_minus_e_plus_f"), s.at("euler").at("expected_2c_minus_b_minus_p"));
  EXPECT_EQ(s.at("conforming").at("bad_edges"), 0);
  EXPECT_EQ(s.at("conforming").at("boundary_mismatch"), 0);
  EXPECT_EQ(s.at("right_isosceles").at("not_right_isosceles"), 0);
  EXPECT_EQ(s.at("right_isosceles").at("clockwise_or_degenerate"), 0);
  // Total triangle area = filled area, exactly in lattice units.
  EXPECT_EQ(s.at("area").at("triangles_px2").get<double>(), s.at("area").at("filled_px2").get<double>());
  EXPECT_EQ(s.at("area").at("filled_px2").get<std::int64_t>(),
            r.at("mask").at("fill").at("filled_pixels_final").get<std::int64_t>());
  // Geodesic triangles vs lattice cells on WGS84 (authalic sphere cells when rotated): a boundary
  // effect of first order in the pixel size, 5e-7 plain and 4e-4 rotated at 0.5° pixels.
  EXPECT_LT(s.at("area").at("relative_difference").get<double>(), 1e-3);
}

}  // namespace

// The seed's reference parameters (Δ0 = 4°, L = 3, K = 2, h = 0). The seed (ETOPO2) has 65777
// triangles / 36834 nodes; an independent implementation on ETOPO5 got 64965 / 36237. Ours must be
// within 2% of the latter (the filled set depends on the details of h = 0 sampling) and 3% of the seed.
TEST(GlobalMeshEtopo5, SeedReferenceCountsAndInvariants) {
  const auto& run = mesh_run("");
  const auto& c = run.report.at("mesh_counts");
  const double tri = c.at("triangles").get<double>(), nodes = c.at("nodes").get<double>();
  EXPECT_NEAR(tri / 64965.0, 1.0, 0.02);
  EXPECT_NEAR(nodes / 36237.0, 1.0, 0.02);
  EXPECT_NEAR(tri / 65777.0, 1.0, 0.03);
  EXPECT_NEAR(nodes / 36834.0, 1.0, 0.03);
  EXPECT_EQ(run.report.at("seed_reference").at("triangles"), 65777);
  expect_invariants(run.report);
  // Squares with midside nodes on all four sides occur, so the table needs all 16 codes.
  EXPECT_GT(c.at("squares").get<int>(), 25000);
}

TEST(GlobalMeshEtopo5, BareDlRuleGivesAboutHalf) {
  const auto& run = mesh_run("--set quadtree.coast_band=0");
  const auto& c = run.report.at("mesh_counts");
  EXPECT_NEAR(c.at("triangles").get<double>() / 35999.0, 1.0, 0.02);
  EXPECT_NEAR(c.at("nodes").get<double>() / 21198.0, 1.0, 0.02);
  expect_invariants(run.report);
}

TEST(GlobalMeshEtopo5, OutputsAreBitIdenticalForOneAndTwoThreads) {
  const auto& one = mesh_run("", 1);
  const auto& two = mesh_run("", 2);
  const auto a = checksums(one.report), b = checksums(two.report);
  EXPECT_EQ(a.size(), 6u);
  EXPECT_EQ(a, b);
  // Each checksum is what the standard xxhsum prints for the written file.
  if (run_command("command -v xxhsum").exit_code != 0) GTEST_SKIP() << "xxhsum not installed";
  for (const auto& [file, sum] : a) {
    const auto r = run_command("xxhsum -H1 " + (two.dir / file).string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.substr(0, 16), sum) << file;
  }
}

TEST(GlobalMeshEtopo5, RotatedPoleChangesCountsAndClosesThePoles) {
  const auto& plain = mesh_run("");
  const auto& rot = mesh_run("-c " + std::string(AQ_SOURCE_DIR) + "/configs/rotated_greenland.toml");
  expect_invariants(rot.report);
  EXPECT_NE(rot.report.at("mesh_counts").at("triangles"), plain.report.at("mesh_counts").at("triangles"));
  // Seed Fig. 10 (ETOPO2): 66714 / 37284.
  EXPECT_NEAR(rot.report.at("mesh_counts").at("triangles").get<double>() / 66714.0, 1.0, 0.03);
  EXPECT_EQ(plain.report.at("mesh").at("pole_loops"), 1);  // without rotation the Arctic reaches φ = 90°
  EXPECT_EQ(rot.report.at("mesh").at("pole_loops"), 0);    // with the pole in Greenland both poles are dry
}

TEST(GlobalMeshEtopo5, GmshReadsTheRealMesh) {
  if (run_command("command -v gmsh").exit_code != 0) GTEST_SKIP() << "gmsh not installed";
  const auto& run = mesh_run("");
  const auto& c = run.report.at("mesh_counts");
  const fs::path msh = run.dir / "seed_4deg_L3.msh";
  const auto r = run_command("gmsh " + msh.string() + " -0 -o " + (run.dir / "reread.msh").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // gmsh reports "<n> nodes <m> elements": elements = triangles + boundary (coast) lines.
  const auto bnd = run.report.at("statistics").at("boundary_edges").get<std::int64_t>();
  EXPECT_THAT(r.out, ::testing::HasSubstr(std::to_string(c.at("triangles").get<std::int64_t>() + bnd) + " elements"));
}

TEST(GlobalMeshEtopo5, VtkReadsTheRealVtu) {
  const std::string py = "/usr/bin/python3";
  if (run_command(py + " -c 'import vtk'").exit_code != 0) GTEST_SKIP() << "python3-vtk9 not installed";
  const auto& run = mesh_run("");
  const fs::path vtu = run.dir / "seed_4deg_L3.vtu";
  const auto r =
      run_command(py + " -c \"import vtk; r=vtk.vtkXMLUnstructuredGridReader(); r.SetFileName('" + vtu.string() +
                  "'); r.Update(); g=r.GetOutput(); print(g.GetNumberOfPoints(), g.GetNumberOfCells())\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  long points = 0, cells = 0;
  ASSERT_EQ(std::sscanf(r.out.c_str(), "%ld %ld", &points, &cells), 2) << r.out;
  // The geographic mesh: the Arctic's polar row re-templated into the pole cap.
  EXPECT_EQ(points, run.report.at("geographic_mesh").at("nodes").get<long>());
  EXPECT_EQ(cells, run.report.at("geographic_mesh").at("triangles").get<long>());
}

TEST(GlobalMeshEtopo5, UgridAndFort14HeadersMatchTheReport) {
  const auto& run = mesh_run("");
  // The files hold the geographic mesh (pole cap), the report's mesh_counts the lattice mesh;
  // fort.14 holds it cleaned for the models (no triangle with one neighbour, no pinch).
  const auto tri = run.report.at("geographic_mesh").at("triangles").get<long>();
  const auto& cleaning = run.report.at("cleaning");
  std::ifstream f14(run.dir / "seed_4deg_L3.14");
  std::string title;
  std::getline(f14, title);
  long ne = 0, np = 0;
  f14 >> ne >> np;
  EXPECT_EQ(ne, cleaning.at("triangles").get<long>());
  EXPECT_EQ(np, cleaning.at("nodes").get<long>());
  EXPECT_EQ(ne, tri - cleaning.at("one_neighbour_triangles_removed").get<long>() -
                    cleaning.at("pinch_triangles_removed").get<long>());
  // Of the lattice mesh's two pinches one went with a triangle with one neighbour, one was resolved.
  EXPECT_EQ(cleaning.at("pinches_removed").get<long>(), 1);
  if (run_command("command -v ncdump").exit_code == 0) {
    const auto h = run_command("ncdump -h " + (run.dir / "seed_4deg_L3.nc").string());
    ASSERT_EQ(h.exit_code, 0);
    EXPECT_THAT(h.out, ::testing::HasSubstr("cf_role = \"mesh_topology\""));
    EXPECT_THAT(h.out, ::testing::HasSubstr("nMesh_face = " + std::to_string(tri)));
    EXPECT_THAT(h.out, ::testing::HasSubstr("sea_floor_depth_below_geoid"));
  }
  if (run_command("command -v cdo").exit_code == 0) {
    const auto g = run_command("cdo -s griddes " + (run.dir / "seed_4deg_L3.nc").string());
    ASSERT_EQ(g.exit_code, 0) << g.err;
    EXPECT_THAT(g.out, ::testing::HasSubstr("gridsize  = " + std::to_string(tri)));
  }
}

TEST(GlobalMeshEtopo5, BadInputsFailCleanlyWithoutPartialFiles) {
  const fs::path dir = fs::temp_directory_path() / ("aq_global_bad_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  auto r = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.string() + " --set input.path=/nonexistent.nc");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, ::testing::HasSubstr("/nonexistent.nc"));
  EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir));
  r = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.string() +
                  " --set mask.seeds=[[30.0,0.0]] --set mask.seed_radius_deg=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ::testing::HasSubstr("mask.seeds[0]"));
  EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir));
  r = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.string() +
                  " --set quadtree.levels=14 --set input.max_memory_gb=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ::testing::HasSubstr("quadtree.levels = 14"));
  EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir));
}

namespace {

using Vec3 = std::array<double, 3>;

Vec3 unit_xyz(double lon_deg, double lat_deg) {
  const double lo = lon_deg * M_PI / 180.0, la = lat_deg * M_PI / 180.0;
  return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
}

// Geometry and topology facts of a triangle mesh given by geographic node positions.
struct WrittenFacts {
  std::int64_t duplicate_points = 0, zero_area = 0, clockwise = 0, bad_edges = 0;
  std::set<std::pair<std::int64_t, std::int64_t>> boundary;  // undirected, smaller id first
  double geodesic_area_km2 = 0.0;
};

WrittenFacts written_facts(const std::vector<double>& lon, const std::vector<double>& lat,
                           const std::vector<std::array<std::int64_t, 3>>& tris) {
  WrittenFacts f;
  std::set<std::tuple<long long, long long, long long>> seen;
  std::vector<Vec3> v;
  for (std::size_t n = 0; n < lon.size(); ++n) {
    v.push_back(unit_xyz(lon[n], lat[n]));
    auto q = [](double x) { return std::llround(x * 1e9); };  // 6 mm on the Earth
    if (!seen.insert({q(v.back()[0]), q(v.back()[1]), q(v.back()[2])}).second) ++f.duplicate_points;
  }
  std::map<std::pair<std::int64_t, std::int64_t>, int> half;
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  for (const auto& t : tris) {
    const Vec3 &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
    const Vec3 bc{b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
    const double det = a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2];
    const double den = 1.0 + a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + b[0] * c[0] + b[1] * c[1] + b[2] * c[2] +
                       c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
    const double sr = 2.0 * std::atan2(det, den);
    if (std::abs(sr) < 1e-12) ++f.zero_area;
    if (sr < 0.0) ++f.clockwise;
    GeographicLib::PolygonArea poly(wgs84);
    for (const auto n : t) poly.AddPoint(lat[n], lon[n]);
    double perimeter = 0.0, area = 0.0;
    poly.Compute(false, true, perimeter, area);
    f.geodesic_area_km2 += area * 1e-6;
    for (int e = 0; e < 3; ++e) ++half[{t[e], t[(e + 1) % 3]}];
  }
  for (const auto& [e, k] : half) {
    if (k != 1) ++f.bad_edges;
    if (half.count({e.second, e.first}) == 0)
      f.boundary.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
  }
  return f;
}

}  // namespace

// Issue 11: the default run reaches φ = 90°; its fort.14 and UGRID used to hold 109 triangles with
// two nodes at the pole (zero area on the Earth) and 109 nodes at one point. The written meshes
// must have neither, stay conforming, and keep the filled area (less the small polar island).
TEST(GlobalMeshEtopo5, WrittenMeshesHaveNoDegenerateElements) {
  const auto& run = mesh_run("");
  const auto& geo = run.report.at("geographic_mesh");
  ASSERT_EQ(geo.at("poles").size(), 1u);
  const auto& cap = geo.at("poles")[0];
  EXPECT_EQ(cap.at("pole"), "north");
  EXPECT_EQ(cap.at("method"), "cap");
  EXPECT_GE(cap.at("min_angle_deg").get<double>(), 20.0);  // 24.0° (the lattice had 4° × 0.3° slivers)
  EXPECT_LE(cap.at("max_valence").get<int>(), 10);
  EXPECT_GE(cap.at("island_nodes").get<int>(), 4);
  EXPECT_LT(cap.at("island_radius_deg").get<double>(), 1.5);
  const auto& area = run.report.at("statistics").at("area");
  const double filled_km2 = area.at("filled_km2").get<double>();
  const double lattice_km2 = area.at("triangles_km2").get<double>();
  const double tolerance = 0.05 * 0.5 * M_PI / 180.0;  // the statistics' check: 0.05 × pixel (rad)
  // The polar island (authalic sphere; its WGS84 area differs by < 0.3%, 2e-7 of the total).
  const double island_km2 = cap.at("island_area_km2").get<double>();
  EXPECT_LT(island_km2 / filled_km2, 1e-4);

  // fort.14: nodes, elements, land boundaries.
  {
    std::ifstream f(run.dir / "seed_4deg_L3.14");
    std::string line;
    std::getline(f, line);
    std::int64_t ne = 0, np = 0;
    f >> ne >> np;
    std::vector<double> lon(static_cast<std::size_t>(np)), lat(lon.size());
    for (std::int64_t k = 0; k < np; ++k) {
      std::int64_t id = 0;
      double depth = 0.0;
      f >> id >> lon[static_cast<std::size_t>(k)] >> lat[static_cast<std::size_t>(k)] >> depth;
      ASSERT_EQ(id, k + 1);
    }
    std::vector<std::array<std::int64_t, 3>> tris(static_cast<std::size_t>(ne));
    for (auto& t : tris) {
      std::int64_t id = 0, three = 0;
      f >> id >> three >> t[0] >> t[1] >> t[2];
      for (auto& v : t) --v;
    }
    std::int64_t nope = 0, neta = 0, nbou = 0, nvel = 0;
    std::getline(f, line);
    f >> nope;
    std::getline(f, line);
    f >> neta;
    std::getline(f, line);
    f >> nbou;
    std::getline(f, line);
    f >> nvel;
    std::getline(f, line);
    std::set<std::pair<std::int64_t, std::int64_t>> declared;
    for (std::int64_t b = 0; b < nbou; ++b) {
      std::int64_t nvell = 0, ibtype = 0, prev = -1;
      f >> nvell >> ibtype;
      std::getline(f, line);
      for (std::int64_t k = 0; k < nvell; ++k) {
        std::int64_t n = 0;
        f >> n;
        --n;
        if (prev >= 0) declared.insert({std::min(prev, n), std::max(prev, n)});
        prev = n;
      }
    }
    ASSERT_TRUE(f.good());
    const WrittenFacts w = written_facts(lon, lat, tris);
    EXPECT_EQ(w.duplicate_points, 0);
    EXPECT_EQ(w.zero_area, 0);
    EXPECT_EQ(w.clockwise, 0);
    EXPECT_EQ(w.bad_edges, 0);
    EXPECT_EQ(w.boundary, declared);  // every edge in one triangle is a land boundary edge, and back
    // fort.14 is the geographic mesh cleaned for the models: less the triangles removed.
    const double removed_km2 = run.report.at("cleaning").at("area_removed_km2").get<double>();
    EXPECT_GT(removed_km2, 0.0);
    EXPECT_LT(removed_km2 / filled_km2, 0.01);
    EXPECT_NEAR((w.geodesic_area_km2 + removed_km2 + island_km2) / lattice_km2, 1.0, 1e-6);
    EXPECT_NEAR((w.geodesic_area_km2 + removed_km2) / filled_km2, 1.0, tolerance);
    // No node on (or within the island round) the pole.
    const double radius = cap.at("island_radius_deg").get<double>();
    EXPECT_GT(radius, 0.3);
    std::int64_t beyond = 0;
    for (const double la : lat) beyond += la > 90.0 - radius + 1e-9 ? 1 : 0;
    EXPECT_EQ(beyond, 0);
  }

  // UGRID: the same mesh through netCDF.
  {
    const aq::test::UgridTriangles u = aq::test::read_ugrid_triangles(run.dir / "seed_4deg_L3.nc");
    ASSERT_TRUE(u.error.empty()) << u.error;
    const std::vector<double>&lon = u.lon, &lat = u.lat;
    const auto& tris = u.triangles;
    const std::size_t np = lon.size();
    const WrittenFacts w = written_facts(lon, lat, tris);
    EXPECT_EQ(static_cast<std::int64_t>(np), geo.at("nodes").get<std::int64_t>());
    EXPECT_EQ(w.duplicate_points, 0);
    EXPECT_EQ(w.zero_area, 0);
    EXPECT_EQ(w.clockwise, 0);
    EXPECT_EQ(w.bad_edges, 0);
    EXPECT_NEAR((w.geodesic_area_km2 + island_km2) / lattice_km2, 1.0, 1e-6);
  }
}

// Issue 11: with mesh.elements = "squares" the UGRID file used to keep the lattice squares with
// the pole row: 109 nodes at one point. The pole row is now merged; the squares touching it are
// 3-node polygons. Every face (fan-triangulated) is anticlockwise with positive area, no two
// nodes share a point, and the faces cover the lattice mesh's area.
TEST(GlobalMeshEtopo5, SquaresUgridHasNoDuplicatePoleNodes) {
  const auto& run = mesh_run("--set mesh.elements=squares --set 'output.formats=[\"ugrid\"]'");
  const auto& geo = run.report.at("geographic_mesh");
  ASSERT_EQ(geo.at("poles").size(), 1u);
  EXPECT_EQ(geo.at("poles")[0].at("method"), "merge");
  EXPECT_EQ(geo.at("poles")[0].at("removed_nodes").get<std::int64_t>(), 108);  // 109 pole-row nodes -> 1
  fs::path nc_path;
  for (const auto& e : fs::directory_iterator(run.dir))
    if (e.path().extension() == ".nc") nc_path = e.path();
  int nc = -1, v = -1, d = -1;
  ASSERT_EQ(nc_open(nc_path.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  std::size_t np = 0, nf = 0, nmax = 0;
  ASSERT_EQ(nc_inq_dimid(nc, "nMesh_node", &d), NC_NOERR);
  nc_inq_dimlen(nc, d, &np);
  ASSERT_EQ(nc_inq_dimid(nc, "nMesh_face", &d), NC_NOERR);
  nc_inq_dimlen(nc, d, &nf);
  ASSERT_EQ(nc_inq_dimid(nc, "nMaxMesh_face_nodes", &d), NC_NOERR);
  nc_inq_dimlen(nc, d, &nmax);
  std::vector<double> lon(np), lat(np);
  ASSERT_EQ(nc_inq_varid(nc, "mesh_node_x", &v), NC_NOERR);
  nc_get_var_double(nc, v, lon.data());
  ASSERT_EQ(nc_inq_varid(nc, "mesh_node_y", &v), NC_NOERR);
  nc_get_var_double(nc, v, lat.data());
  std::vector<long long> faces(nmax * nf);
  ASSERT_EQ(nc_inq_varid(nc, "mesh_face_nodes", &v), NC_NOERR);
  nc_get_var_longlong(nc, v, faces.data());
  long long fill = 0;
  ASSERT_EQ(nc_get_att_longlong(nc, v, "_FillValue", &fill), NC_NOERR);
  long long start = 0;
  if (nc_get_att_longlong(nc, v, "start_index", &start) != NC_NOERR) start = 0;
  nc_close(nc);
  std::vector<std::array<std::int64_t, 3>> fan;  // faces as triangle fans
  std::int64_t three_node = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    std::vector<std::int64_t> p;
    for (std::size_t k = 0; k < nmax; ++k)
      if (faces[f * nmax + k] != fill) p.push_back(faces[f * nmax + k] - start);
    ASSERT_GE(p.size(), 3u) << "face " << f;
    three_node += p.size() == 3 ? 1 : 0;
    // Fan from the face's centre (hanging nodes make a fan from a corner degenerate).
    Vec3 c{0.0, 0.0, 0.0};
    for (const auto n : p) {
      const Vec3 u = unit_xyz(lon[static_cast<std::size_t>(n)], lat[static_cast<std::size_t>(n)]);
      for (int a = 0; a < 3; ++a) c[a] += u[a];
    }
    const auto centre = static_cast<std::int64_t>(lon.size());
    lon.push_back(std::atan2(c[1], c[0]) * 180.0 / M_PI);
    lat.push_back(std::atan2(c[2], std::hypot(c[0], c[1])) * 180.0 / M_PI);
    for (std::size_t k = 0; k < p.size(); ++k) fan.push_back({centre, p[k], p[(k + 1) % p.size()]});
  }
  EXPECT_GT(three_node, 0);  // the squares on the polar row
  const WrittenFacts w = written_facts(lon, lat, fan);
  EXPECT_EQ(static_cast<std::int64_t>(np), geo.at("nodes").get<std::int64_t>());
  EXPECT_EQ(w.duplicate_points, 0);
  EXPECT_EQ(w.zero_area, 0);
  EXPECT_EQ(w.clockwise, 0);
  EXPECT_EQ(w.bad_edges, 0);
  EXPECT_NEAR(w.geodesic_area_km2 / run.report.at("statistics").at("area").at("triangles_km2").get<double>(), 1.0,
              1e-9);
}

}  // namespace integration_global_mesh_test

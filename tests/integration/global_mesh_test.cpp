// The global discretizer end to end on the real ETOPO5 (ferret-datasets), through the
// `aquatoria mesh` command as a user runs it: counts against the seed and an independent
// implementation, whole-mesh invariants from the report, determinism across 1 and 2 threads,
// the rotated pole, and real clients (gmsh, VTK, ncdump, CDO) reading the real files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "support/run_command.hpp"

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
  for (const auto& o : report.at("outputs")) m[o.at("file")] = o.at("checksum_fnv1a64");
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
  const auto tri = run.report.at("mesh_counts").at("triangles").get<long>();
  const auto nodes = run.report.at("mesh_counts").at("nodes").get<long>();
  // The pole row is merged into one point and the triangles degenerate there are dropped.
  EXPECT_LT(points, nodes);
  EXPECT_GT(points, nodes - 400);
  EXPECT_LE(cells, tri);
  EXPECT_GT(cells, tri - 400);
}

TEST(GlobalMeshEtopo5, UgridAndFort14HeadersMatchTheReport) {
  const auto& run = mesh_run("");
  const auto tri = run.report.at("mesh_counts").at("triangles").get<long>();
  const auto nodes = run.report.at("mesh_counts").at("nodes").get<long>();
  std::ifstream f14(run.dir / "seed_4deg_L3.14");
  std::string title;
  std::getline(f14, title);
  long ne = 0, np = 0;
  f14 >> ne >> np;
  EXPECT_EQ(ne, tri);
  EXPECT_EQ(np, nodes);
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

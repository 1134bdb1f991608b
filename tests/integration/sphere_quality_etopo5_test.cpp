// SPDX-License-Identifier: GPL-3.0-or-later
// Shape quality on the sphere on the real ETOPO5 (issue 12): the seed reference run's figures
// from the issue's table (lattice mesh), the report's figures recomputed independently from the
// written UGRID file, and the FESOM, SCHISM and angle-coloured preview files bit-identical for
// 1 and 2 threads; bad new keys fail before any file is written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/global_run.hpp"
#include "config/load.hpp"
#include "mesh_files/sphere_quality.hpp"
#include "support/run_command.hpp"

namespace integration_sphere_quality_etopo5_test {

namespace fs = std::filesystem;
using aq::test::run_command;
using nlohmann::json;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct MeshRun {
  fs::path dir;
  json report;
  std::string err;
};

MeshRun run_mesh(const std::string& tag, const std::string& args, int threads) {
  MeshRun run;
  run.dir = fs::temp_directory_path() / ("aq_quality_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(run.dir);
  const auto r = run_command("OMP_NUM_THREADS=" + std::to_string(threads) + " " + AQ_BINARY + " mesh -q -o " +
                             run.dir.string() + " " + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  run.err = r.err;
  for (const auto& e : fs::directory_iterator(run.dir))
    if (e.path().string().ends_with("_report.json")) run.report = json::parse(std::ifstream(e.path()));
  return run;
}

// Smallest angle (degrees) of the spherical triangle a, b, c (lon/lat degrees), by the spherical
// law of cosines from the three side lengths: independent of the library's tangent-vector form.
double min_angle_deg(const double* lon, const double* lat) {
  auto side = [&](int i, int j) {
    const double c = std::sin(lat[i] * kDeg) * std::sin(lat[j] * kDeg) +
                     std::cos(lat[i] * kDeg) * std::cos(lat[j] * kDeg) * std::cos((lon[i] - lon[j]) * kDeg);
    return std::acos(std::clamp(c, -1.0, 1.0));
  };
  const double a = side(1, 2), b = side(2, 0), c = side(0, 1);
  auto angle = [](double opp, double s1, double s2) {
    return std::acos(
               std::clamp((std::cos(opp) - std::cos(s1) * std::cos(s2)) / (std::sin(s1) * std::sin(s2)), -1.0, 1.0)) /
           kDeg;
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

std::vector<double> read_var(int nc, const char* name) {
  int var = 0, ndims = 0, dims[NC_MAX_VAR_DIMS];
  EXPECT_EQ(nc_inq_varid(nc, name, &var), NC_NOERR) << name;
  nc_inq_varndims(nc, var, &ndims);
  nc_inq_vardimid(nc, var, dims);
  std::size_t n = 1;
  for (int d = 0; d < ndims; ++d) {
    std::size_t len = 0;
    nc_inq_dimlen(nc, dims[d], &len);
    n *= len;
  }
  std::vector<double> v(n);
  EXPECT_EQ(nc_get_var_double(nc, var, v.data()), NC_NOERR) << name;
  return v;
}

}  // namespace

// The issue-12 table, measured on the lattice mesh of the seed reference run: min angle p1 / p5 /
// median 5.0° / 7.9° / 35.6°, 27.1 % under 20° (65133 triangles).
TEST(SphereQualityEtopo5, SeedReferenceLatticeMeshReproducesTheIssueTable) {
  const auto loaded = aq::config::load_global(std::nullopt, {});
  const aq::Logger quiet([](aq::LogLevel, std::string_view) {});
  const auto setup = aq::app::prepare_global_run(loaded.options);
  const auto run = aq::app::run_global_pipeline(loaded.options, setup, quiet, nullptr, false);
  ASSERT_EQ(run.mesh.triangle_count(), 65133);
  const auto q = aq::io::summarize_quality(aq::io::triangle_shapes(run.mesh));
  EXPECT_NEAR(q.min_angle_p1_deg, 5.0, 0.05);
  EXPECT_NEAR(q.min_angle_p5_deg, 7.9, 0.05);
  EXPECT_NEAR(q.min_angle_p50_deg, 35.6, 0.05);
  EXPECT_NEAR(q.below_20_deg_percent, 27.1, 0.05);
}

// The report's figures (geographic mesh, as written) recomputed from the UGRID file.
TEST(SphereQualityEtopo5, ReportAgreesWithTheWrittenUgridFile) {
  const MeshRun run = run_mesh("ugrid", "--set 'output.formats=[\"ugrid\"]'", 2);
  const json& q = run.report.at("quality");
  int nc = 0;
  ASSERT_EQ(nc_open((run.dir / "seed_4deg_L3.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  const auto lon = read_var(nc, "mesh_node_x"), lat = read_var(nc, "mesh_node_y");
  const auto faces = read_var(nc, "mesh_face_nodes");
  nc_close(nc);
  const std::size_t nf = faces.size() / 3;
  ASSERT_EQ(static_cast<long>(nf), q.at("triangles").get<long>());
  std::vector<double> angles(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    double lo[3], la[3];
    for (int k = 0; k < 3; ++k) {
      const auto n = static_cast<std::size_t>(faces[3 * f + static_cast<std::size_t>(k)]);
      lo[k] = lon[n];
      la[k] = lat[n];
    }
    angles[f] = min_angle_deg(lo, la);
  }
  std::vector<double> sorted = angles;
  std::sort(sorted.begin(), sorted.end());
  auto pct = [&](double p) { return sorted[static_cast<std::size_t>(std::floor(p * static_cast<double>(nf - 1)))]; };
  const json& a = q.at("min_angle_deg");
  EXPECT_NEAR(a.at("p0").get<double>(), pct(0.0), 0.006);
  EXPECT_NEAR(a.at("p1").get<double>(), pct(0.01), 0.006);
  EXPECT_NEAR(a.at("p5").get<double>(), pct(0.05), 0.006);
  EXPECT_NEAR(a.at("p50").get<double>(), pct(0.5), 0.006);
  const double below20 =
      100.0 * static_cast<double>(std::count_if(angles.begin(), angles.end(), [](double x) { return x < 20.0; })) /
      static_cast<double>(nf);
  EXPECT_NEAR(q.at("min_angle_below_20_deg_percent").get<double>(), below20, 0.006);
  // The pole cap replaced the 4° × 0.3° slivers of the polar row: no triangle under 3.9°.
  EXPECT_GT(pct(0.0), 3.9);
  EXPECT_GT(q.at("edge_ratio").at("p99").get<double>(), q.at("edge_ratio").at("p50").get<double>());
  EXPECT_GE(q.at("neighbour_area_ratio").at("p99").get<double>(), 1.0);
}

TEST(SphereQualityEtopo5, NewFormatsAreBitIdenticalForOneAndTwoThreads) {
  const std::string args =
      "--set 'output.formats=[\"fesom\",\"schism\",\"png\"]' --set output.png_color=angle --set output.png_width=800";
  const MeshRun one = run_mesh("t1", args, 1), two = run_mesh("t2", args, 2);
  ASSERT_EQ(one.report.at("outputs").size(), 6u);
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_EQ(one.report.at("outputs")[k].at("checksum_xxh64"), two.report.at("outputs")[k].at("checksum_xxh64"))
        << one.report.at("outputs")[k].at("file");
  json qa = one.report.at("quality"), qb = two.report.at("quality");
  for (auto* q : {&qa, &qb})
    for (const char* k : {"seconds", "cpu_seconds", "geographic_mesh_seconds"}) q->erase(k);
  EXPECT_EQ(qa, qb);
  // Not rotated: FESOM's standard frame (model pole on Greenland), in the log too; the model
  // formats are cleaned (the two pinches of the lattice mesh removed), with the lon-lat
  // lattice's obtuse triangles a warning; SCHISM's time steps in the log.
  EXPECT_TRUE(one.report.at("fesom").at("force_rotation").get<bool>());
  EXPECT_EQ(one.report.at("fesom").at("alphaEuler").get<double>(), 50.0);
  EXPECT_EQ(one.report.at("fesom").at("betaEuler").get<double>(), 15.0);
  EXPECT_EQ(one.report.at("fesom").at("gammaEuler").get<double>(), -90.0);
  // A quiet run (-q) prints the warnings only.
  EXPECT_THAT(one.err, ::testing::HasSubstr("use the Mercator lattice"));
  EXPECT_THAT(one.err, ::testing::HasSubstr("poleward of 54.0° latitude"));
  // SCHISM's time steps: 300 s (its usual, without advection) fits; with advection no Δt does.
  const json& sch = one.report.at("schism");
  EXPECT_LT(sch.at("dt_advection_off_min_s").get<double>(), 300.0);
  EXPECT_GT(sch.at("dt_advection_on_min_s").get<double>(), sch.at("dt_max_s").get<double>());
  EXPECT_EQ(one.report.at("cleaning").at("pinches_removed").get<int>(), 1);
  EXPECT_EQ(one.report.at("quality").at("max_angle_above_120_deg_triangles").get<int>(), 2984);
  EXPECT_GT(one.report.at("cleaning").at("angle_above_120_deg_triangles").get<int>(), 1000);
}

TEST(SphereQualityEtopo5, BadNewKeysFailBeforeAnyFile) {
  const fs::path dir = fs::temp_directory_path() / ("aq_quality_bad_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  for (const auto& [set, key] :
       std::vector<std::pair<std::string, std::string>>{{"output.png_color=depth", "output.png_color"},
                                                        {"output.fesom_levels=[0,5,10]", "output.fesom_levels"},
                                                        {"output.fesom_levels=[0,5,10,10,20]", "output.fesom_levels"},
                                                        {"'output.formats=[\"fesom2\"]'", "output.formats"}}) {
    const auto r = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.string() + " --set " + set);
    EXPECT_EQ(r.exit_code, 2) << set;
    EXPECT_THAT(r.err, ::testing::HasSubstr(key)) << set;
    EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir)) << set;
  }
  // FESOM with squares only: a configuration error naming both keys, nothing written.
  const auto r = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.string() +
                             " --set mesh.elements=squares --set 'output.formats=[\"fesom\"]'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ::testing::HasSubstr("mesh.elements"));
  EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir));
}

TEST(SphereQualityEtopo5, RotatedRunGivesFesomTheEulerAnglesOfItsPole) {
  const MeshRun run = run_mesh("rot", "--set rotation.enabled=true --set 'output.formats=[\"fesom\"]'", 2);
  const json& f = run.report.at("fesom");
  EXPECT_TRUE(f.at("force_rotation").get<bool>());
  EXPECT_NEAR(f.at("alphaEuler").get<double>(), -44.858333 + 90.0, 1e-9);
  EXPECT_NEAR(f.at("betaEuler").get<double>(), 90.0 - 78.141667, 1e-9);
  EXPECT_EQ(f.at("gammaEuler").get<double>(), -90.0);
  EXPECT_EQ(f.at("levels_m").size(), 48u);
  // The issue-12 table's rotated row (configs/rotated_greenland.toml's mesh): no pole rows, so the
  // geographic mesh is the lattice mesh: 66632 triangles, 5.5° / 7.4° / 34.7°, 26.8 % under 20°.
  const json& q = run.report.at("quality");
  EXPECT_EQ(q.at("triangles").get<long>(), 66632);
  EXPECT_NEAR(q.at("min_angle_deg").at("p1").get<double>(), 5.5, 0.05);
  EXPECT_NEAR(q.at("min_angle_deg").at("p5").get<double>(), 7.4, 0.05);
  EXPECT_NEAR(q.at("min_angle_deg").at("p50").get<double>(), 34.7, 0.05);
  EXPECT_NEAR(q.at("min_angle_below_20_deg_percent").get<double>(), 26.8, 0.05);
}

}  // namespace integration_sphere_quality_etopo5_test

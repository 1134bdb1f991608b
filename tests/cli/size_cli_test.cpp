// SPDX-License-Identifier: GPL-3.0-or-later
// The size field end to end on ETOPO5 (ARCHITECTURE §4.10): configs/global_tides.toml at a
// coarser level runs, its report's time step equals a brute-force loop over the written UGRID file
// (shortest great-circle edge / √(g·H), H the deepest node, read back with the netCDF C API), the
// Courant numbers at size.cfl.dt_s follow from it, the outputs are the same with one and two
// threads, and a smaller gradation gives more elements.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"
#include "support/ugrid_read.hpp"

namespace cli_size_cli_test {

namespace {

namespace fs = std::filesystem;

const std::string kConfig = std::string(AQ_SOURCE_DIR) + "/configs/global_tides.toml";

aq::test::CommandResult run(const fs::path& dir, const std::string& extra, int threads = 2) {
  return aq::test::run_command("OMP_NUM_THREADS=" + std::to_string(threads) + " " + std::string(AQ_BINARY) +
                               " mesh -q -c " + kConfig + " --set quadtree.levels=3 --set output.formats='[\"ugrid\", \"fort14\"]' -o " +
                               dir.string() + " " + extra);
}

std::vector<double> node_depths(const fs::path& nc_path) {
  int nc = -1, v = -1, d = -1;
  std::size_t n = 0;
  std::vector<double> depth;
  if (nc_open(nc_path.c_str(), NC_NOWRITE, &nc) != NC_NOERR) return depth;
  if (nc_inq_dimid(nc, "nMesh_node", &d) == NC_NOERR && nc_inq_dimlen(nc, d, &n) == NC_NOERR &&
      nc_inq_varid(nc, "depth", &v) == NC_NOERR) {
    depth.resize(n);
    if (nc_get_var_double(nc, v, depth.data()) != NC_NOERR) depth.clear();
  }
  nc_close(nc);
  return depth;
}

double great_circle_m(double lon1, double lat1, double lon2, double lat2) {
  const double r = M_PI / 180.0;
  const double a = std::pow(std::sin((lat2 - lat1) * r / 2), 2) +
                   std::cos(lat1 * r) * std::cos(lat2 * r) * std::pow(std::sin((lon2 - lon1) * r / 2), 2);
  return 2.0 * 6371008.8 * std::asin(std::min(1.0, std::sqrt(a)));
}

TEST(SizeCli, TimeStepOfTheReportIsTheBruteForceMinimumOverTheUgridFile) {
  const fs::path dir = aq::test::fresh_dir("size", "dt");
  const auto r = run(dir, "--set size.cfl.dt_s=120");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = aq::test::read_report(dir, "global_tides");
  const auto u = aq::test::read_ugrid_triangles(dir / "global_tides.nc");
  ASSERT_TRUE(u.error.empty()) << u.error;
  const std::vector<double> depth = node_depths(dir / "global_tides.nc");
  ASSERT_EQ(depth.size(), u.lon.size());
  const double min_depth = report["time_step"]["min_depth_m"].get<double>();
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> dts;
  for (const auto& t : u.triangles) {
    double edge = std::numeric_limits<double>::infinity(), h = min_depth;
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
      edge = std::min(edge, great_circle_m(u.lon[a], u.lat[a], u.lon[b], u.lat[b]));
      h = std::max(h, depth[a]);
    }
    dts.push_back(edge / std::sqrt(9.81 * h));
    best = std::min(best, dts.back());
  }
  const double reported = report["time_step"]["max_stable_dt_s"].get<double>();
  EXPECT_GT(reported, 1.0);
  EXPECT_NEAR(reported, best, 1e-5 * best);
  // Courant numbers at 120 s: the maximum is 120 / the smallest dt, the count above 0.5 matches.
  const auto& c = report["time_step"]["courant"];
  EXPECT_NEAR(c["max"].get<double>(), 120.0 / best, 1e-5 * 120.0 / best);
  const auto above = std::count_if(dts.begin(), dts.end(), [](double dt) { return 120.0 / dt > 0.5; });
  EXPECT_EQ(c["above_courant_max"].get<std::int64_t>(), above);
  std::int64_t by_level = 0;
  for (const auto& n : c["above_by_level"]) by_level += n.get<std::int64_t>();
  EXPECT_EQ(by_level, above);
  EXPECT_LE(c["above_touching_coast"].get<std::int64_t>(), above);
  // The step the report recommends keeps every triangle of the file at Courant <= 0.5.
  const double rec = report["time_step"]["dt_at_courant_max_s"].get<double>();
  EXPECT_NEAR(rec, 0.5 * best, 1e-5 * best);
  EXPECT_EQ(std::count_if(dts.begin(), dts.end(), [&](double dt) { return rec / dt > 0.5 + 1e-9; }), 0);
  EXPECT_TRUE(report.contains("size"));
  EXPECT_TRUE(report["quadtree"].contains("grading"));
  // The levels keep the field's grading (g = 0.2) wherever the CFL bound lets them.
  if (report["quadtree"]["grading"]["cfl_refused_splits"].get<std::int64_t>() == 0) {
    EXPECT_LE(report["quadtree"]["grading"]["max"].get<double>(), 0.2 + 1e-3);
  }
  fs::remove_all(dir);
}

TEST(SizeCli, LevelsKeepTheGradationOnEtopo5) {
  const fs::path dir = aq::test::fresh_dir("size", "grading");
  const auto r = run(dir, "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto g = aq::test::read_report(dir, "global_tides")["quadtree"]["grading"];
  EXPECT_EQ(g["gradation"].get<double>(), 0.2);
  EXPECT_GT(g["runs"].get<std::int64_t>(), 1000);
  EXPECT_GT(g["grading_splits"].get<std::int64_t>(), 0);
  EXPECT_LE(g["max"].get<double>(), 0.2 + 1e-3);
  EXPECT_LE(g["p90"].get<double>(), 0.2 + 1e-3);
  fs::remove_all(dir);
}

TEST(SizeCli, SameFilesWithOneAndTwoThreadsAndGradationMatters) {
  const fs::path d1 = aq::test::fresh_dir("size", "t1"), d2 = aq::test::fresh_dir("size", "t2");
  const auto r1 = run(d1, "", 1), r2 = run(d2, "", 2);
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const char* f : {"global_tides.nc", "global_tides.14"})
    EXPECT_TRUE(aq::test::slurp(d1 / f) == aq::test::slurp(d2 / f)) << f << " differs between 1 and 2 threads";
  const fs::path d3 = aq::test::fresh_dir("size", "g");
  const auto r3 = run(d3, "--set size.gradation=0.1");
  ASSERT_EQ(r3.exit_code, 0) << r3.err;
  const auto a = aq::test::read_report(d1, "global_tides"), b = aq::test::read_report(d3, "global_tides");
  EXPECT_GT(b["quadtree"]["leaves"].get<std::int64_t>(), a["quadtree"]["leaves"].get<std::int64_t>());
  for (const auto& d : {d1, d2, d3}) fs::remove_all(d);
}

TEST(SizeCli, BadSizeKeysNameTheKey) {
  const fs::path dir = aq::test::fresh_dir("size", "bad");
  const auto r = run(dir, "--set size.gradation=-1 --set size.wavelength.wl=abc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("size.gradation"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("size.wavelength.wl"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "global_tides.nc"));
}

}  // namespace

}  // namespace cli_size_cli_test

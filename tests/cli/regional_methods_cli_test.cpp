// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional` with the seed-004 methods (regional.method = tfi, star, ed2, rl, best): the
// Black Sea end to end with the usual files, the swan config, the selection table, bad keys, and
// the same bytes on 1 and 2 threads.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"

namespace cli_regional_methods_cli_test {

namespace fs = std::filesystem;
using aq::test::run_aquatoria;
using aq::test::run_command;
using ::testing::HasSubstr;

namespace {
const std::string kConfigs = std::string(AQ_SOURCE_DIR) + "/configs/";

fs::path fresh_dir(const std::string& name) { return aq::test::fresh_dir("methods_cli", name); }

nlohmann::json report(const fs::path& dir, const std::string& name) { return aq::test::read_report(dir, name); }
}  // namespace

TEST(RegionalMethodsCli, BlackSeaEd2WritesEveryFileAndChecks) {
  const fs::path out = fresh_dir("ed2");
  const auto r =
      run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml --set regional.method=ed2 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"black_sea_xygrid.nc", "black_sea_grid.png", "black_sea_grd.nc", "black_sea_roms.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto rep = report(out, "black_sea");
  const auto& g = rep.at("regional");
  EXPECT_EQ(g.at("method"), "ed2");
  EXPECT_EQ(g.at("supergrid"), nlohmann::json::array({131, 101}));
  EXPECT_EQ(g.at("self_intersecting_cells"), 0);
  EXPECT_EQ(g.at("boundary_crossings"), 0);
  EXPECT_GT(g.at("elliptic_iterations").get<int>(), 5);
  // The Black Sea's thin corner cells creep, so ED2 stops when the averages settle, well before the cap.
  EXPECT_EQ(g.at("elliptic_stop"), "averages settled");
  EXPECT_TRUE(g.at("elliptic_converged").get<bool>());
  EXPECT_LT(g.at("elliptic_iterations").get<int>(), 200);
  EXPECT_GT(g.at("elliptic_last_move").get<double>(), 0.0);
  EXPECT_LT(g.at("elliptic_last_move").get<double>(), 1e-3);
  EXPECT_FALSE(g.at("elliptic_rejected").get<bool>());
  EXPECT_GT(rep.at("quality").at("f1").at("worst").get<double>(), 0.0);
  const auto c = run_aquatoria("check " + (out / "black_sea_xygrid.nc").string());
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_THAT(c.out, HasSubstr("f2"));
}

TEST(RegionalMethodsCli, BlackSeaBestPrintsTheSelectionTable) {
  const fs::path out = fresh_dir("best");
  const auto r = run_aquatoria("regional -c " + kConfigs + "black_sea.toml --set regional.method=best -o " +
                               out.string() + " --set roms.enabled=false --no-coastline");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("regional best: candidates"));
  EXPECT_THAT(r.err, HasSubstr("conformal"));
  EXPECT_THAT(r.err, HasSubstr("tfi+1 section"));
  const auto g = report(out, "black_sea").at("regional");
  ASSERT_GE(g.at("candidates").size(), 3U);
  EXPECT_FALSE(g.at("selection_steps").empty());
  EXPECT_TRUE(fs::exists(out / "black_sea_xygrid.nc"));
  EXPECT_EQ(g.at("self_intersecting_cells"), 0);
  // best is never worse than the winner: ED2 from the conformal grid loses its orthogonality
  // (f2 0.995 -> 0.047), so the rule keeps the conformal grid itself.
  EXPECT_THAT(r.err, HasSubstr("rule: the ed2 grid replaces the chosen"));
  EXPECT_EQ(g.at("chosen"), "conformal");
  const auto q = report(out, "black_sea").at("quality");
  std::size_t winner = 0;
  while (g.at("candidates").at(winner).at("name") != g.at("chosen")) ++winner;
  const auto& f = g.at("candidates").at(winner).at("f_worst");
  EXPECT_GE(q.at("f1").at("worst").get<double>(), f.at(0).get<double>());
  EXPECT_GE(q.at("f2").at("worst").get<double>(), f.at(1).get<double>());
  EXPECT_TRUE(g.at("elliptic_rejected").get<bool>());
  ASSERT_EQ(g.at("final_check").size(), 2U);
}

TEST(RegionalMethodsCli, SwanFoldsWithoutTheSectionAndNotWithIt) {
  const fs::path a = fresh_dir("swan_section"), b = fresh_dir("swan_classic");
  const auto r1 = run_aquatoria("regional -q -c " + kConfigs + "swan.toml -o " + a.string());
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const auto r2 = run_aquatoria("regional -q -c " + kConfigs + "swan.toml --set regional.sections=[] -o " + b.string());
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_EQ(report(a, "swan").at("regional").at("self_intersecting_cells"), 0);
  EXPECT_GT(report(b, "swan").at("regional").at("self_intersecting_cells").get<int>(), 0);
  EXPECT_TRUE(fs::exists(a / "swan_xygrid.nc"));
  EXPECT_TRUE(fs::exists(a / "swan_grid.png"));
  // A section along eta instead: the run says so, and it does not remove a fold that runs across
  // the rows (the column section does).
  const fs::path c = fresh_dir("swan_eta");
  const auto r3 =
      run_aquatoria("regional -q -c " + kConfigs +
                    "swan.toml --set regional.sections=[] --set regional.sections_eta=[[0.5]] -o " + c.string());
  ASSERT_EQ(r3.exit_code, 0) << r3.err;
  EXPECT_EQ(report(c, "swan").at("regional").at("initial_grid"), "tfi+1 eta section");
  EXPECT_GT(report(c, "swan").at("regional").at("self_intersecting_cells").get<int>(), 0);
}

TEST(RegionalMethodsCli, SameBytesOnOneAndTwoThreadsForEveryMethod) {
  for (const std::string m : {"tfi", "ed2", "rl", "best"}) {  // star: see BadMethodKeysAreClearErrors
    std::string bytes[2];
    for (const int t : {1, 2}) {
      const fs::path out = fresh_dir("threads_" + m + std::to_string(t));
      const auto r = run_command("OMP_NUM_THREADS=" + std::to_string(t) + " " + AQ_BINARY + " regional -q -c " +
                                 kConfigs + "swan.toml --set regional.method=" + m + " -o " + out.string());
      ASSERT_EQ(r.exit_code, 0) << m << ": " << r.err;
      bytes[t - 1] = aq::test::slurp(out / "swan_xygrid.nc");
    }
    EXPECT_FALSE(bytes[0].empty()) << m;
    EXPECT_EQ(bytes[0], bytes[1]) << m;
  }
}

TEST(RegionalMethodsCli, BadMethodKeysAreClearErrors) {
  const fs::path out = fresh_dir("bad");
  auto r = run_aquatoria("regional -q -c " + kConfigs + "swan.toml --set regional.method=spline -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("regional.method"));
  r = run_aquatoria("regional -q -c " + kConfigs + "swan.toml --set regional.weight=\"1+*x\" -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("regional.weight"));
  r = run_aquatoria("regional -q -c " + kConfigs + "swan.toml --set regional.sections=[[1.5]] -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("sections"));
  r = run_aquatoria("regional -q -c " + kConfigs + "swan.toml --set regional.sections_eta=[[0.5]] -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("regional.sections_eta"));
  EXPECT_THAT(r.err, HasSubstr("cannot be combined with sections"));
  r = run_aquatoria("regional -q -c " + kConfigs +
                    "swan.toml --set regional.method=ed2 --set regional.elliptic_criteria_tolerance=0 -o " +
                    out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("elliptic_criteria_tolerance"));
  // The swan is not star-shaped (the top's tangents at both ends meet below the bottom).
  r = run_aquatoria("regional -q -c " + kConfigs + "swan.toml --set regional.method=star -o " + out.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("not star-shaped"));
  EXPECT_FALSE(fs::exists(out / "swan_xygrid.nc"));
}

}  // namespace cli_regional_methods_cli_test

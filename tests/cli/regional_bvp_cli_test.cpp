// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional` with method = bvp (seed 003), end to end: the Black Sea contour in the plane
// and on the sphere (the usual files, check tables in the report), seed 003's channel (f_max
// history), same bytes on 1 and 2 threads, and a bad key value refused without output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"

namespace cli_regional_bvp_cli_test {

namespace fs = std::filesystem;
using aq::test::run_aquatoria;
using ::testing::HasSubstr;

namespace {
const std::string kConfigs = std::string(AQ_SOURCE_DIR) + "/configs/";

fs::path fresh_dir(const std::string& name) { return aq::test::fresh_dir("bvp_cli", name); }

nlohmann::json report(const fs::path& dir, const std::string& name) { return aq::test::read_report(dir, name); }
}  // namespace

TEST(RegionalBvpCli, BlackSeaInThePlane) {
  const fs::path out = fresh_dir("plane");
  const auto r = run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml -o " + out.string() +
                               " --set regional.method=bvp --set roms.enabled=false");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "black_sea_xygrid.nc"));
  EXPECT_TRUE(fs::exists(out / "black_sea_grid.png"));
  const auto rep = report(out, "black_sea");
  const auto& g = rep.at("regional");
  EXPECT_EQ(g.at("method"), "bvp");
  EXPECT_EQ(g.at("supergrid"), nlohmann::json::array({131, 101}));  // the conformal grid's size
  EXPECT_NEAR(g.at("aspect_ratio").get<double>(), 1.300823, 2e-3);  // the conformal modulus
  const auto& fmax = g.at("bvp_f_max");
  EXPECT_GT(fmax.front().get<double>(), 0.3);  // the TFI grid
  const double best = fmax.at(g.at("bvp_best_iteration").get<std::size_t>()).get<double>();
  EXPECT_LT(best, 0.1);
  EXPECT_LT(rep.at("quality").at("ortho_err_50").at("rms").get<double>(), 5e-3);
  EXPECT_EQ(rep.at("quality").at("f1").at("worst").get<double>() > 0.0, true);  // no folded cell
  // check reads it back.
  const auto c = run_aquatoria("check " + (out / "black_sea_xygrid.nc").string());
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_THAT(c.out, HasSubstr("ortho_err_46"));
}

TEST(RegionalBvpCli, BlackSeaOnTheSphereWritesTheRomsFile) {
  const fs::path out = fresh_dir("sphere");
  const auto r = run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml -o " + out.string() +
                               " --set regional.method=bvp --set regional.surface=sphere");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"black_sea_xygrid.nc", "black_sea_grd.nc", "black_sea_grid.png", "black_sea_roms.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto rep = report(out, "black_sea");
  EXPECT_EQ(rep.at("regional").at("surface"), "sphere");
  EXPECT_EQ(rep.at("regional").at("supergrid"), nlohmann::json::array({131, 101}));
  EXPECT_LT(rep.at("quality").at("ortho_err_50").at("rms").get<double>(), 5e-3);
}

TEST(RegionalBvpCli, ChannelHistoryAndSameBytesOnOneAndTwoThreads) {
  std::string bytes[2];
  for (int t = 1; t <= 2; ++t) {
    const fs::path out = fresh_dir("channel" + std::to_string(t));
    const auto r = aq::test::run_command("OMP_NUM_THREADS=" + std::to_string(t) + " " + std::string(AQ_BINARY) +
                                         " regional -q -c " + kConfigs + "channel_bvp.toml -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    bytes[t - 1] = aq::test::slurp(out / "channel_bvp_xygrid.nc");
    const auto g = report(out, "channel_bvp").at("regional");
    EXPECT_EQ(g.at("supergrid"), nlohmann::json::array({51, 51}));
    const auto& f = g.at("bvp_f_max");
    EXPECT_GT(f.at(0).get<double>(), 0.1);
    EXPECT_LT(std::min(f.at(1).get<double>(), f.at(2).get<double>()), 2e-2);
  }
  EXPECT_FALSE(bytes[0].empty());
  EXPECT_EQ(bytes[0], bytes[1]);
}

TEST(RegionalBvpCli, BadMethodOrSurfaceIsRefused) {
  const fs::path out = fresh_dir("bad");
  auto r = run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml -o " + out.string() +
                         " --set regional.method=elliptic");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("regional.method"));
  r = run_aquatoria("regional -q -c " + kConfigs + "black_sea.toml -o " + out.string() +
                    " --set regional.surface=sphere");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("only the bvp method"));
  EXPECT_FALSE(fs::exists(out / "black_sea_xygrid.nc"));
}

TEST(RegionalBvpCli, TwoBlocksAreMergedIntoOneGrid) {
  const fs::path out = fresh_dir("two");
  const auto r = run_aquatoria("regional -q -c " + kConfigs + "two_blocks.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "two_blocks_xygrid.nc"));
  const auto g = report(out, "two_blocks").at("regional");
  EXPECT_EQ(g.at("bvp_blocks"), 2);
  EXPECT_EQ(g.at("supergrid").at(1), 51);
  EXPECT_EQ(g.at("supergrid").at(0).get<int>() % 2, 1);
  EXPECT_LT(g.at("bvp_interface_kink_rad").get<double>(), 0.1);  // C1 across the interface
  EXPECT_LT(g.at("bvp_f_avg").back().get<double>(), 1e-3);
  const auto rep = report(out, "two_blocks");
  EXPECT_GT(rep.at("quality").at("f1").at("worst").get<double>(), 0.0);  // no folded cell at the seam
}

}  // namespace cli_regional_bvp_cli_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The command line: help, version, usage errors (exit 2), input errors (exit 1, path named),
// configuration errors (exit 2, key and line named, all problems in one run).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "config/load.hpp"
#include "config/regional.hpp"
#include "support/run_command.hpp"

namespace cli_cli_test {

using aq::test::run_aquatoria;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {
fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "aq_cli_test";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}
}  // namespace

TEST(Cli, HelpListsSubcommands) {
  const auto r = run_aquatoria("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("info"));
  EXPECT_THAT(r.out, HasSubstr("mesh"));
}

TEST(Cli, SubcommandHelp) {
  const auto r = run_aquatoria("info --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--at"));
}

TEST(Cli, Version) {
  const auto r = run_aquatoria("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("aquatoria 0."));
}

// --keys lists every key with its default, and an enumerated key's names with their meanings, from
// the one table of names (config/kinds.hpp).
TEST(Cli, KeysListEveryKeyAndTheNamesOfEnumeratedOnes) {
  const auto m = run_aquatoria("mesh --keys");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  for (const std::string& k : aq::config::global_keys()) EXPECT_THAT("\n" + m.out, HasSubstr("\n" + k + " = ")) << k;
  EXPECT_THAT(m.out, HasSubstr("mask.sampling = \"vertex\""));
  EXPECT_THAT(m.out, HasSubstr("\"area\" (the deepest raster cell inside the pixel decides)"));
  EXPECT_THAT(m.out, HasSubstr("output.formats = [\"msh\",\"ugrid\",\"vtu\",\"fort14\",\"text\",\"png\"]"));
  const auto r = run_aquatoria("regional --keys");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& k : aq::config::regional_keys()) EXPECT_THAT("\n" + r.out, HasSubstr("\n" + k + " = ")) << k;
  EXPECT_THAT(r.out, HasSubstr("roms.distances = \"sphere\""));
  EXPECT_THAT(r.out, HasSubstr("\"wgs84\" (geodesics on the WGS84 ellipsoid)"));
}

TEST(Cli, BadOptionIsUsageError) {
  const auto r = run_aquatoria("info --no-such-option x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no-such-option"));
  EXPECT_EQ(run_aquatoria("").exit_code, 2);
  EXPECT_EQ(run_aquatoria("frobnicate").exit_code, 2);
}

TEST(Cli, MissingFileIsInputError) {
  const auto r = run_aquatoria("info /nonexistent/bathy.nc");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("/nonexistent/bathy.nc"));
}

TEST(Cli, BadAtPointIsUsageError) {
  const auto r = run_aquatoria(std::string("info ") + AQ_ETOPO_DIR + "/etopo60.cdf --at 10,100");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--at 10,100"));
}

TEST(Cli, InfoOnEtopo5) {
  const auto r = run_aquatoria(std::string("info ") + AQ_ETOPO_DIR + "/etopo5.cdf --at -150,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("4320 x 2161"));
  EXPECT_THAT(r.out, HasSubstr("min -10376.0 m, max 7833.0 m"));
  EXPECT_THAT(r.out, HasSubstr("global (wraps)"));
  EXPECT_THAT(r.out, HasSubstr("at -150,0: -4007.00 m (sea)"));
}

TEST(Cli, UnknownConfigKeyNamesKeyAndLine) {
  const auto p = write_temp("unknown.toml", "[quadtree]\nlevels = 3\nlevles = 4\n");
  const auto r = run_aquatoria("mesh -c " + p.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown.toml:3:"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.levles"));
}

TEST(Cli, BadSizeRulesNameTheRuleAndExitTwo) {
  const std::string box = "lon_min_deg = 0, lon_max_deg = 5, lat_min_deg = 0, lat_max_deg = 5";
  const auto r = run_aquatoria("mesh -q --set 'quadtree.box_rules=[{" + box + ", level = 2, size_km = 50}, {" + box +
                               ", size_km = nan}, {" + box + "}]' --set 'quadtree.depth_rules=[{min_depth_m = 0, " +
                               "max_depth_m = 200, size_km = -5}]'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("4 configuration errors"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.box_rules[0]: gives both level and size_km"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.box_rules[1].size_km: nan is not a finite number > 0 (km)"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.box_rules[2]: needs level or size_km"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.depth_rules[0].size_km: -5 is not a finite number > 0 (km)"));
}

TEST(Cli, ThreeBadValuesAllReported) {
  const auto p =
      write_temp("bad3.toml", "[mask]\ncursor = -1\n[quadtree]\nstep_deg = 5.5\n[output]\nformats = [\"stl\"]\n");
  const auto r = run_aquatoria("mesh -c " + p.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("3 configuration errors"));
  EXPECT_THAT(r.err, HasSubstr("mask.cursor"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.step_deg"));
  EXPECT_THAT(r.err, HasSubstr("output.formats"));
}

}  // namespace cli_cli_test

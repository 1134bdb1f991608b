// SPDX-License-Identifier: GPL-3.0-or-later
// Names say what was run (issue 11): without -c and output.name, a run whose parameters differ
// from the seed's reference run is named after them, and says so; output-only keys keep the
// seed's name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_run_name_cli_test {

namespace fs = std::filesystem;
using aq::test::run_aquatoria;
using ::testing::HasSubstr;

TEST(CliRunName, OverriddenDefaultsNameTheFilesAfterTheParameters) {
  aq::testing::TempDir dir;
  const auto r = run_aquatoria(
      "mesh --set quadtree.step_deg=1 --set quadtree.levels=3 --set 'output.formats=[\"text\"]' "
      "--set mask.passages=false -o " +
      dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "global_1deg_L3.txt"));
  EXPECT_TRUE(fs::exists(dir / "global_1deg_L3_report.json"));
  EXPECT_FALSE(fs::exists(dir / "seed_4deg_L3.txt"));
  // The run says which name it used and why.
  EXPECT_THAT(r.err, HasSubstr("name: global_1deg_L3 (no -c and no output.name"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.step_deg = 1"));
  EXPECT_THAT(r.err, HasSubstr("mask.passages = false"));
}

TEST(CliRunName, OutputKeysAloneKeepTheSeedName) {
  aq::testing::TempDir dir;
  const auto r =
      run_aquatoria("mesh --set 'output.formats=[\"text\"]' --set quadtree.levels=3 -o " + dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "seed_4deg_L3.txt"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("name: ")));
}

TEST(CliRunName, AnExplicitNameWins) {
  aq::testing::TempDir dir;
  const auto r =
      run_aquatoria("mesh -q --set quadtree.step_deg=2 --set output.name=mine --set 'output.formats=[\"text\"]' -o " +
                    dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "mine.txt"));
}

}  // namespace cli_run_name_cli_test

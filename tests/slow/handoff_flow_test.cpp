// SPDX-License-Identifier: GPL-3.0-or-later
// The hand-off in three commands on configs/global_1deg_L5.toml (ETOPO5, Δ0 = 1°, L = 5):
//   aquatoria mesh -c ... -o DIR;  aquatoria blocks -c ... -o DIR --top 2;
//   aquatoria regional -c DIR/blocks/block_001.toml
// Each step's files and pictures exist; the nesting file beside the ROMS grid has one record per
// boundary ρ/u/v point with valid weights, and the refinement ratio is about blocks.refinement.
// A block is no ROMS refinement: it gets neither contact points nor an updated parent grid.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <variant>

#include "grid_files/nesting_netcdf.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace slow_handoff_flow_test {

namespace fs = std::filesystem;
using aq::test::run_aquatoria;

TEST(HandoffFlow, MeshBlocksRegionalOnTheOneDegreeL5Run) {
  aq::testing::TempDir dir;
  const std::string config = std::string(AQ_SOURCE_DIR) + "/configs/global_1deg_L5.toml";
  const auto mesh = run_aquatoria("mesh -c " + config + " -o " + dir.path().string() + " -q");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  EXPECT_TRUE(fs::exists(dir / "global_1deg_L5.png"));

  const auto blocks = run_aquatoria("blocks -c " + config + " -o " + dir.path().string() + " --top 2 -q");
  ASSERT_EQ(blocks.exit_code, 0) << blocks.err;
  EXPECT_THAT(blocks.out, ::testing::HasSubstr("block_002"));
  const fs::path b = dir / "blocks";
  EXPECT_TRUE(fs::exists(b / "blocks.png"));
  EXPECT_TRUE(fs::exists(b / "block_001.png"));

  const auto regional = run_aquatoria("regional -c " + (b / "block_001.toml").string());
  ASSERT_EQ(regional.exit_code, 0) << regional.err;
  EXPECT_TRUE(fs::exists(b / "block_001_grd.nc"));
  EXPECT_TRUE(fs::exists(b / "block_001_roms.png"));
  ASSERT_TRUE(fs::exists(b / "block_001_nesting.nc")) << regional.err;
  // A block is nested in the global mesh, not a ROMS refinement: no contact points, no parent grid.
  EXPECT_FALSE(fs::exists(b / "block_001_contact.nc"));
  EXPECT_FALSE(fs::exists(b / "block_001_parent_grd.nc"));

  const aq::io::NestingFile n = aq::io::read_nesting(b / "block_001_nesting.nc");
  ASSERT_GT(n.size(), 100u);
  std::int64_t inside = 0, outside_attr = -1;
  double ratio = 0.0;
  for (const auto& [key, value] : n.attributes) {
    if (key == "points_outside") outside_attr = std::get<std::int64_t>(value);
    if (key == "refinement_ratio") ratio = std::get<double>(value);
  }
  for (std::size_t k = 0; k < n.size(); ++k) {
    if (n.element[k] < 0) continue;
    ++inside;
    double sum = 0.0;
    for (const double w : n.weights[k]) {
      EXPECT_GE(w, -1e-12);
      EXPECT_LE(w, 1.0 + 1e-12);
      sum += w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
  }
  EXPECT_GT(inside, 10);
  EXPECT_EQ(outside_attr, static_cast<std::int64_t>(n.size()) - inside);
  // Regional cells a third of the finest global element (blocks.refinement = 3), within the
  // spread of element shapes and latitudes.
  EXPECT_GT(ratio, 2.0);
  EXPECT_LT(ratio, 4.5);
}

}  // namespace slow_handoff_flow_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The hand-off a user can trust: the global -> blocks -> regional -> refinement chain notices
// when a file in it has been replaced. A block config whose global run was rewritten is refused;
// `blocks` leaves no block of an earlier run; a refinement whose parent changed since it was cut is
// refused (naming both files and the key that differs) unless --force; a run overwriting outputs
// made from other inputs says so; `check` reads the ROMS and MOM6 files a regional run writes.
#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_handoff_chain_cli_test {

using aq::test::run_aquatoria;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

// The seed's reference lattice (Δ0 = 4°, L = 3) on ETOPO60: a second or two.
std::string blocks_run(const fs::path& out, int top, const std::string& more = "") {
  return std::string("blocks --set input.path=") + AQ_ETOPO_DIR +
         "/etopo60.cdf --set quadtree.step_deg=4 --set quadtree.levels=3 --set mask.passages=false -o " + out.string() +
         " --top " + std::to_string(top) + " " + more;
}

std::string text(const fs::path& p) {
  std::ifstream f(p);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(HandoffChainCli, BlocksRemovesItsEarlierBlocksAndAStaleBlockConfigIsRefused) {
  aq::testing::TempDir dir;
  const fs::path b = dir / "blocks";
  const auto first = run_aquatoria(blocks_run(dir.path(), 5));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_TRUE(fs::exists(b / "block_005.toml"));
  EXPECT_THAT(text(b / "block_001.toml"), HasSubstr("global_config_checksum"));
  // Keep block 1's config of this run under another name: a block config that outlives its run.
  fs::copy_file(b / "block_001.toml", b / "kept_001.toml");

  // Again with fewer blocks and another global run (L = 2: another lattice).
  const auto second = run_aquatoria(blocks_run(dir.path(), 2, "--set quadtree.levels=2"));
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.err, HasSubstr("removed 9 files of 3 blocks of an earlier run"));
  for (const char* gone : {"block_003.toml", "block_003.izogrid", "block_003.png", "block_005.toml", "block_005.png"})
    EXPECT_FALSE(fs::exists(b / gone)) << gone;
  EXPECT_TRUE(fs::exists(b / "block_002.toml"));

  // The kept config names global.toml, now another global run: refused, naming both files.
  const auto stale = run_aquatoria("regional -c " + (b / "kept_001.toml").string() + " --stop-after contour");
  EXPECT_EQ(stale.exit_code, 1) << stale.err;
  EXPECT_THAT(stale.err, HasSubstr("kept_001.toml"));
  EXPECT_THAT(stale.err, HasSubstr((b / "global.toml").string()));
  EXPECT_THAT(stale.err, HasSubstr("has changed since this config was written"));
  EXPECT_FALSE(fs::exists(b / "block_001_contour.png"));
  // This run's own block config runs.
  const auto fresh = run_aquatoria("regional -c " + (b / "block_001.toml").string() + " --stop-after contour");
  EXPECT_EQ(fresh.exit_code, 0) << fresh.err;
}

TEST(HandoffChainCli, ARefinementRefusesAChangedParentAndChecksReadEveryGridFile) {
  aq::testing::TempDir dir;
  const std::string parent_cfg = std::string(AQ_SOURCE_DIR) + "/configs/black_sea.toml";
  const std::string child_cfg = std::string(AQ_SOURCE_DIR) + "/configs/black_sea_nw_shelf.toml";
  const fs::path parent = dir / "parent" / "black_sea_grd.nc";
  const std::string make_parent = "regional -c " + parent_cfg + " --no-coastline -o " + (dir / "parent").string();
  const std::string child = "regional -c " + child_cfg + " --set nesting.parent=\"" + parent.string() + "\" -o " +
                            (dir / "child").string() + " --no-coastline";
  const auto p1 = run_aquatoria(make_parent);
  ASSERT_EQ(p1.exit_code, 0) << p1.err;
  // Model-ready by default: rx0 <= 0.2 with rx0 and rx1 in the log.
  EXPECT_THAT(p1.err, HasSubstr("roms.rmax = 0.2"));
  EXPECT_THAT(p1.err, HasSubstr("rx1"));
  // MOM6 files beside the ROMS grid.
  for (const char* f : {"black_sea_ocean_hgrid.nc", "black_sea_ocean_topog.nc", "black_sea_ocean_mask.nc"})
    EXPECT_TRUE(fs::exists(dir / "parent" / f)) << f;

  const auto c1 = run_aquatoria(child);
  ASSERT_EQ(c1.exit_code, 0) << c1.err;

  // The parent made again from another input: its run says it overwrites other outputs.
  const auto p2 = run_aquatoria(make_parent + " --set roms.hmin_m=12");
  ASSERT_EQ(p2.exit_code, 0) << p2.err;
  EXPECT_THAT(p2.err, HasSubstr("overwrites the outputs of an earlier run made from other inputs"));
  EXPECT_THAT(p2.err, HasSubstr("roms.hmin_m: 10.0 -> 12.0"));

  // The refinement now refuses, naming the parent, its own grid and what differs.
  const auto c2 = run_aquatoria(child);
  EXPECT_EQ(c2.exit_code, 1) << c2.err;
  EXPECT_THAT(c2.err, HasSubstr(parent.string()));
  EXPECT_THAT(c2.err, HasSubstr("black_sea_nw_shelf_grd.nc"));
  EXPECT_THAT(c2.err, HasSubstr("roms.hmin_m: 10.0 -> 12.0"));
  EXPECT_THAT(c2.err, HasSubstr("--force"));
  const auto c3 = run_aquatoria(child + " --force");
  EXPECT_EQ(c3.exit_code, 0) << c3.err;
  EXPECT_THAT(c3.err, HasSubstr("--force: cutting this grid from the new parent"));

  // `check` reads the ROMS grid and the MOM6 supergrid as well as the planar grid.
  for (const char* f : {"black_sea_grd.nc", "black_sea_ocean_hgrid.nc", "black_sea_xygrid.nc"}) {
    const auto k = run_aquatoria("check --no-png " + (dir / "parent" / f).string() + " -o " +
                                 (dir / (std::string(f) + ".check.nc")).string());
    EXPECT_EQ(k.exit_code, 0) << f << ": " << k.err;
  }
}

TEST(HandoffChainCli, DataHonestyWarnings) {
  aq::testing::TempDir dir;
  // L = 5 on the 4° lattice: 7.5' pixels on the 60' raster.
  const auto fine = run_aquatoria(std::string("mesh --set input.path=") + AQ_ETOPO_DIR +
                                  "/etopo60.cdf --set quadtree.levels=5 --set mask.passages=false -o " +
                                  dir.path().string());
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  EXPECT_THAT(fine.err, HasSubstr("lattice finer than its data: 7.5' pixels on a 60' raster (8 pixels per raster"));
  // The seed's run at h = 0 on ETOPO5: ice shelves at exactly 0 m are meshed as ocean; the log says
  // so, with the key that changes it.
  const auto seed = run_aquatoria("mesh -o " + dir.path().string());
  ASSERT_EQ(seed.exit_code, 0) << seed.err;
  EXPECT_THAT(seed.err, HasSubstr("sit at exactly the threshold depth 0 m"));
  EXPECT_THAT(seed.err, HasSubstr("south of 77°S"));
  EXPECT_THAT(seed.err, HasSubstr("mask.min_depth_m > 0 leaves them dry"));
  EXPECT_THAT(seed.err, ::testing::Not(HasSubstr("lattice finer than its data")));
}

}  // namespace cli_handoff_chain_cli_test

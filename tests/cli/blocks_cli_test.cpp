// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria blocks`: ranks the coastal blocks of a small global run and writes their configs,
// contours and pictures; a written block config runs `aquatoria regional` to its contour; user
// boxes without water and bad --top values are refused with a clear message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace cli_blocks_cli_test {

using aq::test::run_aquatoria;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

// The seed's reference lattice (Δ0 = 4°, L = 3) on ETOPO60: a second or two.
std::string small_run(const fs::path& out) {
  return std::string("blocks --set input.path=") + AQ_ETOPO_DIR +
         "/etopo60.cdf --set quadtree.step_deg=4 --set quadtree.levels=3 --set mask.passages=false -o " + out.string();
}

}  // namespace

TEST(BlocksCli, ListsBlocksWritesFilesAndTheFirstRunsToItsContour) {
  aq::testing::TempDir dir;
  const auto r = run_aquatoria(small_run(dir.path()) + " --top 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("block_001"));
  EXPECT_THAT(r.out, HasSubstr("block_003"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("block_004")));
  EXPECT_THAT(r.out, HasSubstr("level-0 square"));
  const fs::path b = dir / "blocks";
  for (const char* f : {"global.toml", "blocks.png", "blocks.json", "block_001.toml", "block_001.izogrid",
                        "block_001.png", "block_003.toml"})
    EXPECT_TRUE(fs::exists(b / f)) << f;
  EXPECT_FALSE(fs::exists(b / "block_004.toml"));
  std::ifstream js(b / "blocks.json");
  const auto j = nlohmann::json::parse(js);
  ASSERT_EQ(j["blocks"]["list"].size(), 3u);
  EXPECT_GE(j["blocks"]["list"][0]["coastal_pixels"].get<int>(), j["blocks"]["list"][1]["coastal_pixels"].get<int>());
  EXPECT_GT(j["blocks"]["candidates"].get<int>(), 100);
  // The written global config is the effective one (the --set values are in it).
  std::ifstream gs(b / "global.toml");
  const std::string global((std::istreambuf_iterator<char>(gs)), std::istreambuf_iterator<char>());
  EXPECT_THAT(global, HasSubstr("etopo60.cdf"));
  EXPECT_THAT(global, HasSubstr("step_deg = 4.0"));

  const auto g = run_aquatoria("regional -c " + (b / "block_001.toml").string() + " --stop-after contour");
  EXPECT_EQ(g.exit_code, 0) << g.err;
  EXPECT_TRUE(fs::exists(b / "block_001_contour.png")) << g.err;
}

TEST(BlocksCli, ShrinkToWetContoursAreUsable) {
  aq::testing::TempDir dir;
  const auto r = run_aquatoria(small_run(dir.path()) + " --top 2 --set blocks.shrink_to_wet=true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"block_001", "block_002"}) {
    const auto g = run_aquatoria("regional -c " + (dir / "blocks" / (std::string(name) + ".toml")).string() +
                                 " --stop-after contour");
    EXPECT_EQ(g.exit_code, 0) << name << ": " << g.err;
  }
}

TEST(BlocksCli, UserBoxWithoutWaterIsAClearError) {
  aq::testing::TempDir dir;
  // Central Africa (Chad): no water of the global ocean.
  const auto r = run_aquatoria(small_run(dir.path()) + " --set 'blocks.boxes=[[15.0, 20.0, 10.0, 15.0]]'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("blocks.boxes[0]"));
  EXPECT_THAT(r.err, HasSubstr("no water"));
  EXPECT_FALSE(fs::exists(dir / "blocks" / "block_001.toml"));
}

TEST(BlocksCli, UserBoxOverTheCoast) {
  aq::testing::TempDir dir;
  // The Bay of Biscay.
  const auto r = run_aquatoria(small_run(dir.path()) + " --set 'blocks.boxes=[[-10.0, -1.0, 43.0, 48.5]]'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("blocks.boxes[0]"));
  const auto g = run_aquatoria("regional -c " + (dir / "blocks" / "block_001.toml").string() + " --stop-after contour");
  EXPECT_EQ(g.exit_code, 0) << g.err;
}

TEST(BlocksCli, SameFilesWithOneAndTwoThreads) {
  aq::testing::TempDir d1, d2;
  const auto r1 = aq::test::run_command("OMP_NUM_THREADS=1 " + std::string(AQ_BINARY) + " " + small_run(d1.path()) +
                                        " --top 4 --set blocks.shrink_to_wet=true -q");
  const auto r2 = aq::test::run_command("OMP_NUM_THREADS=2 " + std::string(AQ_BINARY) + " " + small_run(d2.path()) +
                                        " --top 4 --set blocks.shrink_to_wet=true -q");
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_EQ(r1.out, r2.out);
  for (const char* f : {"block_001.izogrid", "block_004.izogrid", "block_002.toml", "blocks.png", "block_003.png"}) {
    std::string a = aq::test::slurp(d1 / "blocks" / f), b = aq::test::slurp(d2 / "blocks" / f);
    EXPECT_FALSE(a.empty()) << f;
    // The configs name their (different) folders: compare with the folder taken out.
    for (auto [text, folder] : {std::pair{&a, d1.path().string()}, std::pair{&b, d2.path().string()}})
      for (std::size_t p = text->find(folder); p != std::string::npos; p = text->find(folder))
        text->erase(p, folder.size());
    // ... and global.toml's checksum, which covers those folder names.
    for (std::string* text : {&a, &b}) {
      const std::size_t p = text->find("global_config_checksum");
      if (p != std::string::npos) text->erase(p, text->find('\n', p) - p);
    }
    EXPECT_TRUE(a == b) << f;
  }
}

TEST(BlocksCli, BadTopIsAUsageError) {
  aq::testing::TempDir dir;
  const auto r = run_aquatoria(small_run(dir.path()) + " --top 1000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("1000"));
}

}  // namespace cli_blocks_cli_test

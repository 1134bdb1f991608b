// SPDX-License-Identifier: GPL-3.0-or-later
// FESOM2 as a client (issue 20): the real ocean model (../shared/clients/fesom2 builds FESOM2 and
// its partitioner fesom_meshpart once into a cache, ~/.cache/aq-fesom2, under a lock) reads our
// FESOM files as written, with the namelist's rotation from the report ("auto").
//  * fesom_meshpart partitions the default, rotated Greenland and Mercator meshes (it refused
//    every one before the cleaning: "find_elem_neighbors_ini:Insufficient number of neighbors");
//  * FESOM2 runs the Mercator mesh for 6 hours of tide: normal end, no NaN, and its SSH solver
//    converges in few iterations (31 mean / 39 max per step measured on the pruned mesh; the
//    lon-lat meshes needed 800-2000).
// Skipped, with a message, when the FESOM2 folder is not there.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace fesom2_fesom2_client_test {

namespace fs = std::filesystem;
using aq::test::run_command;

namespace {

// Makes the FESOM files of `config` (empty: the built-in default run) in `dir`; returns the
// prefix DIR/NAME the client takes.
std::string make_mesh(const aq::testing::TempDir& dir, const std::string& config, const std::string& name) {
  const std::string cfg = config.empty() ? "" : " -c " + (fs::path(AQ_SOURCE_DIR) / config).string();
  const auto mesh = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + cfg +
                                " --set 'output.formats=[\"fesom\"]'");
  EXPECT_EQ(mesh.exit_code, 0) << mesh.err;
  return (dir / name).string();
}

long first_number(const fs::path& p) {
  std::ifstream f(p);
  long n = -1;
  f >> n;
  return n;
}

void partition_case(const std::string& config, const std::string& name) {
  const fs::path script = aq::test::client_script("fesom2", "fesom2.sh");
  if (!fs::exists(script)) {
    GTEST_SKIP() << "FESOM2 client test skipped: " << script.string()
                 << " not found (clone the shared folder next to the repository to run it)";
  }
  const aq::testing::TempDir dir;
  const std::string prefix = make_mesh(dir, config, name);
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto part =
      run_command("bash " + script.string() + " part " + prefix + " --workdir " + (dir / "part").string());
  ASSERT_EQ(part.exit_code, 0) << part.err;
  std::cout << "fesom_meshpart on " << name << ":\n" << part.out;
  const auto kv = aq::test::key_values(part.out);
  ASSERT_TRUE(kv.count("meshpart_status")) << part.out << part.err;
  EXPECT_EQ(kv.at("meshpart_status"), "normal");
  EXPECT_EQ(kv.at("elements_with_lt2_neighbours"), "0");
  EXPECT_EQ(kv.count("edges_in_gt2_elements"), 0u);
  EXPECT_EQ(kv.at("nodes"), std::to_string(first_number(prefix + "_nod2d.out")));
  EXPECT_EQ(kv.at("elements"), std::to_string(first_number(prefix + "_elem2d.out")));
  EXPECT_EQ(kv.at("isolated_nodes_moved"), "0");
}

TEST(Fesom2Client, PartitionerAcceptsTheDefaultMesh) { partition_case("", "seed_4deg_L3"); }

TEST(Fesom2Client, PartitionerAcceptsTheRotatedGreenlandMesh) {
  partition_case("configs/rotated_greenland.toml", "rotated_greenland");
}

TEST(Fesom2Client, PartitionerAcceptsTheMercatorMesh) {
  partition_case("configs/global_mercator.toml", "global_mercator");
}

TEST(Fesom2Client, MercatorMeshRunsSixHours) {
  const fs::path script = aq::test::client_script("fesom2", "fesom2.sh");
  if (!fs::exists(script)) {
    GTEST_SKIP() << "FESOM2 client test skipped: " << script.string()
                 << " not found (clone the shared folder next to the repository to run it)";
  }
  const aq::testing::TempDir dir;
  const std::string prefix = make_mesh(dir, "configs/global_mercator.toml", "global_mercator");
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto run = run_command("bash " + script.string() + " run " + prefix + " 6 --workdir " + (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::cout << "FESOM2 on global_mercator, 6 h:\n" << run.out;
  const auto kv = aq::test::key_values(run.out);
  ASSERT_TRUE(kv.count("fesom_status")) << run.out << run.err;
  EXPECT_EQ(kv.at("meshpart_status"), "normal");
  EXPECT_EQ(kv.at("fesom_status"), "normal");
  EXPECT_EQ(kv.at("time_steps"), "24/24");
  EXPECT_EQ(kv.at("nan"), "no");
  ASSERT_TRUE(kv.count("max_abs_eta"));
  const double eta = std::stod(kv.at("max_abs_eta"));
  EXPECT_GT(eta, 0.05);  // the tide moved the ocean
  EXPECT_LT(eta, 2.0);
  // "mean M, max X, non-converged N, r.z<0 R"
  long mean = -1, max = -1, non_converged = -1, not_spd = -1;
  ASSERT_EQ(std::sscanf(kv.at("ssh_solver").c_str(), "mean %ld, max %ld, non-converged %ld, r.z<0 %ld", &mean, &max,
                        &non_converged, &not_spd),
            4)
      << kv.at("ssh_solver");
  EXPECT_LT(mean, 100);
  EXPECT_LT(max, 150);
  EXPECT_EQ(non_converged, 0);
  EXPECT_EQ(not_spd, 0);
}

}  // namespace

}  // namespace fesom2_fesom2_client_test

// SPDX-License-Identifier: GPL-3.0-or-later
// SCHISM as a client (issue 20): the real ocean model (../shared/clients/schism builds pschism once
// into a cache, ~/.cache/aq-schism, under a lock) runs the hgrid.gr3 of the default run and of
// configs/global_mercator.toml as written for a day of M2 tidal potential with momentum advection
// off (the client's default, Δt = 300 s): normal end, every step, no NaN, max |η| below 3 m. Both
// meshes were refused before the cleaning ("ABORT: Illegal bnd node": their pinch vertices).
// Skipped, with a message, when the SCHISM folder is not there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace schism_schism_client_test {

namespace fs = std::filesystem;
using aq::test::run_command;

namespace {

void run_case(const std::string& config, const std::string& name) {
  const fs::path script = aq::test::client_script("schism", "schism.sh");
  if (!fs::exists(script)) {
    GTEST_SKIP() << "SCHISM client test skipped: " << script.string()
                 << " not found (clone the shared folder next to the repository to run it)";
  }
  const aq::testing::TempDir dir;
  const std::string cfg = config.empty() ? "" : " -c " + (fs::path(AQ_SOURCE_DIR) / config).string();
  const auto mesh = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + cfg +
                                " --set 'output.formats=[\"schism\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const fs::path gr3 = dir / (name + ".gr3");
  ASSERT_TRUE(fs::exists(gr3));
  const auto run =
      run_command("bash " + script.string() + " run " + gr3.string() + " 24 --workdir " + (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::cout << "SCHISM on " << name << ".gr3, 24 h, advection off:\n" << run.out;
  const auto kv = aq::test::key_values(run.out);
  ASSERT_TRUE(kv.count("schism_status")) << run.out << run.err;
  EXPECT_EQ(kv.at("schism_status"), "normal");
  EXPECT_EQ(kv.at("time_steps"), "288/288");
  EXPECT_EQ(kv.at("nan"), "no");
  ASSERT_TRUE(kv.count("max_abs_eta"));
  const double eta = std::stod(kv.at("max_abs_eta"));
  EXPECT_GT(eta, 0.1);
  EXPECT_LT(eta, 3.0);
  // SCHISM read the file we wrote.
  std::ifstream f(gr3);
  std::string title;
  std::getline(f, title);
  long ne = 0, np = 0;
  f >> ne >> np;
  EXPECT_EQ(kv.at("nodes"), std::to_string(np));
  EXPECT_EQ(kv.at("elements"), std::to_string(ne));
}

TEST(SchismClient, DefaultMeshRunsOneDay) { run_case("", "seed_4deg_L3"); }

TEST(SchismClient, MercatorMeshRunsOneDay) { run_case("configs/global_mercator.toml", "global_mercator"); }

}  // namespace

}  // namespace schism_schism_client_test

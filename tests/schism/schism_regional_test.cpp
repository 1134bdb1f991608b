// SCHISM on the regional meshes (README "Regional FE meshes"): configs/north_sea.toml and
// configs/gulf_of_mexico_fe.toml are meshed, and SCHISM (2 MPI ranks) runs each hgrid.gr3 for 24 hours with a
// 0.5 m M2 elevation on every open-boundary node (`schism.sh run MESH.gr3 24 --open-m2 0.5`). It
// must read the open segments we wrote (NOPE, NETA as in the file), end normally, without NaN,
// with max |η| of the order of the forcing (0.1..5 m). Skipped when ../shared/clients/schism is
// absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using aq::test::run_command;

namespace {

void run_regional(const std::string& name) {
  const fs::path script = aq::test::client_script("schism", "schism.sh");
  if (!fs::exists(script)) GTEST_SKIP() << "SCHISM client test skipped: " << script.string() << " not found";
  const aq::testing::TempDir dir;
  const auto mesh = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + " -c " +
                                (fs::path(AQ_SOURCE_DIR) / "configs" / (name + ".toml")).string() +
                                " --set 'output.formats=[\"schism\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const fs::path gr3 = dir / (name + ".gr3");
  // NOPE and NETA as written.
  std::ifstream f(gr3);
  std::string line;
  std::getline(f, line);
  long ne = 0, np = 0;
  f >> ne >> np;
  std::getline(f, line);
  for (long k = 0; k < ne + np; ++k) std::getline(f, line);
  long nope = 0, neta = 0;
  f >> nope;
  std::getline(f, line);
  f >> neta;
  ASSERT_GT(nope, 0);
  const auto run = run_command("bash " + script.string() + " run " + gr3.string() + " 24 --open-m2 0.5 --workdir " +
                               (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::cout << "SCHISM on " << name << ".gr3, 24 h, M2 0.5 m on the open boundary:\n" << run.out;
  const auto kv = aq::test::key_values(run.out);
  ASSERT_TRUE(kv.count("schism_status")) << run.out << run.err;
  EXPECT_EQ(kv.at("schism_status"), "normal");
  EXPECT_EQ(kv.at("nan"), "no");
  EXPECT_EQ(kv.at("time_steps"), "288/288");
  EXPECT_EQ(kv.at("nodes"), std::to_string(np));
  EXPECT_EQ(kv.at("elements"), std::to_string(ne));
  EXPECT_EQ(kv.at("open_segments"), std::to_string(nope));
  EXPECT_EQ(kv.at("open_nodes"), std::to_string(neta));
  ASSERT_TRUE(kv.count("max_abs_eta"));
  const double eta = std::stod(kv.at("max_abs_eta"));
  EXPECT_GT(eta, 0.1);
  EXPECT_LT(eta, 5.0);
}

TEST(SchismRegional, NorthSeaM2OnTheOpenBoundaryRunsADay) { run_regional("north_sea"); }

TEST(SchismRegional, GulfOfMexicoM2OnTheOpenBoundaryRunsADay) { run_regional("gulf_of_mexico_fe"); }

}  // namespace

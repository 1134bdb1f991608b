// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC floods the shipped storm-surge mesh (README "A storm-surge mesh"): configs/gulf_surge.toml
// is meshed into fort.14 (the floodplain up to +10 m written with negative depths) and ADCIRC runs
// it for 24 hours with wetting and drying (NOLIFA = 2: `adcirc.sh run MESH.14 24 --ics 2
// --open-m2 2.0 --wetdry`, a 2 m M2 on the open boundary): normal end, no NaN, every node with a
// negative depth in our file starts dry, and some of them flood. Skipped when
// ../shared/clients/adcirc is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace adcirc_adcirc_surge_test {

namespace {

namespace fs = std::filesystem;

TEST(AdcircSurge, GulfSurgeFloodplainWetsAndDriesForADay) {
  const fs::path script = aq::test::client_script("adcirc", "adcirc.sh");
  if (!fs::exists(script)) GTEST_SKIP() << "ADCIRC client test skipped: " << script.string() << " not found";
  const aq::testing::TempDir dir;
  const auto mesh = aq::test::run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + " -c " +
                                          (fs::path(AQ_SOURCE_DIR) / "configs" / "gulf_surge.toml").string() +
                                          " --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const fs::path file = dir / "gulf_surge.14";
  std::ifstream f(file);
  std::string line;
  std::getline(f, line);
  long ne = 0, np = 0, negative = 0;
  f >> ne >> np;
  for (long k = 0; k < np; ++k) {
    long id = 0;
    double x = 0, y = 0, depth = 0;
    f >> id >> x >> y >> depth;
    negative += depth < 0.0 ? 1 : 0;
    ASSERT_GE(depth, -10.0 - 1e-9) << "node " << id << " above the floodplain's top";
  }
  ASSERT_TRUE(f) << file.string();
  ASSERT_GT(negative, 100) << "the floodplain is in the file";
  const auto run = aq::test::run_command("bash " + script.string() + " run " + file.string() +
                                         " 24 --ics 2 --open-m2 2.0 --wetdry --workdir " + (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::cout << "ADCIRC on gulf_surge.14, 24 h, M2 2 m on the open boundary, wetting and drying:\n" << run.out;
  const auto kv = aq::test::key_values(run.out);
  ASSERT_TRUE(kv.count("adcirc_status")) << run.out << run.err;
  EXPECT_EQ(kv.at("adcirc_status"), "normal");
  EXPECT_EQ(kv.at("nan"), "no");
  EXPECT_EQ(kv.at("nodes"), std::to_string(np));
  EXPECT_EQ(kv.at("elements"), std::to_string(ne));
  ASSERT_TRUE(kv.count("dry_start_nodes") && kv.count("flooded_nodes") && kv.count("never_wet_nodes")) << run.out;
  EXPECT_EQ(kv.at("dry_start_nodes"), std::to_string(negative));
  const long flooded = std::stol(kv.at("flooded_nodes")), never = std::stol(kv.at("never_wet_nodes"));
  EXPECT_LE(flooded, negative);
  EXPECT_GE(flooded + never, negative);  // never_wet_nodes counts every node never wet (a node at 0 m too)
  EXPECT_GT(flooded, 10) << "floodplain nodes that flood";
  EXPECT_GT(never, 10) << "the higher floodplain stays dry under a 2 m tide";
  const double eta = std::stod(kv.at("max_abs_eta"));
  EXPECT_GT(eta, 1.0);
  EXPECT_LT(eta, 10.0);
}

}  // namespace

}  // namespace adcirc_adcirc_surge_test

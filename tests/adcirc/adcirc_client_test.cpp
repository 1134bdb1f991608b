// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC as a client (issues 11, 12): the real ocean model (v56.2, serial; ../shared/clients/adcirc
// builds it once into a cache) runs the fort.14 of the default run (unrotated, the pole cap in
// the Arctic; ICS = 22), of configs/rotated_greenland.toml and of configs/global_mercator.toml
// (ICS = −22 with the same pole) for 6 model hours of M2 tidal-potential forcing: it must end
// normally, without NaN, with max |η| below 3 m. Skipped, with a message, when the ADCIRC folder
// is not there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace adcirc_adcirc_client_test {

namespace fs = std::filesystem;
using aq::test::run_command;

namespace {

fs::path adcirc_script() { return aq::test::client_script("adcirc", "adcirc.sh"); }

// Makes the mesh (`config` empty: the built-in default run), runs ADCIRC for 6 hours on its
// fort.14 and checks the summary.
void run_case(const std::string& config, const std::string& name, int ics) {
  const fs::path script = adcirc_script();
  if (!fs::exists(script)) {
    GTEST_SKIP() << "ADCIRC client test skipped: " << script.string()
                 << " not found (clone the shared folder next to the repository to run it)";
  }
  const aq::testing::TempDir dir;
  const std::string cfg = config.empty() ? "" : " -c " + (fs::path(AQ_SOURCE_DIR) / config).string();
  const auto mesh = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + cfg +
                                " --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const fs::path fort14 = dir / (name + ".14");
  ASSERT_TRUE(fs::exists(fort14));
  const auto report = nlohmann::json::parse(std::ifstream(dir / (name + "_report.json")));

  std::string args =
      " run " + fort14.string() + " 6 --ics " + std::to_string(ics) + " --workdir " + (dir / "run").string();
  if (ics < 0) {
    const auto& rot = report.at("config").at("rotation");
    args += " --pole " + std::to_string(rot.at("pole_lon_deg").get<double>()) + "," +
            std::to_string(rot.at("pole_lat_deg").get<double>());
  }
  const auto run = run_command("bash " + script.string() + args);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto kv = aq::test::key_values(run.out);
  std::cout << "ADCIRC on " << name << ".14 (ICS " << ics << "):\n" << run.out;
  ASSERT_TRUE(kv.count("adcirc_status")) << run.out << run.err;
  EXPECT_EQ(kv.at("adcirc_status"), "normal");
  EXPECT_EQ(kv.at("nan"), "no");
  EXPECT_EQ(kv.at("mesh_warnings"), "0");
  ASSERT_TRUE(kv.count("max_abs_eta"));
  EXPECT_LT(std::stod(kv.at("max_abs_eta")), 3.0);
  // ADCIRC read the file we wrote.
  std::ifstream f(fort14);
  std::string title;
  std::int64_t ne = 0, np = 0;
  std::getline(f, title);
  f >> ne >> np;
  EXPECT_EQ(kv.at("nodes"), std::to_string(np));
  EXPECT_EQ(kv.at("elements"), std::to_string(ne));
}

TEST(AdcircClient, DefaultMeshRunsSixHours) { run_case("", "seed_4deg_L3", 22); }

TEST(AdcircClient, RotatedGreenlandMeshRunsSixHours) {
  run_case("configs/rotated_greenland.toml", "rotated_greenland", -22);
}

// The Mercator lattice of the rotated frame (issue 12): elements down to a few km next to the
// rotated poles, geographic coordinates in the file, ADCIRC's own rotation (ICS -22) for its
// equations. 6 hours at DT = 15 s end normally (max |η| about 0.10 m).
TEST(AdcircClient, MercatorMeshRunsSixHours) { run_case("configs/global_mercator.toml", "global_mercator", -22); }

}  // namespace

}  // namespace adcirc_adcirc_client_test

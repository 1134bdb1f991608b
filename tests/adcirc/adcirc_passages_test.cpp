// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC on a global tide mesh whose straits are carved open (README "Passages, channels and
// rivers"): configs/global_tides.toml at quadtree.levels = 3 (about 100 000 nodes: the 24 h run of
// the full L = 5 mesh takes hours, the report gives it), 3 model hours of M2 tidal potential at
// the time step the report recommends (ICS = −22 with the mesh's pole). It must end normally
// without NaN, with the Mediterranean meshed (Gibraltar carved) and its water moving: the hourly
// |η| over the western Mediterranean's nodes grows under the ramp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace adcirc_adcirc_passages_test {

namespace fs = std::filesystem;
using aq::test::run_command;

TEST(AdcircPassages, GlobalTidesWithTheMediterraneanRunsThreeHours) {
  const fs::path script = aq::test::client_script("adcirc", "adcirc.sh");
  if (!fs::exists(script)) GTEST_SKIP() << "ADCIRC client test skipped: " << script.string() << " not found";
  const aq::testing::TempDir dir;
  const auto mesh = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + " -c " +
                                (fs::path(AQ_SOURCE_DIR) / "configs" / "global_tides.toml").string() +
                                " --set quadtree.levels=3 --set 'output.formats=[\"fort14\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const auto report = nlohmann::json::parse(std::ifstream(dir / "global_tides_report.json"));
  bool gibraltar = false;
  for (const auto& p : report["mask"]["passages"])
    if (p["name"] == "Gibraltar") gibraltar = p["carved"] == true && p["status"] == "open";
  ASSERT_TRUE(gibraltar);
  const double dt = report["time_step"]["dt_at_courant_max_s"].get<double>();
  ASSERT_GT(dt, 5.0);
  const auto& rot = report.at("config").at("rotation");
  std::ostringstream args;
  args << " run " << (dir / "global_tides.14").string() << " 3 --ics -22 --dt " << std::floor(dt * 10.0) / 10.0
       << " --pole " << rot.at("pole_lon_deg").get<double>() << "," << rot.at("pole_lat_deg").get<double>()
       << " --workdir " << (dir / "run").string();
  const auto run = run_command("bash " + script.string() + args.str());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::cout << "ADCIRC on global_tides (L = 3, straits carved), 3 h at dt = " << dt << " s:\n" << run.out;
  const auto kv = aq::test::key_values(run.out);
  ASSERT_TRUE(kv.count("adcirc_status")) << run.out << run.err;
  EXPECT_EQ(kv.at("adcirc_status"), "normal");
  EXPECT_EQ(kv.at("nan"), "no");
  EXPECT_EQ(kv.at("mesh_warnings"), "0");
  EXPECT_LT(std::stod(kv.at("max_abs_eta")), 3.0);
  // The western Mediterranean's nodes (0..9°E, 36..43°N) and their hourly |η| (fort.63).
  std::ifstream f14(dir / "global_tides.14");
  std::string line;
  std::getline(f14, line);
  long ne = 0, np = 0;
  f14 >> ne >> np;
  std::vector<char> med(static_cast<std::size_t>(np) + 1, 0);
  long in_med = 0;
  for (long k = 0; k < np; ++k) {
    long id = 0;
    double lon = 0.0, lat = 0.0, depth = 0.0;
    f14 >> id >> lon >> lat >> depth;
    if (lon >= 0.0 && lon <= 9.0 && lat >= 36.0 && lat <= 43.0) {
      med[static_cast<std::size_t>(id)] = 1;
      ++in_med;
    }
  }
  ASSERT_GT(in_med, 100);
  std::ifstream f63(dir / "run" / "fort.63");
  ASSERT_TRUE(f63.good());
  std::getline(f63, line);
  std::getline(f63, line);
  std::vector<double> hourly;
  while (std::getline(f63, line)) {  // a record: its time line, then np lines "id eta"
    double most = 0.0;
    for (long k = 0; k < np && std::getline(f63, line); ++k) {
      std::istringstream s(line);
      long id = 0;
      double eta = 0.0;
      s >> id >> eta;
      if (id > 0 && id <= np && med[static_cast<std::size_t>(id)] != 0) most = std::max(most, std::abs(eta));
    }
    hourly.push_back(most);
  }
  ASSERT_EQ(hourly.size(), 3U);
  // Measured 1.2, 4.8, 8.8 mm: the equilibrium tide under the half-day ramp.
  EXPECT_GT(hourly[2], 2e-3);
  EXPECT_GT(hourly[2], hourly[0]);
}

}  // namespace adcirc_adcirc_passages_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper for the regional client tests (tests/adcirc, tests/schism; README "Regional FE
// meshes"): a configs/NAME.toml is meshed into one model format, and the model (through its
// ../shared/clients script) runs it for 24 hours with a 0.5 m M2 elevation on every open-boundary
// node. Both fort.14 and hgrid.gr3 start with a title line, "NE NP", NP node lines, NE element
// lines, then NOPE and NETA: they are read back to check the model took what we wrote.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "support/client_summary.hpp"
#include "support/fort14_read.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace aq::test {

struct RegionalClientCase {
  std::string model;   ///< client folder and the name of the summary's status key (<model>_status)
  std::string script;  ///< the client script in that folder
  std::string format;  ///< output.formats entry
  std::string ext;     ///< the file's extension
};

/// Meshes configs/<name>.toml, runs the model on it for a day with `--open-m2 0.5` and checks what
/// every model's summary must say: normal end, no NaN, the nodes, elements, open segments and open
/// nodes of our file, and max |η| of the order of the forcing (0.1..5 m). Returns the summary.
inline void run_regional_client(const RegionalClientCase& c, const std::string& name,
                                std::map<std::string, std::string>* summary = nullptr) {
  namespace fs = std::filesystem;
  const fs::path script = client_script(c.model, c.script);
  if (!fs::exists(script)) GTEST_SKIP() << c.model << " client test skipped: " << script.string() << " not found";
  const aq::testing::TempDir dir;
  const auto mesh = run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + " -c " +
                                (fs::path(AQ_SOURCE_DIR) / "configs" / (name + ".toml")).string() +
                                " --set 'output.formats=[\"" + c.format + "\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const fs::path file = dir / (name + "." + c.ext);
  const Fort14 f = read_fort14(file);
  ASSERT_TRUE(f.error.empty()) << f.error;
  const long ne = f.elements, np = f.nodes(), nope = f.nope, neta = f.neta;
  ASSERT_GT(nope, 0) << file.string() << " has no open boundary";
  const auto run = run_command("bash " + script.string() + " run " + file.string() + " 24 --open-m2 0.5 --workdir " +
                               (dir / "run").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::cout << c.model << " on " << file.filename().string() << ", 24 h, M2 0.5 m on the open boundary:\n" << run.out;
  const auto kv = key_values(run.out);
  ASSERT_TRUE(kv.count(c.model + "_status")) << run.out << run.err;
  EXPECT_EQ(kv.at(c.model + "_status"), "normal");
  EXPECT_EQ(kv.at("nan"), "no");
  EXPECT_EQ(kv.at("nodes"), std::to_string(np));
  EXPECT_EQ(kv.at("elements"), std::to_string(ne));
  EXPECT_EQ(kv.at("open_segments"), std::to_string(nope));
  EXPECT_EQ(kv.at("open_nodes"), std::to_string(neta));
  ASSERT_TRUE(kv.count("max_abs_eta"));
  const double eta = std::stod(kv.at("max_abs_eta"));
  EXPECT_GT(eta, 0.1);
  EXPECT_LT(eta, 5.0);
  if (summary != nullptr) *summary = kv;
}

}  // namespace aq::test

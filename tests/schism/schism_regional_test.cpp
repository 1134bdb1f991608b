// SPDX-License-Identifier: GPL-3.0-or-later
// SCHISM on the regional meshes (README "Regional FE meshes"): configs/north_sea.toml and
// configs/gulf_of_mexico_fe.toml are meshed, and SCHISM (2 MPI ranks) runs each hgrid.gr3 for 24
// hours with a 0.5 m M2 elevation on every open-boundary node (`schism.sh run MESH.gr3 24
// --open-m2 0.5`). It must read the open segments we wrote, end normally after all 288 steps,
// without NaN, with max |η| of the order of the forcing (support/regional_client.hpp). Skipped
// when ../shared/clients/schism is absent.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "support/regional_client.hpp"

namespace schism_schism_regional_test {

namespace {

const aq::test::RegionalClientCase kSchism{"schism", "schism.sh", "schism", "gr3"};

void run_schism(const std::string& name) {
  std::map<std::string, std::string> kv;
  aq::test::run_regional_client(kSchism, name, &kv);
  if (::testing::Test::IsSkipped() || ::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(kv.at("time_steps"), "288/288");
}

TEST(SchismRegional, NorthSeaM2OnTheOpenBoundaryRunsADay) { run_schism("north_sea"); }

TEST(SchismRegional, GulfOfMexicoM2OnTheOpenBoundaryRunsADay) { run_schism("gulf_of_mexico_fe"); }

}  // namespace

}  // namespace schism_schism_regional_test

// SPDX-License-Identifier: GPL-3.0-or-later
// ADCIRC on the regional meshes (README "Regional FE meshes"): configs/north_sea.toml and
// configs/gulf_of_mexico_fe.toml are meshed, and ADCIRC runs each fort.14 for 24 hours with a
// 0.5 m M2 elevation on every open-boundary node (`adcirc.sh run MESH.14 24 --open-m2 0.5`). It
// must read the open segments we wrote (NOPE, NETA as in the file), end normally, without NaN,
// with max |η| of the order of the forcing (support/regional_client.hpp). Skipped when
// ../shared/clients/adcirc is absent.
#include <gtest/gtest.h>

#include "support/regional_client.hpp"

namespace adcirc_adcirc_regional_test {

namespace {

const aq::test::RegionalClientCase kAdcirc{"adcirc", "adcirc.sh", "fort14", "14"};

TEST(AdcircRegional, NorthSeaM2OnTheOpenBoundaryRunsADay) { aq::test::run_regional_client(kAdcirc, "north_sea"); }

TEST(AdcircRegional, GulfOfMexicoM2OnTheOpenBoundaryRunsADay) {
  aq::test::run_regional_client(kAdcirc, "gulf_of_mexico_fe");
}

}  // namespace

}  // namespace adcirc_adcirc_regional_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: the nesting file holds NaN (global_element_size, refinement_ratio) and -1
// (element, element_nodes, element_level) at the boundary points outside the wet global mesh;
// black_sea_nesting.nc had 113 such NaN values with no _FillValue, so CF readers took them for
// data. Every such variable now declares its fill value.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <limits>

#include "grid_files/nesting_netcdf.hpp"
#include "support/temp_dir.hpp"

namespace unit_grid_files_nesting_fill_value_test {

namespace {

aq::io::NestingFile two_points() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  aq::io::NestingFile f;
  f.point_type = {0, 0};
  f.boundary = {1, 1};
  f.element_level = {3, -1};
  f.xi_index = {0, 1};
  f.eta_index = {0, 0};
  f.lon = {30.0, 30.5};
  f.lat = {43.0, 43.0};
  f.x = {0.0, 1.0};
  f.y = {0.0, 0.0};
  f.element = {17, -1};
  f.element_nodes = {{{1, 2, 3}}, {{-1, -1, -1}}};
  f.weights = {{{0.2, 0.3, 0.5}}, {{0.0, 0.0, 0.0}}};
  f.global_element_size_m = {5000.0, nan};
  f.regional_cell_size_m = {1000.0, 1000.0};
  f.refinement_ratio = {5.0, nan};
  return f;
}

}  // namespace

TEST(NestingFillValue, EveryVariableHoldingNanOrMinusOneDeclaresIt) {
  aq::testing::TempDir dir;
  const auto path = dir / "n.nc";
  aq::io::write_nesting(path, two_points());
  int nc = -1;
  ASSERT_EQ(nc_open(path.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  for (const char* name : {"global_element_size", "refinement_ratio"}) {
    SCOPED_TRACE(name);
    int v = -1;
    ASSERT_EQ(nc_inq_varid(nc, name, &v), NC_NOERR);
    double fill = 0.0;
    ASSERT_EQ(nc_get_att_double(nc, v, "_FillValue", &fill), NC_NOERR);
    EXPECT_TRUE(std::isnan(fill));
  }
  for (const char* name : {"element", "element_nodes", "element_level"}) {
    SCOPED_TRACE(name);
    int v = -1;
    ASSERT_EQ(nc_inq_varid(nc, name, &v), NC_NOERR);
    long long fill = 0;
    ASSERT_EQ(nc_get_att_longlong(nc, v, "_FillValue", &fill), NC_NOERR);
    EXPECT_EQ(fill, -1);
  }
  // Variables that never hold a sentinel keep no fill value.
  int v = -1;
  ASSERT_EQ(nc_inq_varid(nc, "regional_cell_size", &v), NC_NOERR);
  EXPECT_EQ(nc_inq_att(nc, v, "_FillValue", nullptr, nullptr), NC_ENOTATT);
  nc_close(nc);
}

}  // namespace unit_grid_files_nesting_fill_value_test

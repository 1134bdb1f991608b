// SPDX-License-Identifier: GPL-3.0-or-later
// roms.depth_statistic end to end (issue 9): the Black Sea grid (about 2 ETOPO5 points per ρ
// cell) with "auto", "mean" and "min". auto keeps point there (fewer than 4 points per cell);
// min is never shallower than mean, mean differs from point, and the file and report say which
// statistic made hraw. The known answers of each statistic are in tests/unit/mask/cell_elevation_test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netcdf.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"

namespace cli_roms_depth_statistic_cli_test {

using aq::test::run_aquatoria;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

struct RomsDepth {
  std::vector<double> hraw;
  std::string statistic;
};

RomsDepth run(const std::string& statistic) {
  const fs::path out = aq::test::fresh_dir("roms_depth_statistic", statistic);
  const auto r = run_aquatoria("regional -c " + std::string(AQ_SOURCE_DIR) + "/configs/black_sea.toml -o " +
                               out.string() + " --set roms.depth_statistic=" + statistic);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("roms: depth statistic"));
  RomsDepth d;
  int nc = -1, v = -1, ndims = 0, dims[NC_MAX_VAR_DIMS] = {};

  if (nc_open((out / "black_sea_grd.nc").c_str(), NC_NOWRITE, &nc) != NC_NOERR) {
    ADD_FAILURE() << "no ROMS file for " << statistic;
    return d;
  }
  EXPECT_EQ(nc_inq_varid(nc, "hraw", &v), NC_NOERR);
  EXPECT_EQ(nc_inq_varndims(nc, v, &ndims), NC_NOERR);
  EXPECT_EQ(ndims, 3);  // (bath, eta_rho, xi_rho)
  EXPECT_EQ(nc_inq_vardimid(nc, v, dims), NC_NOERR);
  std::size_t size = 1;
  for (int k = 0; k < ndims; ++k) {
    std::size_t n = 0;
    nc_inq_dimlen(nc, dims[k], &n);
    size *= n;
  }
  d.hraw.resize(size);
  EXPECT_EQ(nc_get_var_double(nc, v, d.hraw.data()), NC_NOERR);
  std::size_t len = 0;
  nc_inq_attlen(nc, NC_GLOBAL, "depth_statistic", &len);
  d.statistic.resize(len);
  nc_get_att_text(nc, NC_GLOBAL, "depth_statistic", d.statistic.data());
  nc_close(nc);
  const auto rep = aq::test::read_report(out, "black_sea");
  EXPECT_EQ(rep["roms"]["depth"]["statistic"].get<std::string>(), d.statistic);
  fs::remove_all(out);
  return d;
}

}  // namespace

TEST(RomsDepthStatisticCli, MinIsDeepestMeanDiffersFromPointAutoIsPointOnACoarseRaster) {
  const auto point = run("auto"), mean = run("mean"), min = run("min");
  EXPECT_EQ(point.statistic, "point");  // auto: fewer than 4 raster points per cell
  EXPECT_EQ(mean.statistic, "mean");
  EXPECT_EQ(min.statistic, "min");
  ASSERT_EQ(mean.hraw.size(), point.hraw.size());
  ASSERT_EQ(min.hraw.size(), point.hraw.size());
  std::size_t differ = 0, shallower = 0;
  for (std::size_t k = 0; k < mean.hraw.size(); ++k) {
    if (mean.hraw[k] != point.hraw[k]) ++differ;
    if (min.hraw[k] < mean.hraw[k] - 1e-9) ++shallower;  // hraw is depth: min elevation is deepest
  }
  EXPECT_GT(differ, mean.hraw.size() / 2);
  EXPECT_EQ(shallower, 0u);
}

}  // namespace cli_roms_depth_statistic_cli_test

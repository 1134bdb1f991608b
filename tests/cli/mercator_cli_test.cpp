// SPDX-License-Identifier: GPL-3.0-or-later
// The Mercator lattice end to end on ETOPO5 (issue 12): configs/global_mercator.toml gives
// triangles that are well shaped on the sphere (min angles computed here from the written UGRID
// file with the netCDF C API, independently of the program's own statistics), leaf sizes within
// √2 of the size targets per latitude band, the same files with one and two threads; and the
// unrotated Mercator lattice is refused because the Arctic Ocean lies beyond its rows. Blocks and
// nesting on this lattice: mercator_blocks_cli_test.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netcdf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"
#include "support/ugrid_read.hpp"

namespace cli_mercator_cli_test {

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kConfig = std::string(AQ_SOURCE_DIR) + "/configs/global_mercator.toml";

aq::test::CommandResult run(const std::string& args, int threads) {
  return aq::test::run_command("OMP_NUM_THREADS=" + std::to_string(threads) + " " + std::string(AQ_BINARY) +
                               " mesh -q " + args);
}

using Vec = std::array<double, 3>;
Vec unit(double lon_deg, double lat_deg) {
  const double lo = lon_deg * M_PI / 180.0, la = lat_deg * M_PI / 180.0;
  return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
}
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
// Angle (degrees) at p between the great circles p→q and p→r: between the tangent vectors there.
double vertex_angle(const Vec& p, const Vec& q, const Vec& r) {
  Vec tq{}, tr{};
  for (int k = 0; k < 3; ++k) {
    tq[k] = q[k] - dot(p, q) * p[k];
    tr[k] = r[k] - dot(p, r) * p[k];
  }
  const double c = dot(tq, tr) / std::sqrt(dot(tq, tq) * dot(tr, tr));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

// Spherical min angle of every triangle of a UGRID file.
std::vector<double> min_angles_from_ugrid(const fs::path& path) {
  const aq::test::UgridTriangles u = aq::test::read_ugrid_triangles(path);
  EXPECT_TRUE(u.error.empty()) << u.error;
  std::vector<double> out;
  out.reserve(u.triangles.size());
  for (const auto& t : u.triangles) {
    std::array<Vec, 3> p{};
    for (std::size_t a = 0; a < 3; ++a) {
      const auto n = static_cast<std::size_t>(t[a]);
      p[a] = unit(u.lon.at(n), u.lat.at(n));
    }
    out.push_back(
        std::min({vertex_angle(p[0], p[1], p[2]), vertex_angle(p[1], p[2], p[0]), vertex_angle(p[2], p[0], p[1])}));
  }
  return out;
}

// The lattice kind the UGRID file declares (global attribute aquatoria_lattice_kind).
std::string lattice_kind(const fs::path& path) {
  int nc = -1;
  std::size_t len = 0;
  std::string kind;
  if (nc_open(path.c_str(), NC_NOWRITE, &nc) != NC_NOERR) return kind;
  if (nc_inq_attlen(nc, NC_GLOBAL, "aquatoria_lattice_kind", &len) == NC_NOERR) {
    kind.resize(len);
    nc_get_att_text(nc, NC_GLOBAL, "aquatoria_lattice_kind", kind.data());
  }
  nc_close(nc);
  return kind;
}

TEST(MercatorCli, RotatedEtopo5TrianglesAreWellShapedOnTheSphereAndSizesFollowTheTargets) {
  const fs::path d1 = aq::test::fresh_dir("mercator", "t1"), d2 = aq::test::fresh_dir("mercator", "t2");
  const std::string formats = " --set 'output.formats=[\"ugrid\", \"msh\", \"vtu\", \"fort14\", \"text\", \"png\"]'";
  const auto r1 = run("-c " + kConfig + " --set output.dir=" + d1.string() + formats, 1);
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const auto r2 = run("-c " + kConfig + " --set output.dir=" + d2.string() + formats, 2);
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const char* f : {"global_mercator.nc", "global_mercator.msh", "global_mercator.vtu", "global_mercator.14",
                        "global_mercator.txt", "global_mercator.png"}) {
    const std::string a = aq::test::slurp(d1 / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == aq::test::slurp(d2 / f)) << f << " differs between 1 and 2 threads";
  }

  const std::vector<double> angles = min_angles_from_ugrid(d1 / "global_mercator.nc");
  const nlohmann::json rep = aq::test::read_report(d1, "global_mercator");
  ASSERT_GT(angles.size(), 50000u);
  const auto at_least_40 = std::count_if(angles.begin(), angles.end(), [](double a) { return a >= 40.0; });
  EXPECT_GE(static_cast<double>(at_least_40), 0.99 * static_cast<double>(angles.size()));
  EXPECT_GE(*std::min_element(angles.begin(), angles.end()), 30.0);
  EXPECT_EQ(rep.at("lattice").at("kind"), "mercator");
  EXPECT_EQ(lattice_kind(d1 / "global_mercator.nc"), "mercator");

  // No leaf is coarser than √2 × the open-ocean target at any |φ′| (without the size rule the
  // level-0 squares are 445 km at the equator), and below 60° the median is not finer than the
  // coastal target allows (without the size rule the coast band is level 3 everywhere).
  const nlohmann::json& q = rep.at("quadtree");
  const double size = q.at("size_km").get<double>(), coast = q.at("coast_size_km").get<double>();
  ASSERT_EQ(size, 220.0);
  ASSERT_EQ(coast, 55.0);
  ASSERT_GE(q.at("size_by_latitude").size(), 8u);
  for (const auto& b : q.at("size_by_latitude")) {
    EXPECT_LE(b.at("max_km").get<double>(), std::sqrt(2.0) * size) << b.dump();
    if (b.at("abs_lat_max_deg").get<int>() <= 60) {
      EXPECT_GE(b.at("median_km").get<double>(), coast / std::sqrt(2.0)) << b.dump();
    }
  }
}

TEST(MercatorCli, WithoutRotationTheArcticBeyondTheRowsIsAnErrorAndNothingIsWritten) {
  const fs::path d = aq::test::fresh_dir("mercator", "norot");
  const auto r = run("--set quadtree.lattice=mercator --set output.dir=" + d.string(), 2);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("north cap"));
  EXPECT_THAT(r.err, HasSubstr("quadtree.mercator_lat_max_deg"));
  EXPECT_THAT(r.err, HasSubstr("rotation.enabled = true"));
  EXPECT_TRUE(!fs::exists(d) || fs::is_empty(d));
}

}  // namespace

}  // namespace cli_mercator_cli_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The hand-off on the rotated Mercator lattice (issue 12), end to end on ETOPO5 with
// configs/global_mercator.toml:
//   aquatoria mesh -c configs/global_mercator.toml;  aquatoria blocks -c ... --top 2;
//   aquatoria regional -c DIR/blocks/block_001.toml
// Checked here, with the lattice geometry written out in the test (Mercator ordinate
// y = ln tan(π/4 + φ′/2), rows evenly spaced in y) and the global mesh read back from its UGRID
// file (geographic nodes, rotated into the lattice frame):
//   * a block's box is a level-0 square of Mercator rows, and every control point of its contour
//     is a lattice vertex on the square's outline, on an edge or node of the wet mesh where the
//     mesh has one there;
//   * the block's regional grid runs and its nesting file's boundary points are located: each
//     element holds the point (brute-force search over every triangle in the (λ′, y) plane), the
//     weights are in [0, 1], sum to 1 and reproduce the point from the triangle's nodes; points
//     flagged outside lie in no triangle;
//   * blocks and regional write the same files with one and two threads.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "config/regional.hpp"
#include "core/rotation.hpp"
#include "curvilinear/common/projection.hpp"
#include "curvilinear/regional.hpp"
#include "grid_files/nesting_netcdf.hpp"
#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"
#include "support/ugrid_read.hpp"

namespace cli_mercator_blocks_cli_test {

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kConfig = std::string(AQ_SOURCE_DIR) + "/configs/global_mercator.toml";
constexpr double kDeg = M_PI / 180.0;

aq::test::CommandResult run(const std::string& args, int threads) {
  return aq::test::run_command("OMP_NUM_THREADS=" + std::to_string(threads) + " " + std::string(AQ_BINARY) + " " +
                               args);
}

double mercator_y_deg(double lat_deg) { return std::log(std::tan(M_PI / 4.0 + 0.5 * lat_deg * kDeg)) / kDeg; }
double mercator_lat_deg(double y_deg) { return (2.0 * std::atan(std::exp(y_deg * kDeg)) - M_PI / 2.0) / kDeg; }

template <typename T>
T attribute(const aq::io::NestingFile& f, const std::string& key) {
  for (const auto& [k, v] : f.attributes)
    if (k == key) return std::get<T>(v);
  ADD_FAILURE() << key << " missing";
  return T{};
}

// The lattice of the run: λ′ = λ0 + x·Δ, y = y0 + row·Δ (Mercator ordinate, degrees).
struct Plane {
  aq::PoleRotation rotation;
  double lon0 = -180.0, y0 = 0.0, pixel = 0.0;
  // Lattice-frame λ′ (degrees) and Mercator y of a geographic point.
  [[nodiscard]] std::array<double, 2> of(double lon, double lat) const {
    double rlon = 0.0, rlat = 0.0;
    rotation.to_rotated(lon, lat, rlon, rlat);
    return {rlon, mercator_y_deg(rlat)};
  }
  [[nodiscard]] std::array<double, 2> geographic(double rlon, double y) const {
    double lon = 0.0, lat = 0.0;
    rotation.to_geographic(rlon, mercator_lat_deg(y), lon, lat);
    return {lon, lat};
  }
  [[nodiscard]] double column(double rlon) const {
    const double c = (rlon - lon0) / pixel;
    return c - 720.0 * std::floor(c / 720.0);
  }
  [[nodiscard]] double row(double y) const { return (y - y0) / pixel; }
};

double lon_diff(double a, double b) { return std::remainder(a - b, 360.0); }

// The global mesh from its UGRID file, nodes in the lattice plane.
struct PlaneMesh {
  aq::test::UgridTriangles u;
  std::vector<std::array<double, 2>> node;  // (λ′, y)

  PlaneMesh(const fs::path& ugrid, const Plane& p) : u(aq::test::read_ugrid_triangles(ugrid)) {
    for (std::size_t n = 0; n < u.lon.size(); ++n) node.push_back(p.of(u.lon[n], u.lat[n]));
  }
  // Barycentric weights of plane point q in triangle t, λ′ brought next to its first node.
  [[nodiscard]] std::array<double, 3> weights(std::size_t t, std::array<double, 2> q) const {
    std::array<std::array<double, 2>, 3> v{};
    for (std::size_t a = 0; a < 3; ++a) v[a] = node[static_cast<std::size_t>(u.triangles[t][a])];
    for (std::size_t a = 1; a < 3; ++a) v[a][0] = v[0][0] + lon_diff(v[a][0], v[0][0]);
    q[0] = v[0][0] + lon_diff(q[0], v[0][0]);
    const double det = (v[1][1] - v[2][1]) * (v[0][0] - v[2][0]) + (v[2][0] - v[1][0]) * (v[0][1] - v[2][1]);
    const double w0 = ((v[1][1] - v[2][1]) * (q[0] - v[2][0]) + (v[2][0] - v[1][0]) * (q[1] - v[2][1])) / det;
    const double w1 = ((v[2][1] - v[0][1]) * (q[0] - v[2][0]) + (v[0][0] - v[2][0]) * (q[1] - v[2][1])) / det;
    return {w0, w1, 1.0 - w0 - w1};
  }
  // The largest smallest weight over all triangles (>= 0: inside or on an edge) and its triangle.
  [[nodiscard]] std::pair<double, std::size_t> best(const std::array<double, 2>& q) const {
    double b = -1e300;
    std::size_t bt = 0;
    for (std::size_t t = 0; t < u.triangles.size(); ++t) {
      const auto w = weights(t, q);
      const double m = std::min({w[0], w[1], w[2]});
      if (m > b) {
        b = m;
        bt = t;
      }
    }
    return {b, bt};
  }
};

bool same_files(const fs::path& a, const fs::path& b, const std::vector<std::string>& names) {
  bool same = true;
  for (const auto& f : names) {
    const std::string x = aq::test::slurp(a / f), y = aq::test::slurp(b / f);
    EXPECT_FALSE(x.empty()) << f;
    EXPECT_TRUE(x == y) << f << " differs between 1 and 2 threads";
    same = same && !x.empty() && x == y;
  }
  return same;
}

}  // namespace

TEST(MercatorBlocksCli, BlocksContoursAndNestingOnTheRotatedMercatorMesh) {
  const fs::path d = aq::test::fresh_dir("mercator_blocks", "run"), d2 = aq::test::fresh_dir("mercator_blocks", "t2");
  const auto mesh = run("mesh -q -c " + kConfig + " -o " + d.string() + " --set 'output.formats=[\"ugrid\"]'", 2);
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const auto blocks = run("blocks -q -c " + kConfig + " -o " + d.string() + " --top 2", 1);
  ASSERT_EQ(blocks.exit_code, 0) << blocks.err;
  EXPECT_THAT(blocks.out, HasSubstr("block_002"));
  EXPECT_THAT(blocks.out, HasSubstr("level-0 square"));
  const auto blocks2 = run("blocks -q -c " + kConfig + " -o " + d2.string() + " --top 2", 2);
  ASSERT_EQ(blocks2.exit_code, 0) << blocks2.err;
  EXPECT_EQ(blocks.out, blocks2.out);
  same_files(d / "blocks", d2 / "blocks", {"block_001.izogrid", "block_002.izogrid", "block_001.png", "blocks.png"});

  const fs::path b = d / "blocks";
  const auto regional = run("regional -q -c " + (b / "block_001.toml").string(), 1);
  ASSERT_EQ(regional.exit_code, 0) << regional.err;
  for (const char* f : {"block_001_grd.nc", "block_001_roms.png", "block_001_nesting.nc"})
    EXPECT_TRUE(fs::exists(b / f)) << f;
  const auto regional2 = run("regional -q -c " + (b / "block_001.toml").string() + " -o " + (d2 / "r").string(), 2);
  ASSERT_EQ(regional2.exit_code, 0) << regional2.err;
  same_files(b, d2 / "r", {"block_001_grd.nc", "block_001_nesting.nc"});

  // The lattice, from the nesting file (what a user of the file has).
  const aq::io::NestingFile n = aq::io::read_nesting(b / "block_001_nesting.nc");
  ASSERT_EQ(attribute<std::string>(n, "lattice_kind"), "mercator");
  Plane p;
  p.rotation = aq::PoleRotation(attribute<double>(n, "pole_lon_deg"), attribute<double>(n, "pole_lat_deg"));
  p.lon0 = attribute<double>(n, "lattice_lon0_deg");
  p.y0 = attribute<double>(n, "lattice_y0_deg");
  const auto levels = attribute<std::int64_t>(n, "lattice_levels");
  p.pixel = attribute<double>(n, "lattice_step0_deg") / static_cast<double>(std::int64_t{1} << levels);
  ASSERT_EQ(p.pixel, 0.5);
  const double square = static_cast<double>(std::int64_t{1} << levels);  // pixels per level-0 square

  const PlaneMesh m(d / "global_mercator.nc", p);
  ASSERT_TRUE(m.u.error.empty()) << m.u.error;
  ASSERT_GT(m.u.triangles.size(), 50000u);

  // Blocks: level-0 squares of Mercator rows.
  const auto js = nlohmann::json::parse(aq::test::slurp(b / "blocks.json"));
  EXPECT_EQ(js["blocks"]["lattice"], "mercator");
  const auto& list = js["blocks"]["list"];
  ASSERT_EQ(list.size(), 2u);
  for (const auto& blk : list) {
    const auto sq = blk["square"];
    const double a0 = sq[0].get<double>() * square, b0 = sq[1].get<double>() * square;
    EXPECT_EQ(blk["box_system"], "lattice");
    EXPECT_NEAR(p.row(mercator_y_deg(blk["box"][2].get<double>())), b0, 1e-9);
    EXPECT_NEAR(p.row(mercator_y_deg(blk["box"][3].get<double>())), b0 + square, 1e-9);
    EXPECT_NEAR(p.column(blk["box"][0].get<double>()), a0, 1e-9);
    EXPECT_EQ(blk["ny"].get<int>(), 24);  // 8 pixels high, blocks.refinement = 3

    // Every control point of the contour: a lattice vertex on the square's outline.
    const fs::path toml = blk["config"].get<std::string>();
    const auto loaded = aq::config::load_regional(toml.string(), {});
    const auto& rp = loaded.options.params;
    const aq::curvilinear::Projection proj(rp.projection);
    ASSERT_EQ(rp.x.size(), 32u);
    int on_mesh = 0;
    for (std::size_t k = 0; k < rp.x.size(); ++k) {
      const auto g = proj.inverse(rp.x[k], rp.y[k]);
      const auto q = p.of(g.lon_deg, g.lat_deg);
      const double col = p.column(q[0]), row = p.row(q[1]);
      EXPECT_NEAR(col, std::round(col), 1e-6) << toml << " point " << k;
      EXPECT_NEAR(row, std::round(row), 1e-6) << toml << " point " << k;
      const double c = std::round(col), r = std::round(row);
      EXPECT_TRUE(c == a0 || c == a0 + square || std::fmod(c + 720.0 - a0, 720.0) == square || r == b0 ||
                  r == b0 + square)
          << toml << " point " << k << " at " << col << ", " << row;
      // On the wet mesh it lies on an element edge or node (elements do not cross level-0 squares).
      const auto [w, t] = m.best(q);
      if (w < -1e-9) continue;
      ++on_mesh;
      EXPECT_NEAR(w, 0.0, 1e-9) << toml << " point " << k << " in triangle " << t;
    }
    EXPECT_GT(on_mesh, 0) << toml;
  }

  // Nesting: every located point lies in its element, with weights that reproduce it.
  ASSERT_GT(n.size(), 100u);
  std::int64_t inside = 0, outside = 0;
  for (std::size_t k = 0; k < n.size(); ++k) {
    const auto q = p.of(n.lon[k], n.lat[k]);
    const auto [wbest, tbest] = m.best(q);
    if (n.element[k] < 0) {
      ++outside;
      EXPECT_LT(wbest, 1e-9) << "point " << k << " flagged outside lies in triangle " << tbest;
      continue;
    }
    ++inside;
    const auto t = static_cast<std::size_t>(n.element[k]);
    ASSERT_LT(t, m.u.triangles.size());
    double sum = 0.0, rlon = 0.0, y = 0.0;
    const auto wt = m.weights(t, q);
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_EQ(n.element_nodes[k][a], m.u.triangles[t][a]) << "point " << k;
      const double w = n.weights[k][a];
      EXPECT_GE(w, 0.0);
      EXPECT_LE(w, 1.0);
      EXPECT_NEAR(w, wt[a], 1e-9) << "point " << k;
      sum += w;
      const auto& v = m.node[static_cast<std::size_t>(m.u.triangles[t][a])];
      rlon += w * (q[0] + lon_diff(v[0], q[0]));
      y += w * v[1];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(lon_diff(rlon, q[0]), 0.0, 1e-9);
    EXPECT_NEAR(y, q[1], 1e-9);
    const auto g = p.geographic(rlon, y);
    EXPECT_NEAR(lon_diff(g[0], n.lon[k]), 0.0, 1e-9);
    EXPECT_NEAR(g[1], n.lat[k], 1e-9);
  }
  EXPECT_EQ(attribute<std::int64_t>(n, "points_outside"), outside);
  EXPECT_GT(inside, static_cast<std::int64_t>(n.size()) / 4);
  // Regional cells about a third of the finest global element (blocks.refinement = 3).
  const double ratio = attribute<double>(n, "refinement_ratio");
  EXPECT_GT(ratio, 2.0);
  EXPECT_LT(ratio, 4.5);
}

}  // namespace cli_mercator_blocks_cli_test

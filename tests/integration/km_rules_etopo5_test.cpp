// SPDX-License-Identifier: GPL-3.0-or-later
// A box rule in kilometres on ETOPO5 (issue 12), on the Mercator lattice of the rotated frame
// (configs/global_mercator.toml): the leaves whose centre is in the box take the size nearest the
// target (within √2) at their latitude φ′, where the levels allow it; away from the box the leaves
// are those of the run without the rule; the files are the same with one and two threads, and the
// report and log give the rule as the user wrote it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "app/global_run.hpp"
#include "config/load.hpp"
#include "support/cli_outputs.hpp"
#include "support/run_command.hpp"

namespace integration_km_rules_etopo5_test {

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kConfig = std::string(AQ_SOURCE_DIR) + "/configs/global_mercator.toml";
const std::string kEtopo5 = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";
// The North Atlantic from the equator to 50°N: φ′ from about 12° to 62° in the Greenland frame.
constexpr double kLonMin = -45.0, kLonMax = -20.0, kLatMin = 0.0, kLatMax = 50.0, kTargetKm = 100.0;
const std::string kBoxSet =
    "quadtree.box_rules=[{lon_min_deg = -45, lon_max_deg = -20, lat_min_deg = 0, "
    "lat_max_deg = 50, size_km = 100}]";

bool in_box(double lon, double lat) { return lat >= kLatMin && lat <= kLatMax && lon >= kLonMin && lon <= kLonMax; }

struct MeshLeaves {
  aq::Lattice lat;
  aq::PoleRotation rot;
  std::vector<aq::quadtree::Leaf> leaves;
};

MeshLeaves run_pipeline(const std::vector<std::string>& sets) {
  const auto loaded = aq::config::load_global(kConfig, sets);
  const auto setup = aq::app::prepare_global_run(loaded.options);
  auto run = aq::app::run_global_pipeline(loaded.options, setup, aq::Logger::null(), nullptr, false);
  return MeshLeaves{setup.lattice, setup.rotation, std::move(run.leaves)};
}

// Latitude φ′ (rotated frame, degrees) of the fractional pixel row y: φ′ = atan(sinh y).
double row_lat(const aq::Lattice& lat, double y) {
  const double plane = (lat.y0_deg + y * lat.pixel_deg()) * std::numbers::pi / 180.0;
  return std::atan(std::sinh(plane)) * 180.0 / std::numbers::pi;
}

struct Centre {
  double row, lon, lat;  // fractional pixel row; geographic λ, φ
};
Centre centre_of(const MeshLeaves& r, const aq::quadtree::Leaf& f) {
  const double s = static_cast<double>(aq::quadtree::leaf_size(r.lat, f));
  const double row = static_cast<double>(aq::quadtree::leaf_j0(r.lat, f)) + 0.5 * s;
  const double col = static_cast<double>(aq::quadtree::leaf_i0(r.lat, f)) + 0.5 * s;
  Centre c{row, 0.0, 0.0};
  r.rot.to_geographic(r.lat.lon0_deg + col * r.lat.pixel_deg(), row_lat(r.lat, row), c.lon, c.lat);
  return c;
}

// Side on the sphere (km) of a Mercator square of level l centred on row y: Δ_l · cos φ′.
double size_km(const aq::Lattice& lat, int level, double row) {
  const double side_deg = lat.step0_deg / static_cast<double>(1 << level);
  return 6371.0088 * side_deg * std::numbers::pi / 180.0 * std::cos(row_lat(lat, row) * std::numbers::pi / 180.0);
}

using Key = std::tuple<int, std::int64_t, std::int64_t>;
Key key_of(const aq::quadtree::Leaf& f) { return {f.level, f.a, f.b}; }

class KmRulesEtopo5 : public testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kEtopo5)) GTEST_SKIP() << kEtopo5 << " not installed (ferret-datasets)";
  }
};

TEST_F(KmRulesEtopo5, BoxRuleInKilometresOnTheRotatedMercatorLattice) {
  const MeshLeaves plain = run_pipeline({});
  const MeshLeaves boxed = run_pipeline({kBoxSet});
  const aq::Lattice& lat = boxed.lat;
  ASSERT_TRUE(lat.mercator());
  ASSERT_FALSE(boxed.rot.identity());
  const aq::quadtree::LeafLocator plain_at(plain.leaves, lat);

  // Inside: no leaf coarser than √2 × the target unless it is a pixel (level L), none finer than
  // target/√2 unless the run without the rule had it as fine already (the coast) or it is level 0.
  // A leaf's centre lies a quarter of its parent's side from the parent's centre, where squares are
  // up to 2 % smaller than at the parent's centre: that is the tolerance of the lower bound.
  int inside = 0, refined = 0, within = 0;
  std::set<int> levels_inside;
  for (const auto& f : boxed.leaves) {
    const Centre c = centre_of(boxed, f);
    if (!in_box(c.lon, c.lat)) continue;
    ++inside;
    const double s = size_km(lat, f.level, c.row);
    const std::int64_t k = plain_at.find(aq::quadtree::leaf_i0(lat, f), aq::quadtree::leaf_j0(lat, f));
    ASSERT_GE(k, 0);
    const int before = plain.leaves[static_cast<std::size_t>(k)].level;
    refined += f.level > before ? 1 : 0;
    if (f.level < lat.levels) {
      EXPECT_LE(s, std::sqrt(2.0) * kTargetKm * (1 + 1e-9)) << f.level << " " << c.lon << " " << c.lat;
    }
    if (f.level > 0 && s < kTargetKm / std::sqrt(2.0) * 0.98) {
      EXPECT_EQ(f.level, before) << "finer than the target needs at " << c.lon << " " << c.lat;
    }
    within += s <= std::sqrt(2.0) * kTargetKm * (1 + 1e-9) && s >= kTargetKm / std::sqrt(2.0) * 0.98 ? 1 : 0;
    if (f.level > before) levels_inside.insert(f.level);
  }
  EXPECT_GT(inside, 200);
  EXPECT_GT(refined, inside / 2);  // the open ocean's 220 km target leaves most of the box coarser
  EXPECT_GT(within, inside * 8 / 10);
  // The rule asks level 2 (111 km · cos φ′) up to φ′ ≈ 50° and level 1 poleward of it.
  EXPECT_EQ(levels_inside, (std::set<int>{1, 2}));

  // Away from the box (three level-0 squares beyond the pixels whose centre is in it: the
  // squares split around a centre inside, and the 2:1 ripple) the leaves are unchanged.
  const std::int64_t margin = 3 * lat.pixels_per_square(0);
  std::vector<char> near(static_cast<std::size_t>(lat.nx * lat.ny), 0);
  for (std::int64_t j = 0; j < lat.ny; ++j) {
    for (std::int64_t i = 0; i < lat.nx; ++i) {
      double lon = 0.0, la = 0.0;
      boxed.rot.to_geographic(lat.lon0_deg + (static_cast<double>(i) + 0.5) * lat.pixel_deg(),
                              row_lat(lat, static_cast<double>(j) + 0.5), lon, la);
      if (!in_box(lon, la)) continue;
      for (std::int64_t y = std::max<std::int64_t>(0, j - margin); y <= std::min(lat.ny - 1, j + margin); ++y)
        for (std::int64_t x = i - margin; x <= i + margin; ++x)
          near[static_cast<std::size_t>(y * lat.nx + (x + lat.nx) % lat.nx)] = 1;
    }
  }
  const auto touches_near = [&](const aq::quadtree::Leaf& f) {
    const std::int64_t s = aq::quadtree::leaf_size(lat, f), i0 = aq::quadtree::leaf_i0(lat, f),
                       j0 = aq::quadtree::leaf_j0(lat, f);
    for (std::int64_t j = j0; j < j0 + s; ++j)
      for (std::int64_t i = i0; i < i0 + s; ++i)
        if (near[static_cast<std::size_t>(j * lat.nx + i)] != 0) return true;
    return false;
  };
  std::set<Key> plain_keys, boxed_keys;
  for (const auto& f : plain.leaves) plain_keys.insert(key_of(f));
  for (const auto& f : boxed.leaves) boxed_keys.insert(key_of(f));
  int away = 0;
  for (const auto& f : plain.leaves) {
    if (touches_near(f)) continue;
    ++away;
    EXPECT_EQ(boxed_keys.count(key_of(f)), 1u) << "leaf " << f.level << " " << f.a << " " << f.b << " changed";
  }
  for (const auto& f : boxed.leaves) {
    if (!touches_near(f)) {
      EXPECT_EQ(plain_keys.count(key_of(f)), 1u) << "new leaf " << f.level << " " << f.a;
    }
  }
  EXPECT_GT(away, static_cast<int>(plain.leaves.size()) * 3 / 4);
  EXPECT_GT(boxed.leaves.size(), plain.leaves.size());
}

TEST_F(KmRulesEtopo5, SameFilesOnOneAndTwoThreadsAndTheRuleAsGivenInReportAndLog) {
  const std::string args =
      "mesh -c " + kConfig + " --set '" + kBoxSet + "' --set 'output.formats=[\"ugrid\", \"msh\"]'";
  const fs::path d1 = aq::test::fresh_dir("km_rules", "t1"), d2 = aq::test::fresh_dir("km_rules", "t2");
  const auto r1 = aq::test::run_command("OMP_NUM_THREADS=1 " + std::string(AQ_BINARY) + " " + args +
                                        " --set output.dir=" + d1.string());
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  const auto r2 = aq::test::run_command("OMP_NUM_THREADS=2 " + std::string(AQ_BINARY) + " -q " + args +
                                        " --set output.dir=" + d2.string());
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const char* f : {"global_mercator.nc", "global_mercator.msh"}) {
    const std::string a = aq::test::slurp(d1 / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == aq::test::slurp(d2 / f)) << f << " differs between 1 and 2 threads";
  }
  const nlohmann::json rep = aq::test::read_report(d1, "global_mercator");
  const nlohmann::json& given = rep.at("config").at("quadtree").at("box_rules").at(0);
  EXPECT_EQ(given.at("size_km"), 100.0);
  EXPECT_FALSE(given.contains("level"));
  const nlohmann::json& q = rep.at("quadtree").at("box_rules").at(0);
  EXPECT_EQ(q.at("size_km"), 100.0);
  EXPECT_EQ(q.at("level_at_equator"), 2);   // 111 km at φ′ = 0
  EXPECT_EQ(q.at("level_at_last_row"), 0);  // 445 km · cos 86.6° = 26 km
  EXPECT_THAT(r1.err, HasSubstr("quadtree: box_rules[0] = {\"lon_min_deg\":-45.0,\"lon_max_deg\":-20.0,"
                                "\"lat_min_deg\":0.0,\"lat_max_deg\":50.0,\"size_km\":100.0}: level 2"));
}

}  // namespace

}  // namespace integration_km_rules_etopo5_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Depth and box rules in kilometres (issue 12, issue 19): a rule with size_km instead of a level is
// a term of the size field — the target on the field cells whose centre is in its range — and a
// square is split while its size on the sphere exceeds √2 × the field's minimum over it.
// The expected leaves are computed here per pixel from the lattice's definition written out in
// the test (Mercator φ = atan(sinh y), sizes Δ_l·cos φ on the Mercator lattice and Δ_l·√cos φ on
// the lon-lat one), on both lattices, with and without the rotated pole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "quadtree/bits.hpp"
#include "quadtree/leaves.hpp"
#include "raster/bathymetry.hpp"
#include "size/size_field.hpp"
#include "core/log.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::quadtree::unit_quadtree_km_rules_test {
namespace {

constexpr double kRad = std::numbers::pi / 180.0;
constexpr double kRadiusKm = 6371.0088;

Bitmap all_filled(const Lattice& lat) {
  Bitmap b(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j) bits::set_range(b.row(j), 0, lat.nx);
  return b;
}

// Latitude (lattice frame, degrees) of the fractional pixel row y.
double row_lat(const Lattice& lat, double y) {
  const double plane = lat.y0_deg + y * lat.step0_deg / static_cast<double>(1 << lat.levels);
  return lat.mercator() ? std::atan(std::sinh(plane * kRad)) / kRad : plane;
}

// Size (km) of a level-l square centred on row y: its λ side on the equator times cos φ
// (Mercator: both sides) or √cos φ (lon-lat: the root of its area).
double size_km_at(const Lattice& lat, int l, double y) {
  const double side = kRadiusKm * lat.step0_deg / static_cast<double>(1 << l) * kRad;
  const double c = std::cos(row_lat(lat, y) * kRad);
  return lat.mercator() ? side * c : side * std::sqrt(c);
}

// Fractional pixel row of a leaf's centre.
double centre_row(const Lattice& lat, const Leaf& f) {
  return static_cast<double>(leaf_j0(lat, f)) + 0.5 * static_cast<double>(leaf_size(lat, f));
}

using InRange = std::function<bool(double lon, double lat)>;

// One size rule: range test (geographic) and target.
struct KmRule {
  InRange in_range;
  double target_km;
};

// Whether square (l, a, b) is split: the rules are terms of the size field (size/size_field.hpp),
// a constant target on the field grid's cells (level c) whose centre is in the range, and a
// square is split while its size exceeds √2 × the field's minimum over it (over the cells inside
// it, or the cell holding it when l > c).
bool naive_split(const Lattice& lat, const PoleRotation& rot, const std::vector<KmRule>& rules, int l, std::int64_t a,
                 std::int64_t b) {
  if (l >= lat.levels) return false;
  const int c = size::choose_grid_level(lat, -1);
  const double row = (static_cast<double>(b) + 0.5) * static_cast<double>(1 << (lat.levels - l));
  const double size = size_km_at(lat, l, row);
  const std::int64_t a0 = l <= c ? a << (c - l) : a >> (l - c), b0 = l <= c ? b << (c - l) : b >> (l - c);
  const std::int64_t n = l <= c ? std::int64_t{1} << (c - l) : 1;
  for (std::int64_t cb = b0; cb < b0 + n; ++cb)
    for (std::int64_t ca = a0; ca < a0 + n; ++ca) {
      const double crow = (static_cast<double>(cb) + 0.5) * static_cast<double>(1 << (lat.levels - c));
      const double clon = lat.lon0_deg + (static_cast<double>(ca) + 0.5) * lat.step0_deg / static_cast<double>(1 << c);
      double lon = 0.0, la = 0.0;
      rot.to_geographic(clon, row_lat(lat, crow), lon, la);
      for (const KmRule& r : rules)
        if (r.in_range(lon, la) && size > std::sqrt(2.0) * r.target_km) return true;
    }
  return false;
}

void naive_descend(const Lattice& lat, const PoleRotation& rot, const std::vector<KmRule>& rules, int l, std::int64_t a,
                   std::int64_t b, std::vector<int>& levels) {
  if (!naive_split(lat, rot, rules, l, a, b)) {
    const std::int64_t s = std::int64_t{1} << (lat.levels - l);
    for (std::int64_t j = b * s; j < (b + 1) * s; ++j)
      for (std::int64_t i = a * s; i < (a + 1) * s; ++i) levels[static_cast<std::size_t>(j * lat.nx + i)] = l;
    return;
  }
  for (int c = 0; c < 4; ++c) naive_descend(lat, rot, rules, l + 1, 2 * a + (c & 1), 2 * b + (c >> 1), levels);
}

// The level of every pixel of an all-filled lattice under `rules` (before smoothing).
std::vector<int> naive_levels(const Lattice& lat, const PoleRotation& rot, const std::vector<KmRule>& rules) {
  std::vector<int> levels(static_cast<std::size_t>(lat.nx * lat.ny), -1);
  for (std::int64_t b = 0; b < (lat.ny >> lat.levels); ++b)
    for (std::int64_t a = 0; a < (lat.nx >> lat.levels); ++a) naive_descend(lat, rot, rules, 0, a, b, levels);
  return levels;
}

std::vector<Leaf> leaves_with(const Lattice& lat, const config::QuadtreeOptions& o, const PoleRotation& rot,
                              const raster::Bathymetry* bathy = nullptr) {
  LevelMasks m = make_level_masks(all_filled(lat), lat, 0);
  apply_refinement_rules(m, lat, o, rot, bathy);
  config::GlobalConfig c;
  c.quadtree = o;
  apply_size_field(m, lat, size::build_size_field(m.filled(), lat, c, rot, bathy, Logger::null(), nullptr));
  return extract_leaves(m, lat);
}

config::BoxRule km_box(double lon_min, double lon_max, double lat_min, double lat_max, double size_km) {
  config::BoxRule r{lon_min, lon_max, lat_min, lat_max, 0};
  r.size_km = size_km;
  return r;
}

InRange box_range(const config::BoxRule& r) {
  return [r](double lon, double la) {
    return la >= r.lat_min_deg && la <= r.lat_max_deg && lon >= r.lon_min_deg && lon <= r.lon_max_deg;
  };
}

struct Case {
  const char* name;
  bool mercator;
  bool rotated;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class KmBoxRule : public ::testing::TestWithParam<Case> {};

// Δ0 = 15°, L = 5, a 150 km target: the level asked goes from 3 near the equator to 2 and 1
// toward the poles (Mercator) — every leaf must be the one the per-pixel reference gives, and
// leaves whose centre is in the box are no larger than √2 × 150 km.
TEST_P(KmBoxRule, LeavesTakeTheLevelNearestTheTargetAtTheirLatitude) {
  const Case c = GetParam();
  const Lattice lat = c.mercator ? Lattice::make_mercator(15.0, 5, -180.0, 80.0) : Lattice::make(15.0, 5, -180.0);
  const PoleRotation rot = c.rotated ? PoleRotation(-44.858333, 78.141667) : PoleRotation();
  config::QuadtreeOptions o;
  o.box_rules.push_back(km_box(-100.0, 40.0, -70.0, 78.0, 150.0));
  const std::vector<Leaf> leaves = leaves_with(lat, o, rot);
  const std::vector<int> got = testing::level_map(leaves, lat);
  const std::vector<int> want = naive_levels(lat, rot, {{box_range(o.box_rules[0]), 150.0}});
  std::int64_t differ = 0;
  for (std::size_t k = 0; k < got.size(); ++k) differ += got[k] != want[k] ? 1 : 0;
  EXPECT_EQ(differ, 0);

  // The guarantee in physical terms, and that the level follows the latitude.
  std::vector<int> seen(static_cast<std::size_t>(lat.levels) + 1, 0);
  for (const Leaf& f : leaves) {
    const double row = centre_row(lat, f);
    double lon = 0.0, la = 0.0;
    rot.to_geographic(lat.lon0_deg + (static_cast<double>(f.a) + 0.5) * lat.step0_deg / (1 << f.level),
                      row_lat(lat, row), lon, la);
    if (!box_range(o.box_rules[0])(lon, la)) continue;
    ++seen[static_cast<std::size_t>(f.level)];
    EXPECT_LE(size_km_at(lat, f.level, row), std::sqrt(2.0) * 150.0 * (1 + 1e-12)) << f.level << " " << f.b;
  }
  if (c.mercator) {
    EXPECT_GT(seen[1] + seen[2], 0);  // poleward: coarser levels reach 150 km
    EXPECT_GT(seen[3], 0);            // equatorward: level 3 (208 km · cos φ′)
  }
  // Without the rule every leaf is a level-0 square.
  EXPECT_EQ(leaves_with(lat, config::QuadtreeOptions(), rot).size(),
            static_cast<std::size_t>((lat.nx >> lat.levels) * (lat.ny >> lat.levels)));
}

INSTANTIATE_TEST_SUITE_P(Lattices, KmBoxRule,
                         ::testing::Values(Case{"Mercator", true, false}, Case{"MercatorRotated", true, true},
                                           Case{"LonLat", false, false}, Case{"LonLatRotated", false, true}),
                         [](const ::testing::TestParamInfo<Case>& i) { return std::string(i.param.name); });

TEST(KmRules, ABoxSmallerThanTheSquaresStillRefinesTheSquaresOverIt) {
  // A 1° box around the centre of a level-0 square (15°, 1668 km · cos φ′): the size form is a
  // term of the size field, so every square holding a field cell whose centre is in the box is
  // split while larger than √2 × 150 km (a level rule samples only the grid below its level and
  // would leave the square whole).
  const Lattice lat = Lattice::make_mercator(15.0, 5, -180.0, 80.0);
  const std::int64_t b0 = (lat.ny >> lat.levels) / 2;
  const double c_lat = row_lat(lat, (static_cast<double>(b0) + 0.5) * 32.0);
  config::QuadtreeOptions o;
  o.box_rules.push_back(km_box(-173.0, -172.0, c_lat - 0.5, c_lat + 0.5, 150.0));
  const std::vector<Leaf> leaves = leaves_with(lat, o, PoleRotation());
  EXPECT_EQ(testing::level_map(leaves, lat), naive_levels(lat, PoleRotation(), {{box_range(o.box_rules[0]), 150.0}}));
  ASSERT_GT(leaves.size(), static_cast<std::size_t>((lat.nx >> lat.levels) * (lat.ny >> lat.levels)) + 3);
  for (int c = 0; c < 4; ++c) {  // the level-0 square is split
    const Leaf whole{0, 0, b0};
    EXPECT_EQ(std::find(leaves.begin(), leaves.end(), whole), leaves.end()) << c;
  }
}

TEST(KmRules, DepthRuleInKilometresUsesTheRasterThroughTheRotation) {
  // Depth grows with geographic latitude: elevation = -100·(φ + 90) m; [9000, 13000) m is φ in [0°, 40°).
  const std::int64_t nc = 361, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t col = 0; col < nc; ++col)
      v[static_cast<std::size_t>(r * nc + col)] = -100.0f * static_cast<float>(r);
  const raster::Bathymetry bathy = raster::Bathymetry::from_grid(v, nc, nr, -180.0, -90.0, 1.0, 1.0);
  const Lattice lat = Lattice::make_mercator(15.0, 5, -180.0, 80.0);
  const PoleRotation rot(-44.858333, 78.141667);
  config::QuadtreeOptions o;
  config::DepthRule rule{9000.0, 13000.0, 0};
  rule.size_km = 120.0;
  o.depth_rules.push_back(rule);
  const InRange in_range = [&](double lon, double la) {
    const double depth = -bathy.sample(lon, la);
    return depth >= 9000.0 && depth < 13000.0;
  };
  const std::vector<int> got = testing::level_map(leaves_with(lat, o, rot, &bathy), lat);
  const std::vector<int> want = naive_levels(lat, rot, {{in_range, 120.0}});
  std::int64_t differ = 0, refined = 0;
  for (std::size_t k = 0; k < got.size(); ++k) {
    differ += got[k] != want[k] ? 1 : 0;
    refined += got[k] > 0 ? 1 : 0;
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(refined, 0);
}

TEST(KmRules, TheFinestRuleWinsWithLevelRulesAndOtherSizeRules) {
  const Lattice lat = Lattice::make_mercator(15.0, 5, -180.0, 80.0);
  const PoleRotation rot(-44.858333, 78.141667);
  config::QuadtreeOptions a, b, both;
  a.box_rules.push_back(km_box(-100.0, 40.0, -70.0, 78.0, 150.0));
  b.box_rules.push_back({0.0, 90.0, -30.0, 30.0, 4});
  b.box_rules.push_back(km_box(-20.0, 60.0, 10.0, 60.0, 60.0));
  both.box_rules = a.box_rules;
  both.box_rules.insert(both.box_rules.end(), b.box_rules.begin(), b.box_rules.end());
  const std::vector<int> la = testing::level_map(leaves_with(lat, a, rot), lat);
  const std::vector<int> lb = testing::level_map(leaves_with(lat, b, rot), lat);
  const std::vector<int> lboth = testing::level_map(leaves_with(lat, both, rot), lat);
  std::int64_t differ = 0, a_finer = 0, b_finer = 0;
  for (std::size_t k = 0; k < la.size(); ++k) {
    differ += lboth[k] != std::max(la[k], lb[k]) ? 1 : 0;
    a_finer += la[k] > lb[k] ? 1 : 0;
    b_finer += lb[k] > la[k] ? 1 : 0;
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(a_finer, 0);
  EXPECT_GT(b_finer, 0);
}

TEST(KmRules, TargetsBeyondTheLevelsClampToLevelLOrLeaveLevelZero) {
  const Lattice lat = Lattice::make_mercator(15.0, 4, -180.0, 80.0);  // pixels ≥ 18 km (at 80°)
  config::QuadtreeOptions fine, coarse;
  fine.box_rules.push_back(km_box(-100.0, 40.0, -70.0, 78.0, 1.0));
  coarse.box_rules.push_back(km_box(-100.0, 40.0, -70.0, 78.0, 5000.0));
  const auto in_box = box_range(fine.box_rules[0]);
  const std::vector<Leaf> fl = leaves_with(lat, fine, PoleRotation());
  int finest = 0;
  for (const Leaf& f : fl) {
    const double row = centre_row(lat, f);
    const double lon = lat.lon0_deg + (static_cast<double>(f.a) + 0.5) * lat.step0_deg / (1 << f.level);
    if (in_box(lon, row_lat(lat, row))) {
      EXPECT_EQ(f.level, lat.levels);
      ++finest;
    }
  }
  EXPECT_GT(finest, 0);
  EXPECT_EQ(leaves_with(lat, coarse, PoleRotation()), leaves_with(lat, config::QuadtreeOptions(), PoleRotation()));
  // What the report and log say the rule asks: the equator row and the lattice's last row.
  EXPECT_EQ(level_for_size(lat, 1.0, lat.row_of_lat(0.0)), lat.levels);
  EXPECT_EQ(level_for_size(lat, 5000.0, lat.row_of_lat(0.0)), 0);
  // 150 km at the equator: level 0 is 1668 km, so 2^l >= 1668 / (√2·150) = 7.9: level 3.
  EXPECT_EQ(level_for_size(lat, 150.0, lat.row_of_lat(0.0)), 3);
  // At 60°: 834 km, 2^l >= 3.9: level 2.
  EXPECT_EQ(level_for_size(lat, 150.0, lat.row_of_lat(60.0)), 2);
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_km_rules_test

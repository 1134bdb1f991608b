// SPDX-License-Identifier: GPL-3.0-or-later
// Levels chosen by physical size (issue 12): on an all-ocean Mercator lattice the open-ocean rule
// puts every leaf within √2 of the target from the equator to the rows' end, where the level-0
// squares allow it; the lon-lat lattice's squares are sized by √cos φ; the coastal rule stops the
// band at the level nearest its target; and bad targets name the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/leaves.hpp"
#include "size/size_field.hpp"

namespace aq::quadtree::unit_quadtree_size_rules_test {
namespace {

// quadtree.size_km / coast_size_km / coast_band as the size field carries them (size/size_field.hpp).
void apply_size_rules(LevelMasks& m, const Lattice& lat, double size_km, double coast_km, int band) {
  config::GlobalConfig c;
  c.quadtree.size_km = size_km;
  c.quadtree.coast_size_km = coast_km;
  c.quadtree.coast_band = band;
  apply_size_field(m, lat, size::build_size_field(m.filled(), lat, c, PoleRotation(), nullptr, Logger::null(), nullptr));
}

Bitmap all_filled(const Lattice& lat) {
  Bitmap b(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) b.set(i, j);
  return b;
}

std::vector<Leaf> leaves_with_sizes(const Bitmap& filled, const Lattice& lat, double size_km, double coast_km,
                                    int band) {
  LevelMasks m = make_level_masks(filled, lat, 0);
  apply_size_rules(m, lat, size_km, coast_km, band);
  (void)balance(m, BalanceMode::kFace);
  return extract_leaves(m, lat);
}

double leaf_km(const Lattice& lat, const Leaf& f) {
  return square_size_km(lat, f.level,
                        static_cast<double>(leaf_j0(lat, f)) + 0.5 * static_cast<double>(leaf_size(lat, f)));
}

TEST(SizeRules, OpenOceanLeavesAreWithinSqrt2OfTheTargetAtEveryLatitude) {
  // Δ0 = 15°: level 0 is 1668 km at the equator and still 290 km at 80°; L = 6: 26 km pixels.
  const Lattice lat = Lattice::make_mercator(15.0, 6, -180.0, 80.0);
  const double target = 200.0;
  const auto leaves = leaves_with_sizes(all_filled(lat), lat, target, 0.0, 0);
  ASSERT_FALSE(leaves.empty());
  int coarse_enough = 0;
  for (const Leaf& f : leaves) {
    const double s = leaf_km(lat, f);
    ASSERT_LE(s, std::sqrt(2.0) * target * (1 + 1e-12)) << f.level << " " << f.b;
    // Where level 0 is coarse enough, the leaf is not finer than target/√2 either.
    const double level0 = leaf_km(lat, Leaf{0, 0, f.b >> f.level});
    if (level0 >= target / std::sqrt(2.0)) {
      ++coarse_enough;
      ASSERT_GE(s, target / std::sqrt(2.0) * (1 - 1e-12)) << f.level << " " << f.b << " " << s;
    }
  }
  EXPECT_GT(coarse_enough, static_cast<int>(leaves.size()) * 9 / 10);
  // The same lattice without the rule: level-0 squares of 1668 km.
  double largest = 0.0;
  for (const Leaf& f : leaves_with_sizes(all_filled(lat), lat, 0.0, 0.0, 0))
    largest = std::max(largest, leaf_km(lat, f));
  EXPECT_GT(largest, 1000.0);
}

TEST(SizeRules, LonLatSquaresAreSizedByTheRootOfTheirArea) {
  const Lattice lat = Lattice::make(4.0, 3, -180.0);
  // Level 0 at the equator: 4° of the equator; at 60°: √cos 60° of that.
  EXPECT_NEAR(square_size_km(lat, 0, static_cast<double>(lat.ny) / 2), 4.0 * kEarthRadiusKm * kDegToRad, 1e-9);
  EXPECT_NEAR(square_size_km(lat, 1, lat.row_of_lat(60.0)), 2.0 * kEarthRadiusKm * kDegToRad * std::sqrt(0.5), 1e-9);
}

TEST(SizeRules, TheCoastalBandStopsAtTheLevelNearestItsTarget) {
  const Lattice lat = Lattice::make_mercator(4.0, 3, -180.0, 80.0);  // pixels 55.6 km · cos φ′
  Bitmap filled = all_filled(lat);
  // A dry column of pixels (a "coast" on both sides of it) from pole to pole.
  Bitmap cut(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i)
      if (i != 100) cut.set(i, j);
  filled = cut;
  const double coast = 100.0;
  const auto leaves = leaves_with_sizes(filled, lat, 0.0, coast, 2);
  int band_leaves = 0, band_coarser_than_pixels = 0;
  for (const Leaf& f : leaves) {
    const std::int64_t i0 = leaf_i0(lat, f), side = leaf_size(lat, f);
    if (i0 > 102 || i0 + side - 1 < 98) continue;  // holds no pixel of the band (radius 2)
    ++band_leaves;
    // No band leaf is coarser than √2 × the target (the rule's guarantee) ...
    EXPECT_LE(leaf_km(lat, f), std::sqrt(2.0) * coast * (1 + 1e-12)) << f.level << " " << f.a << " " << f.b;
    band_coarser_than_pixels += f.level < lat.levels ? 1 : 0;
  }
  // ... and the band is not split to the pixels everywhere (a band of radius 2 with the rule off
  // would be pixels only): at low latitudes its level-2 squares (111 km) are within √2 of 100 km.
  EXPECT_GT(band_leaves, 0);
  EXPECT_GT(band_coarser_than_pixels, 0);
  LevelMasks plain = make_level_masks(filled, lat, 2);
  (void)balance(plain, BalanceMode::kFace);
  EXPECT_LT(leaves.size(), extract_leaves(plain, lat).size());
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_size_rules_test

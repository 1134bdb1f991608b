// SPDX-License-Identifier: GPL-3.0-or-later
// Quantisation of a graded size field into quadtree levels (apply_size_field): on an all-ocean
// Mercator lattice with a field h = h0 + g·dist to a point, every leaf is at most √2 × the field's
// minimum over it, no leaf is split below what the field or the 2:1 balance asks, and the achieved
// sizes obey a(x) <= 2·a(y) + √2·g·d(x, y) plus the slack of one parent square (ARCHITECTURE §4.10).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/types.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/leaves.hpp"
#include "size/limit_gradient.hpp"

namespace aq::quadtree::unit_quadtree_size_field_test {
namespace {

Bitmap all_filled(const Lattice& lat) {
  Bitmap b(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) b.set(i, j);
  return b;
}

double leaf_km(const Lattice& lat, const Leaf& f) {
  return square_size_km(lat, f.level, static_cast<double>(leaf_j0(lat, f)) + 0.5 * static_cast<double>(leaf_size(lat, f)));
}

struct Built {
  Lattice lat;
  size::SizeField field;
  std::vector<Leaf> leaves;
  std::int64_t forced = 0;
};

Built build(double g) {
  Built b{Lattice::make_mercator(15.0, 6, -180.0, 70.0), {}, {}, 0};
  const size::FieldGrid grid(b.lat, 6);
  std::vector<double> h(static_cast<std::size_t>(grid.cells()), std::numeric_limits<double>::infinity());
  h[static_cast<std::size_t>(grid.index(grid.nx() / 3, grid.ny() / 2))] = 30.0;
  size::limit_gradient(grid, h, g);
  std::vector<float> hf(h.begin(), h.end());
  b.field = size::SizeField(grid, hf, 0.0, 0);
  LevelMasks m = make_level_masks(all_filled(b.lat), b.lat, 0);
  apply_size_field(m, b.lat, b.field);
  b.forced = balance(m, BalanceMode::kFace).forced_splits;
  b.leaves = extract_leaves(m, b.lat);
  return b;
}

TEST(SizeField, EveryLeafIsWithinSqrt2OfTheFieldOverIt) {
  const Built b = build(0.2);
  ASSERT_GT(b.leaves.size(), 100u);
  int at_target = 0;
  for (const Leaf& f : b.leaves) {
    const double a = leaf_km(b.lat, f), h = b.field.grid_min_over_square(f.level, f.a, f.b);
    ASSERT_LE(a, std::sqrt(2.0) * h * (1 + 1e-9)) << f.level << " " << f.a << " " << f.b;
    // The parent was split for the field (or the balance): it was larger than √2·h over it.
    if (f.level > 0 && 2.0 * a > std::sqrt(2.0) * b.field.grid_min_over_square(f.level - 1, f.a / 2, f.b / 2)) ++at_target;
  }
  EXPECT_GT(at_target, static_cast<int>(b.leaves.size()) / 2);
}

TEST(SizeField, AchievedSizesObeyTheGrading) {
  const double g = 0.2;
  const Built b = build(g);
  const size::FieldGrid grid(b.lat, 6);
  std::int64_t violations = 0, pairs = 0;
  // Leaf centres as cells of the field grid (level 6 = pixels); pairs among a sample of leaves.
  const auto centre_cell = [&](const Leaf& f) {
    const std::int64_t s = leaf_size(b.lat, f);
    return grid.index(leaf_i0(b.lat, f) + s / 2, leaf_j0(b.lat, f) + s / 2);
  };
  for (std::size_t x = 0; x < b.leaves.size(); x += 7) {
    for (std::size_t y = 0; y < b.leaves.size(); y += 5) {
      const Leaf& fx = b.leaves[x];
      const Leaf& fy = b.leaves[y];
      const double ax = leaf_km(b.lat, fx), ay = leaf_km(b.lat, fy);
      const double d = grid.distance_km(centre_cell(fx), centre_cell(fy));
      ++pairs;
      // Slack: y's parent square (2·ay across) may hold the minimum that split it.
      if (ax > 2.0 * ay + std::sqrt(2.0) * g * (d + 2.0 * std::sqrt(2.0) * ay) * (1 + 1e-9)) ++violations;
    }
  }
  EXPECT_GT(pairs, 1000);
  EXPECT_EQ(violations, 0);
}

TEST(SizeField, SteeperFieldGivesMoreLevelStepsPerDistance) {
  // A smaller g keeps the fine squares over a wider area: more leaves.
  EXPECT_GT(build(0.1).leaves.size(), build(0.4).leaves.size());
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_size_field_test

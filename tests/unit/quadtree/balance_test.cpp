// SPDX-License-Identifier: GPL-3.0-or-later
// 2:1 smoothing and its checker (balance.hpp), against a naive per-pixel checker and the naive
// ripple algorithm.
#include "quadtree/balance.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "quadtree/build_leaves.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::quadtree::unit_quadtree_balance_test {
namespace {

using testing::make_lattice;
using testing::naive_violations;
using testing::random_mask;

struct Case {
  std::uint32_t seed;
  BalanceMode mode;
};

class BalanceRandom : public ::testing::TestWithParam<Case> {};

TEST_P(BalanceRandom, ViolationsBeforeNoneAfterOnlySplits) {
  const Case c = GetParam();
  const bool corner = c.mode == BalanceMode::kCorner;
  const Lattice lat = make_lattice(45.0, 5);  // 256 × 128 pixels, 5 levels
  const Bitmap m = random_mask(lat.nx, lat.ny, c.seed, 0.6, 0.004, 24);
  const std::vector<Leaf> before = extract_leaves(make_level_masks(m, lat, 0), lat);
  const std::int64_t v0 = count_balance_violations(before, lat, c.mode);
  EXPECT_GT(v0, 0);
  EXPECT_GT(naive_violations(before, lat, corner), 0);

  const std::vector<Leaf> after = balance_leaves(before, lat, c.mode);
  EXPECT_EQ(count_balance_violations(after, lat, c.mode), 0);
  EXPECT_EQ(naive_violations(after, lat, corner), 0);
  EXPECT_TRUE(leaves_sorted(after, lat));
  EXPECT_EQ(leaf_coverage(after, lat), m);
  EXPECT_GT(after.size(), before.size());

  // Only splits: every output leaf lies inside an input leaf of the same or a coarser level;
  // input leaves of level L are all still there.
  const LeafLocator in(before, lat);
  for (const Leaf& f : after) {
    const std::int64_t k = in.find(leaf_i0(lat, f), leaf_j0(lat, f));
    ASSERT_GE(k, 0);
    const Leaf& g = before[static_cast<std::size_t>(k)];
    ASSERT_LE(g.level, f.level);
    ASSERT_EQ(f.a >> (f.level - g.level), g.a);
    ASSERT_EQ(f.b >> (f.level - g.level), g.b);
  }
  const LeafLocator out(after, lat);
  for (const Leaf& g : before) {
    if (g.level != lat.levels) continue;
    ASSERT_EQ(after[static_cast<std::size_t>(out.find(g.a, g.b))], g);
  }

  // The unique coarsest balanced refinement: the naive ripple gives the same leaves.
  EXPECT_EQ(after, testing::naive_balance(before, lat, corner));
  // Balancing a balanced set changes nothing.
  EXPECT_EQ(balance_leaves(after, lat, c.mode), after);
}

INSTANTIATE_TEST_SUITE_P(Seeds, BalanceRandom,
                         ::testing::Values(Case{1, BalanceMode::kFace}, Case{2, BalanceMode::kFace},
                                           Case{3, BalanceMode::kFace}, Case{1, BalanceMode::kCorner},
                                           Case{2, BalanceMode::kCorner}, Case{3, BalanceMode::kCorner}));

// The stage counts the violations on the balanced pyramid instead of one rebuilt from the
// extracted leaves: the rebuilt pyramid is the same bitmaps, so the count is the same, before
// the balance (violations) and after it (none), in both modes.
TEST(Balance, ViolationsOnThePyramidAreThoseOfItsLeaves) {
  const Lattice lat = make_lattice(45.0, 5);
  for (const std::uint32_t seed : {5u, 6u}) {
    const Bitmap m = random_mask(lat.nx, lat.ny, seed, 0.6, 0.004, 24);
    for (const BalanceMode mode : {BalanceMode::kFace, BalanceMode::kCorner}) {
      LevelMasks masks = make_level_masks(m, lat, 2);
      for (int pass = 0; pass < 2; ++pass) {  // as built, then balanced
        const std::vector<Leaf> leaves = extract_leaves(masks, lat);
        const LevelMasks rebuilt = masks_from_leaves(leaves, lat);
        ASSERT_EQ(rebuilt.omega.size(), masks.omega.size());
        for (std::size_t l = 0; l < masks.omega.size(); ++l) EXPECT_EQ(rebuilt.omega[l], masks.omega[l]) << l;
        const std::int64_t v = count_balance_violations(masks, mode);
        EXPECT_EQ(v, count_balance_violations(leaves, lat, mode));
        if (pass == 0) {
          EXPECT_GT(v, 0);
        } else {
          EXPECT_EQ(v, 0);
        }
        EXPECT_NO_THROW(check_leaves_per_level(leaves, count_leaves_per_level(masks)));
        balance(masks, mode);
      }
    }
  }
  const std::vector<Leaf> two = {{0, 0, 0}, {1, 2, 0}};
  EXPECT_THROW(check_leaves_per_level(two, {1, 0}), InternalError);  // one leaf of level 1 too many
  EXPECT_THROW(check_leaves_per_level(two, {2}), InternalError);     // a level beyond the pyramid
  EXPECT_NO_THROW(check_leaves_per_level(two, {1, 1}));
}

TEST(Balance, CornerModeRefinesAtLeastAsMuchAsFace) {
  const Lattice lat = make_lattice(45.0, 5);
  const Bitmap m = random_mask(lat.nx, lat.ny, 4u, 0.6, 0.004, 24);
  const std::vector<Leaf> before = extract_leaves(make_level_masks(m, lat, 0), lat);
  const std::vector<Leaf> face = balance_leaves(before, lat, BalanceMode::kFace);
  const std::vector<Leaf> corner = balance_leaves(before, lat, BalanceMode::kCorner);
  EXPECT_GT(corner.size(), face.size());
  EXPECT_GT(count_balance_violations(face, lat, BalanceMode::kCorner), 0);
  EXPECT_EQ(count_balance_violations(corner, lat, BalanceMode::kFace), 0);
}

TEST(Balance, DiagonalOnlyViolationIsACornerViolation) {
  // L = 2, 4×4-pixel roots. Root (0,0) is one level-0 leaf; its NE corner touches a single pixel
  // leaf at (4,4) diagonally (pixels (4,3) and (3,4) empty).
  const Lattice lat = make_lattice(90.0, 2);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < 4; ++j)
    for (std::int64_t i = 0; i < 4; ++i) m.set(i, j);
  m.set(4, 4);
  const std::vector<Leaf> leaves = extract_leaves(make_level_masks(m, lat, 0), lat);
  EXPECT_EQ(count_balance_violations(leaves, lat, BalanceMode::kFace), 0);
  EXPECT_EQ(count_balance_violations(leaves, lat, BalanceMode::kCorner), 1);
  const std::vector<Leaf> fixed = balance_leaves(leaves, lat, BalanceMode::kCorner);
  EXPECT_EQ(fixed.size(), 5u);  // root (0,0) split into 4 level-1 leaves, plus the pixel
}

TEST(Balance, WorksAcrossTheSeam) {
  // L = 3, 8×8-pixel roots, nx = 32. A level-0 leaf at the east edge (root a0 = 3, pixels
  // 24..31 × 0..7) and a single pixel just across the seam at (0, 3): neighbours 3 levels apart.
  const Lattice lat = make_lattice(90.0, 3);
  ASSERT_EQ(lat.nx, 32);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < 8; ++j)
    for (std::int64_t i = 24; i < 32; ++i) m.set(i, j);
  m.set(0, 3);
  const std::vector<Leaf> before = extract_leaves(make_level_masks(m, lat, 0), lat);
  ASSERT_EQ(before.size(), 2u);
  EXPECT_EQ(count_balance_violations(before, lat, BalanceMode::kFace), 1);
  EXPECT_EQ(naive_violations(before, lat, false), 2);  // the pair seen from both pixels
  const std::vector<Leaf> after = balance_leaves(before, lat, BalanceMode::kFace);
  EXPECT_EQ(count_balance_violations(after, lat, BalanceMode::kFace), 0);
  // Across the seam from pixel (0, 3) is now the level-2 leaf (15, 1) (pixels 30..31 × 2..3),
  // inside the split level-1 square (7, 0); the rest of the root became level-1 leaves.
  const LeafLocator loc(after, lat);
  EXPECT_EQ(after[static_cast<std::size_t>(loc.find(31, 3))], (Leaf{2, 15, 1}));
  EXPECT_EQ(after[static_cast<std::size_t>(loc.find(-1, 3))], (Leaf{2, 15, 1}));
  EXPECT_EQ(after[static_cast<std::size_t>(loc.find(28, 7))], (Leaf{1, 7, 1}));
  EXPECT_EQ(after.size(), 1u + 3u + 4u);
}

TEST(Balance, ModeNames) {
  EXPECT_EQ(parse_name<BalanceMode>("face"), BalanceMode::kFace);
  EXPECT_EQ(parse_name<BalanceMode>("corner"), BalanceMode::kCorner);
  EXPECT_FALSE(parse_name<BalanceMode>("edge").has_value());
  EXPECT_EQ(fmt::format("{}-balanced", BalanceMode::kCorner), "corner-balanced");  // fmt prints the name
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_balance_test

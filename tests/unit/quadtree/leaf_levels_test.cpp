// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel levels painted from leaves (quadtree/leaf_levels.hpp), in bands of rows, including a
// leaf taller than a band.
#include "quadtree/leaf_levels.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aq::quadtree::unit_quadtree_leaf_levels_test {
namespace {

TEST(LeafLevels, PaintsEachLeafsPixelsWithItsLevel) {
  const Lattice lat = Lattice::make(90.0, 2, -180.0);  // 16 x 8 pixels
  ASSERT_EQ(lat.nx, 16);
  ASSERT_EQ(lat.ny, 8);
  const std::vector<Leaf> leaves{{0, 0, 0}, {1, 3, 1}, {2, 5, 6}};
  const LeafLevels levels(leaves, lat);
  std::vector<std::uint8_t> out(16 * 8);
  levels.fill(0, 8, out.data());
  for (std::int64_t j = 0; j < 8; ++j)
    for (std::int64_t i = 0; i < 16; ++i) {
      std::uint8_t expect = 255;
      if (i < 4 && j < 4) expect = 0;
      if (i >= 6 && i < 8 && j >= 2 && j < 4) expect = 1;
      if (i == 5 && j == 6) expect = 2;
      EXPECT_EQ(out[static_cast<std::size_t>(j * 16 + i)], expect) << i << "," << j;
    }
  std::vector<std::uint8_t> part(16 * 2);
  levels.fill(3, 2, part.data(), 9);
  EXPECT_EQ(part[0], 0);       // (0, 3)
  EXPECT_EQ(part[16 + 0], 9);  // (0, 4): empty value
  EXPECT_EQ(part[7], 1);       // (7, 3)
}

TEST(LeafLevels, LeavesTallerThanABand) {
  const Lattice lat = Lattice::make(90.0, 9, -180.0);  // 2048 x 1024 pixels, level-0 leaves 512 tall
  const std::vector<Leaf> leaves{{0, 0, 1}, {9, 600, 700}};
  const LeafLevels levels(leaves, lat);
  std::vector<std::uint8_t> out(static_cast<std::size_t>(lat.nx) * 3);
  levels.fill(699, 3, out.data());
  EXPECT_EQ(out[0], 0);
  EXPECT_EQ(out[511], 0);
  EXPECT_EQ(out[512], 255);
  EXPECT_EQ(out[static_cast<std::size_t>(lat.nx) + 600], 9);  // (600, 700)
  EXPECT_EQ(out[600], 255);                                   // (600, 699)
}

}  // namespace
}  // namespace aq::quadtree::unit_quadtree_leaf_levels_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The window lattice of a regional run (core/lattice.hpp): a block of the global lattice whose
// vertices have the same coordinates, bit for bit, as the global vertices they are.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/lattice.hpp"

namespace unit_core_window_lattice_test {

namespace {

using aq::Lattice;

TEST(WindowLattice, VerticesHaveTheGlobalBits) {
  for (const bool merc : {false, true}) {
    const Lattice g = merc ? Lattice::make_mercator(0.26666666666666666, 6, -180.0, 85.0)
                           : Lattice::make(0.26666666666666666, 6, -180.0);
    const std::int64_t sq = g.pixels_per_square(0);
    const Lattice w = Lattice::window(g, 700 * sq, 60 * sq, 500 * sq, 45 * sq);
    ASSERT_TRUE(w.windowed());
    EXPECT_FALSE(w.periodic());
    EXPECT_EQ(w.nx, 60 * sq);
    EXPECT_EQ(w.ny, 45 * sq);
    EXPECT_EQ(w.nx_global, g.nx);
    EXPECT_EQ(w.ny_global, g.ny);
    for (std::int64_t i = 0; i <= w.nx; i += 7) EXPECT_EQ(w.lon_of(i), g.lon_of(i + 700 * sq)) << i;
    for (std::int64_t j = 0; j <= w.ny; j += 5) {
      EXPECT_EQ(w.lat_of(j), g.lat_of(j + 500 * sq)) << j;
      EXPECT_EQ(w.plane_y_of(j), g.plane_y_of(j + 500 * sq)) << j;
      EXPECT_EQ(w.lat_of_row(static_cast<double>(j) + 0.5), g.lat_of_row(static_cast<double>(j + 500 * sq) + 0.5)) << j;
      EXPECT_NEAR(w.row_of_lat(w.lat_of(j)), static_cast<double>(j), 1e-6) << j;
      EXPECT_FALSE(w.pole_row(j));
    }
    EXPECT_EQ(w.lat_max_deg(), g.lat_max_deg());
    EXPECT_EQ(w.lon_at(3.5), g.lon_at(3.5 + static_cast<double>(700 * sq)));
    EXPECT_DOUBLE_EQ(w.col_of_lon(w.lon_of(17)), 17.0);
    // A point west of the window is west of column 0, not wrapped to its east end.
    EXPECT_LT(w.col_of_lon(w.lon_of(0) - 1.0), 0.0);
  }
}

TEST(WindowLattice, AcrossTheSeamTheColumnsAreContiguous) {
  const Lattice g = Lattice::make(2.0, 2, -180.0);  // 0.5° pixels, 720 columns
  const Lattice w = Lattice::window(g, -8, 40, 100, 40);  // 184°W..164°W, i.e. 176°E..196°E
  EXPECT_EQ(w.i_origin, 712);
  EXPECT_EQ(w.lon_of(0), 176.0);
  EXPECT_EQ(w.lon_of(w.nx), 196.0);
  EXPECT_DOUBLE_EQ(w.col_of_lon(-170.0), 28.0);  // 190°E
  EXPECT_DOUBLE_EQ(w.col_of_lon(178.0), 4.0);
}

TEST(WindowLattice, RowsClampToThePolesWhichStayPoles) {
  const Lattice g = Lattice::make(2.0, 2, -180.0);
  const Lattice w = Lattice::window(g, 0, 80, g.ny - 20, 40);
  EXPECT_EQ(w.ny, 20);
  EXPECT_EQ(w.lat_of(w.ny), 90.0);
  EXPECT_TRUE(w.pole_row(w.ny));
  EXPECT_FALSE(w.pole_row(0));
  // All longitudes: periodic again.
  const Lattice all = Lattice::window(g, -4, g.nx + 8, 0, g.ny);
  EXPECT_TRUE(all.periodic());
  EXPECT_FALSE(all.windowed());
  EXPECT_THROW(Lattice::window(g, 1, 40, 0, 40), aq::InternalError);  // not whole level-0 squares
}

}  // namespace

}  // namespace unit_core_window_lattice_test

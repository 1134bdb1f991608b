// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of seed 004's initial grids (digest B.3): normalised blending, TFI with sections on the swan,
// STAR and the kernel, the boundary-crossing test.
#include "curvilinear/elliptic/initial_grids.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "unit/curvilinear/seed004_domains.hpp"

namespace aq::curvilinear::unit_curvilinear_initial_grids_test {
namespace {

TEST(Blending, NormalisedWeightsSumToOneAndInterpolateTheirSections) {
  const std::vector<double> q{0.0, 0.333, 0.666, 1.0};  // Fig. 3a
  std::vector<double> a;
  for (int k = 0; k <= 1000; ++k) {
    const double x = k / 1000.0;
    blending_weights(q, x, a);
    EXPECT_NEAR(std::accumulate(a.begin(), a.end(), 0.0), 1.0, 1e-14) << x;
    for (const double v : a) EXPECT_GE(v, 0.0);
  }
  for (std::size_t l = 0; l < q.size(); ++l) {
    blending_weights(q, q[l], a);
    for (std::size_t m = 0; m < q.size(); ++m) EXPECT_NEAR(a[m], l == m ? 1.0 : 0.0, 1e-14) << l << " " << m;
  }
}

TEST(Blending, ThePapersWeightsAreNotAPartitionOfUnity) {
  std::vector<double> a;
  raw_blending_weights({0.0, 1.0}, 0.5, a);  // cos⁴ + sin⁴ at π/4
  EXPECT_NEAR(a[0] + a[1], 0.5, 1e-14);
  raw_blending_weights({0.0, 0.333, 0.666, 1.0}, 0.1665, a);
  EXPECT_NEAR(std::accumulate(a.begin(), a.end(), 0.0), 0.72, 0.01);  // the digest's number
}

TEST(Tfi, ReproducesAUniformRectangleWithAndWithoutSections) {
  const Grid2D exact = test::rectangle(21, 11, 2.0, 1.0);
  for (const std::vector<int>& cols : {std::vector<int>{}, std::vector<int>{5, 10, 14}}) {
    Grid2D g = exact;
    for (int j = 1; j < 10; ++j)
      for (int i = 1; i < 20; ++i)
        if (std::find(cols.begin(), cols.end(), i) == cols.end()) g.x[g.at(i, j)] = g.y[g.at(i, j)] = 99.0;
    tfi_fill(g, cols);
    for (std::size_t k = 0; k < g.x.size(); ++k) {
      EXPECT_NEAR(g.x[k], exact.x[k], 1e-14);
      EXPECT_NEAR(g.y[k], exact.y[k], 1e-14);
    }
  }
}

TEST(Tfi, SwanFoldsWithClassicTfiAndOneSectionRemovesTheFold) {
  // Seed 004 Figs. 4–5: classic TFI gives self-intersecting cells; one internal section q1 = 1/2
  // (straight, from the bottom node to the top node of the middle column) gives a valid grid.
  constexpr int L = 21, M = 21;
  Grid2D classic = test::swan_boundary(L, M);
  tfi_fill(classic, {});
  const int folded = self_intersecting_cells(classic);
  EXPECT_GT(folded, 0);
  EXPECT_GT(boundary_crossings(classic), 0);
  Grid2D sectioned = test::swan_boundary(L, M);
  set_section_column(sectioned, Section{(L - 1) / 2, {}}, {});
  tfi_fill(sectioned, {(L - 1) / 2});
  EXPECT_EQ(self_intersecting_cells(sectioned), 0);
  EXPECT_EQ(boundary_crossings(sectioned), 0);
  EXPECT_GT(check_grid(sectioned).f1.worst, 0.0);
  std::printf("swan %dx%d: classic TFI %d self-intersecting cells; with one section 0\n", L, M, folded);
}

// Sections along η (rows): the swan turned on its side (x and y exchanged, and ξ and η, which
// keeps the orientation) folds under classic TFI, and one row section q2 = 1/2 removes the fold;
// the grid is exactly the turned grid of the column section.
TEST(Tfi, RowSectionsOnTheTurnedSwan) {
  constexpr int L = 21, M = 21;
  const auto turn = [](const Grid2D& g) {
    Grid2D t = transposed(g);
    t.x.swap(t.y);
    return t;
  };
  const Grid2D turned_boundary = turn(test::swan_boundary(L, M));
  Grid2D classic = turned_boundary;
  tfi_with_sections(classic, {}, SectionLines::kRows, {});
  EXPECT_GT(self_intersecting_cells(classic), 0);
  Grid2D rows = turned_boundary;
  tfi_with_sections(rows, {Section{(M - 1) / 2, {}}}, SectionLines::kRows, {});
  EXPECT_EQ(self_intersecting_cells(rows), 0);
  EXPECT_EQ(boundary_crossings(rows), 0);
  Grid2D cols = test::swan_boundary(L, M);
  tfi_with_sections(cols, {Section{(L - 1) / 2, {}}}, SectionLines::kColumns, {});
  const Grid2D expected = turn(cols);
  EXPECT_EQ(rows.x, expected.x);
  EXPECT_EQ(rows.y, expected.y);
  // Columns of the turned swan do not help: the fold is across them.
  Grid2D wrong = turned_boundary;
  tfi_with_sections(wrong, {Section{(L - 1) / 2, {}}}, SectionLines::kColumns, {});
  EXPECT_GT(self_intersecting_cells(wrong), 0);
}

TEST(Star, KernelOfAStarShapedAndOfANonStarShapedPolygon) {
  // An L-shaped hexagon: star-shaped, kernel = the unit square at the corner.
  const std::vector<PlanePoint> ell{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto k = polygon_kernel(ell);
  ASSERT_GE(k.size(), 3U);
  double area = 0.0;
  for (std::size_t m = 0; m < k.size(); ++m)
    area += k[m].x * k[(m + 1) % k.size()].y - k[(m + 1) % k.size()].x * k[m].y;
  EXPECT_NEAR(0.5 * area, 1.0, 1e-12);
  // A "U" (two prongs): no point sees both prongs' ends.
  const std::vector<PlanePoint> u{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_TRUE(polygon_kernel(u).empty());
}

TEST(Star, FillsAStarShapedDomainAndRefusesOthers) {
  // The B.8 channel under y = −0.2 cos 2πx is not convex but star-shaped: STAR gives a valid grid.
  Grid2D g = test::wavy_channel_boundary(21, 21, 0.2);
  const PlanePoint pole = star_fill(g, {});
  EXPECT_GT(pole.y, -1.0);
  EXPECT_LT(pole.y, -0.2);
  EXPECT_EQ(self_intersecting_cells(g), 0);
  EXPECT_EQ(boundary_crossings(g), 0);
  EXPECT_GT(check_grid(g).f1.worst, 0.0);
  // The swan is not star-shaped: below the top's tangents at x = 0 and x = 1 lies only y < 0.
  Grid2D swan = test::swan_boundary(21, 21);
  EXPECT_THROW(star_fill(swan, {}), InputError);
}

TEST(Crossings, ALineThroughTheBoundaryIsCounted) {
  Grid2D g = test::rectangle(5, 5, 1.0, 1.0);
  EXPECT_EQ(boundary_crossings(g), 0);
  g.x[g.at(2, 2)] = 1.5;  // interior node pushed out through the east side
  // Its column segments cross x = 1 between boundary nodes; its row segments pass exactly through
  // the boundary node (1, 0.5): a touching, not a proper, intersection.
  EXPECT_EQ(boundary_crossings(g), 2);
  g.y[g.at(2, 2)] = 0.6;  // now all four segments at (2, 2) cross x = 1 between nodes
  EXPECT_EQ(boundary_crossings(g), 4);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_initial_grids_test

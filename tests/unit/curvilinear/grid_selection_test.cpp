// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of seed 004's automatic best-grid choice (digest B.6) on constructed candidate sets whose
// answer follows from the procedure by hand.
#include "curvilinear/elliptic/grid_selection.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace aq::curvilinear::unit_curvilinear_grid_selection_test {
namespace {

Candidate cand(const char* name, std::array<double, 4> worst, std::array<double, 4> avg, int folded = 0,
               int cross = 0) {
  Candidate c;
  c.name = name;
  c.criteria.worst = worst;
  c.criteria.average = avg;
  c.self_intersecting_cells = folded;
  c.boundary_crossings = cross;
  return c;
}

TEST(GridSelection, SequentialFilteringAmongConvexGrids) {
  // A folds (f1 < 0) although its f2..f4 are best: excluded. Among B, C, D:
  //   k = 2: S = B (f2 = 0.5); keep f2_o > 0.70: C (0.80) -> {B, C}; D (0.60) dropped.
  //   k = 3: S = C (f3 = 0.4 > 0.3); keep f3_o > C's 0.60: B (0.65) -> {C, B}.
  //   k = 4: S = B (f4 = 0.5); keep f4_o > B's 0.70: C (0.75) -> {B, C}.
  //   two remain: lexicographic (f2, f3, f4): B (0.5) beats C (0.45).
  const std::vector<Candidate> c{cand("A", {-1, 0.9, 0.9, 0.9}, {0.5, 0.99, 0.99, 0.99}, 3),
                                 cand("B", {0.1, 0.5, 0.3, 0.5}, {0.8, 0.70, 0.65, 0.70}),
                                 cand("C", {0.2, 0.45, 0.4, 0.4}, {0.8, 0.80, 0.60, 0.75}),
                                 cand("D", {0.3, 0.40, 0.2, 0.3}, {0.8, 0.60, 0.90, 0.90})};
  const Selection s = select_best_grid(c);
  EXPECT_EQ(s.chosen, 1);
  EXPECT_EQ(s.steps.size(), 5U);
}

TEST(GridSelection, AFilterStepCanLeaveOneGrid) {
  // k = 2: S = C with the best f2 and the best f2_o: only C remains.
  const std::vector<Candidate> c{cand("B", {0.1, 0.5, 0.3, 0.5}, {0.8, 0.70, 0.65, 0.70}),
                                 cand("C", {0.2, 0.6, 0.1, 0.1}, {0.8, 0.80, 0.10, 0.10})};
  EXPECT_EQ(select_best_grid(c).chosen, 1);
}

TEST(GridSelection, WithoutConvexGridsTheValidOnesCompeteOnF1First) {
  // No grid has f1 > 0. A crosses the boundary: out. B and C are valid; k = 1: S = C (f1 = −0.1),
  // B's f1_o 0.9 > C's 0.5 keeps B; k = 2: S = B (0.3), C's f2_o 0.5 < B's 0.6: only B.
  const std::vector<Candidate> c{cand("A", {-0.05, 0.9, 0.9, 0.9}, {0.99, 0.9, 0.9, 0.9}, 0, 2),
                                 cand("B", {-0.5, 0.3, 0.3, 0.3}, {0.9, 0.6, 0.6, 0.6}),
                                 cand("C", {-0.1, 0.2, 0.2, 0.2}, {0.5, 0.5, 0.5, 0.5})};
  EXPECT_EQ(select_best_grid(c).chosen, 1);
}

TEST(GridSelection, WhenAllFoldTheAveragesDecideLexicographically) {
  const std::vector<Candidate> c{cand("A", {-1, 0.9, 0.9, 0.9}, {0.7, 0.5, 0.9, 0.9}, 1),
                                 cand("B", {-1, 0.1, 0.1, 0.1}, {0.7, 0.6, 0.1, 0.1}, 2),
                                 cand("C", {-1, 0.9, 0.9, 0.9}, {0.6, 0.9, 0.9, 0.9}, 0, 1)};
  EXPECT_EQ(select_best_grid(c).chosen, 1);  // f1_o ties A–B at 0.7; f2_o 0.6 > 0.5
  EXPECT_THROW(select_best_grid({}), InternalError);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_grid_selection_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Consistent masks and depths of a refinement grid and its parent (handoff/nested_bathymetry.hpp):
// synthetic parents and children on index grids. The parent's h over the footprint is the child's
// area-weighted block average (wet points only), exactly; both r-factor bounds hold; the parent is
// only changed by the averages and by deepening; a block average steeper than the parent allows
// deepens the child's block; the blend makes the child's ring the parent's interpolated depth; the
// mask rules (footprint cell = block centre, ring point = parent cell holding it, u/v/ψ products).
#include "handoff/nested_bathymetry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "curvilinear/common/roms_depth.hpp"
#include "handoff/contact_points.hpp"

namespace unit_handoff_nested_bathymetry_test {

namespace {

using aq::curvilinear::RefineBox;
using aq::handoff::NestedDepthInput;
using aq::handoff::NestedDepthResult;

std::size_t at(int ni, int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + i; }

// A parent of (PL+1) x (PM+1) ρ points, a box inside and a child of the box.
struct Case {
  int PL = 20, PM = 16;
  RefineBox box{6, 14, 5, 11, 3};
  NestedDepthInput in;
  int ni() const { return box.L() + 1; }
  int nj() const { return box.M() + 1; }
};

// The parent: a basin deepening eastwards, r-factor ≤ 0.2; the child: its own bathymetry with a
// shelf break running north-south at child column `break_i` (a cliff from `shelf` to `deep` m).
Case make_case(double shelf, double deep, int break_i, double rmax = 0.2) {
  Case c;
  const int pni = c.PL + 1, pnj = c.PM + 1;
  c.in.box = c.box;
  c.in.parent_L = c.PL;
  c.in.parent_M = c.PM;
  c.in.parent_h.resize(static_cast<std::size_t>(pni * pnj));
  c.in.parent_mask.assign(c.in.parent_h.size(), 1);
  for (int j = 0; j < pnj; ++j)
    for (int i = 0; i < pni; ++i) c.in.parent_h[at(pni, i, j)] = 50.0 * std::pow(1.15, i) + 3.0 * j;
  const int ni = c.ni(), nj = c.nj();
  c.in.child_hraw.resize(static_cast<std::size_t>(ni * nj));
  c.in.child_mask.assign(c.in.child_hraw.size(), 1);
  c.in.child_area.resize(c.in.child_hraw.size());
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      c.in.child_hraw[at(ni, i, j)] = (i < break_i ? shelf : deep) + 0.5 * j;
      c.in.child_area[at(ni, i, j)] = 1.0e6 * (1.0 + 0.01 * i + 0.02 * j);  // not uniform
    }
  if (shelf <= 0.0) {
    // No cliff: the parent's own field at the fine points (parent ρ index x = Io + (i − ½)/r − ½)
    // with a bump of ±8 % the parent does not resolve.
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const double x = c.box.i_left + (i - 0.5) / c.box.factor - 0.5,
                     y = c.box.j_bottom + (j - 0.5) / c.box.factor - 0.5;
        c.in.child_hraw[at(ni, i, j)] =
            (50.0 * std::pow(1.15, x) + 3.0 * y) * (1.0 + 0.08 * std::sin(i) * std::cos(0.7 * j));
      }
  }
  c.in.parent_rmax = rmax;
  c.in.child_options.hmin_m = 10.0;
  c.in.child_options.rmax = rmax;
  c.in.blend_cells = 6;
  return c;
}

// The averages by the rule, independently of child_block_averages.
double block_average(const Case& c, const std::vector<double>& h, int I, int J) {
  const int r = c.box.factor, ni = c.ni();
  double sw = 0, swh = 0, sa = 0, sah = 0;
  for (int j = (J - c.box.j_bottom) * r + 1; j <= (J - c.box.j_bottom + 1) * r; ++j)
    for (int i = (I - c.box.i_left) * r + 1; i <= (I - c.box.i_left + 1) * r; ++i) {
      const double a = c.in.child_area[at(ni, i, j)], v = h[at(ni, i, j)];
      sa += a;
      sah += a * v;
      if (c.in.child_mask[at(ni, i, j)] == 0) continue;
      sw += a;
      swh += a * v;
    }
  return sw > 0 ? swh / sw : sah / sa;
}

void expect_invariants(const Case& c, const NestedDepthResult& r) {
  const int pni = c.PL + 1, pnj = c.PM + 1;
  ASSERT_EQ(r.parent_h.size(), c.in.parent_h.size());
  ASSERT_EQ(r.child_h.size(), c.in.child_hraw.size());
  for (int J = c.box.j_bottom; J < c.box.j_top; ++J)
    for (int I = c.box.i_left; I < c.box.i_right; ++I) {
      const double avg = block_average(c, r.child_h, I, J);
      EXPECT_NEAR(r.parent_h[at(pni, I, J)], avg, 1e-12 * avg) << I << "," << J;
    }
  EXPECT_LE(r.invariant_residual_m, 1e-9);
  if (c.in.child_options.rmax > 0.0) {
    EXPECT_LE(aq::curvilinear::max_r_factor(r.child_h, c.in.child_mask, c.ni(), c.nj()),
              c.in.child_options.rmax + 1e-12);
  }
  if (c.in.parent_rmax > 0.0) {
    EXPECT_LE(aq::curvilinear::max_r_factor(r.parent_h, c.in.parent_mask, pni, pnj), c.in.parent_rmax + 1e-12);
  }
  for (const double h : r.child_h) EXPECT_GE(h, c.in.child_options.hmin_m);
  // Outside the footprint the parent is only ever deepened (by its smoothing).
  for (int j = 0; j < pnj; ++j)
    for (int i = 0; i < pni; ++i) {
      const bool inside = i >= c.box.i_left && i < c.box.i_right && j >= c.box.j_bottom && j < c.box.j_top;
      if (!inside) {
        EXPECT_GE(r.parent_h[at(pni, i, j)], c.in.parent_h[at(pni, i, j)]) << i << "," << j;
      }
    }
}

TEST(NestedBathymetry, ParentIsTheChildsBlockAverageAndBothBoundsHold) {
  // A child like the parent with a bump: its averages fit the parent's bound, no block needs
  // deepening, but every footprint cell changes.
  Case c = make_case(0.0, 0.0, 0);
  const NestedDepthResult r = aq::handoff::nested_depth(c.in);
  EXPECT_TRUE(r.settled);
  EXPECT_EQ(r.blocks_raised, 0);
  EXPECT_GE(r.parent_points_changed, 8 * 6);
  EXPECT_EQ(r.parent_outside_changed, 0);
  expect_invariants(c, r);
  EXPECT_EQ(aq::handoff::child_block_averages(r.child_h, c.in.child_mask, c.in.child_area, c.box).size(),
            static_cast<std::size_t>(8 * 6));
}

TEST(NestedBathymetry, ASteepChildSlopeDeepensItsBlocksUntilTheParentBoundHolds) {
  // A 20 m shelf against a 1500 m deep basin: the child smooths the cliff over a few fine cells,
  // steeper per parent cell than r ≤ 0.2 allows; the parent's smoothing deepens the shelf cells
  // and the child's blocks follow.
  Case c = make_case(20.0, 1500.0, 13);
  const NestedDepthResult r = aq::handoff::nested_depth(c.in);
  EXPECT_TRUE(r.settled);
  EXPECT_GT(r.blocks_raised, 0);
  EXPECT_GT(r.block_raise_max_m, 10.0);
  EXPECT_GT(r.rounds, 2);
  expect_invariants(c, r);
  // A stricter parent bound than the child's holds too.
  Case s = make_case(20.0, 1500.0, 13);
  s.in.parent_rmax = 0.1;
  for (double& h : s.in.parent_h) h = 300.0;  // flat: satisfies any bound
  const NestedDepthResult rs = aq::handoff::nested_depth(s.in);
  EXPECT_TRUE(rs.settled);
  expect_invariants(s, rs);
}

TEST(NestedBathymetry, TheRingTakesTheParentsInterpolatedDepth) {
  // No smoothing: the child is the blend and nothing else; on the ring (weight 1) it is the final
  // parent interpolated bilinearly (to the rounds' tolerance), one row in (weight 5/6) mostly so.
  Case c = make_case(0.0, 0.0, 0, 0.0);
  const NestedDepthResult r = aq::handoff::nested_depth(c.in);
  EXPECT_TRUE(r.settled);
  expect_invariants(c, r);
  const auto hp = aq::handoff::parent_rho_on_fine(r.parent_h, c.PL, c.PM, c.box);
  const int ni = c.ni(), nj = c.nj();
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const int d = std::min({i, ni - 1 - i, j, nj - 1 - j});
      const std::size_t k = at(ni, i, j);
      if (d == 0) {
        EXPECT_NEAR(r.child_h[k], hp[k], 1e-5) << i << "," << j;
      } else if (d >= 6) {
        EXPECT_EQ(r.child_h[k], c.in.child_hraw[k]) << i << "," << j;
      }
    }
}

TEST(NestedBathymetry, AveragesUseTheWetPointsOnly) {
  Case c = make_case(0.0, 0.0, 0);
  const int ni = c.ni();
  // Land in part of one block (parent cell 8, 7: child i 7..9, j 7..9) and a whole dry block
  // (parent cell 10, 9: i 13..15, j 13..15; the parent cell is land too).
  for (int j = 7; j <= 9; ++j)
    for (int i = 7; i <= 8; ++i) c.in.child_mask[at(ni, i, j)] = 0;
  for (int j = 13; j <= 15; ++j)
    for (int i = 13; i <= 15; ++i) c.in.child_mask[at(ni, i, j)] = 0;
  c.in.parent_mask[at(c.PL + 1, 10, 9)] = 0;
  const NestedDepthResult r = aq::handoff::nested_depth(c.in);
  expect_invariants(c, r);
  // Parent cell (8, 7): the average of column i = 9 only.
  double sw = 0, swh = 0;
  for (int j = 7; j <= 9; ++j) {
    sw += c.in.child_area[at(ni, 9, j)];
    swh += c.in.child_area[at(ni, 9, j)] * r.child_h[at(ni, 9, j)];
  }
  EXPECT_NEAR(r.parent_h[at(c.PL + 1, 8, 7)], swh / sw, 1e-12 * swh / sw);
}

TEST(NestedBathymetry, MasksFollowTheRules) {
  const int PL = 20, PM = 16, pni = PL + 1, pnj = PM + 1;
  const RefineBox box{6, 14, 5, 11, 3};
  const int ni = box.L() + 1, nj = box.M() + 1;
  std::vector<std::uint8_t> prho(static_cast<std::size_t>(pni * pnj), 1), pu(static_cast<std::size_t>(PL * pnj), 1),
      pv(static_cast<std::size_t>(pni * PM), 1), ppsi(static_cast<std::size_t>(PL * PM), 1);
  std::vector<std::uint8_t> crho(static_cast<std::size_t>(ni * nj), 1), cu, cv, cpsi;
  // Parent land west of I = 5 (the cells holding the child's west ring), and a parent cell in the
  // footprint that the child calls water at its centre.
  for (int j = 0; j < pnj; ++j)
    for (int i = 0; i <= 5; ++i) prho[at(pni, i, j)] = 0;
  prho[at(pni, 9, 8)] = 0;
  // The child: land at the centre of parent cell (10, 6) (child i = 3·4 + 2 = 14, j = 3·1 + 2 = 5).
  crho[at(ni, 14, 5)] = 0;
  const auto st = aq::handoff::nest_masks(box, PL, PM, prho, pu, pv, ppsi, crho, cu, cv, cpsi);
  EXPECT_EQ(st.parent_rho_changed, 2);
  EXPECT_EQ(prho[at(pni, 9, 8)], 1);
  EXPECT_EQ(prho[at(pni, 10, 6)], 0);
  // The faces and corners around the changed cells are products.
  EXPECT_EQ(pu[at(PL, 9, 6)], 0);   // between ρ 9 and 10 of row 6
  EXPECT_EQ(pu[at(PL, 10, 6)], 0);  // between ρ 10 and 11
  EXPECT_EQ(pv[at(pni, 10, 5)], 0);
  EXPECT_EQ(pv[at(pni, 10, 6)], 0);
  EXPECT_EQ(ppsi[at(PL, 9, 5)], 0);
  EXPECT_EQ(pu[at(PL, 8, 8)], 1);  // cell (9, 8) is water again
  // The west ring (fine i = 0 at ξ = 6 − 1/6, in parent cell 5) is land; the rest of the ring water.
  for (int j = 0; j < nj; ++j) EXPECT_EQ(crho[at(ni, 0, j)], 0) << j;
  EXPECT_EQ(st.child_ring_changed, nj);
  EXPECT_EQ(crho[at(ni, ni - 1, 3)], 1);
  EXPECT_EQ(crho[at(ni, 1, 3)], 1);  // the interior keeps its own mask
  // The child's u, v, ψ masks are products of its ρ mask.
  ASSERT_EQ(cu.size(), static_cast<std::size_t>((ni - 1) * nj));
  ASSERT_EQ(cv.size(), static_cast<std::size_t>(ni * (nj - 1)));
  ASSERT_EQ(cpsi.size(), static_cast<std::size_t>((ni - 1) * (nj - 1)));
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i + 1 < ni; ++i)
      EXPECT_EQ(cu[at(ni - 1, i, j)], crho[at(ni, i, j)] * crho[at(ni, i + 1, j)]) << i << "," << j;
  for (int j = 0; j + 1 < nj; ++j)
    for (int i = 0; i < ni; ++i)
      EXPECT_EQ(cv[at(ni, i, j)], crho[at(ni, i, j)] * crho[at(ni, i, j + 1)]) << i << "," << j;
  // Every wet parent cell of the footprint has a wet child point to average (ROMS needs one).
  for (int J = box.j_bottom; J < box.j_top; ++J)
    for (int I = box.i_left; I < box.i_right; ++I) {
      if (prho[at(pni, I, J)] == 0) continue;
      int wet = 0;
      for (int j = (J - 5) * 3 + 1; j <= (J - 5) * 3 + 3; ++j)
        for (int i = (I - 6) * 3 + 1; i <= (I - 6) * 3 + 3; ++i) wet += crho[at(ni, i, j)];
      EXPECT_GT(wet, 0) << I << "," << J;
    }
}

TEST(NestedBathymetry, BadInputsAreRefused) {
  Case c = make_case(0.0, 0.0, 0);
  Case bad_box = c;
  bad_box.in.box = RefineBox{1, 10, 5, 11, 3};
  EXPECT_THROW((void)aq::handoff::nested_depth(bad_box.in), aq::ConfigError);
  Case bad_size = c;
  bad_size.in.child_area.pop_back();
  EXPECT_THROW((void)aq::handoff::nested_depth(bad_size.in), aq::InternalError);
  Case bad_hmin = c;
  bad_hmin.in.child_options.hmin_m = 0.0;
  EXPECT_THROW((void)aq::handoff::nested_depth(bad_hmin.in), aq::InternalError);
}

}  // namespace

}  // namespace unit_handoff_nested_bathymetry_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Refinement of a parent supergrid (curvilinear/refine.hpp): the parent's points inside are copied
// bit for bit, the sizes follow the box, the interpolation is fourth-order accurate on a conformal
// map (the error falls ~16x when the parent's resolution doubles) and keeps it orthogonal, the
// result does not depend on the thread count, and a box leaving the parent is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/common/refine.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace unit_curvilinear_refine_test {

namespace {

using aq::curvilinear::Grid2D;
using aq::curvilinear::RefineBox;

// The conformal map z = exp(ζ) sampled on ζ = (s·h, t·h) + offset: a (n_s × n_t) parent supergrid.
std::complex<double> map(double a, double b) { return std::exp(std::complex<double>(0.2 + a, 0.1 + b)); }

Grid2D parent(int L, int M, double h) {
  Grid2D g(2 * L + 1, 2 * M + 1);
  for (int t = 0; t < g.ny_pts; ++t)
    for (int s = 0; s < g.nx_pts; ++s) {
      const auto z = map(s * h, t * h);
      g.x[g.at(s, t)] = z.real();
      g.y[g.at(s, t)] = z.imag();
    }
  return g;
}

// Largest distance between the refinement of `box` (pad 0) of a parent with supergrid step h and
// the exact map at the fine points.
double refine_error(int L, int M, double h, const RefineBox& box) {
  const Grid2D f = aq::curvilinear::refine_supergrid(parent(L, M, h), box, 0);
  double e = 0;
  for (int T = 0; T < f.ny_pts; ++T)
    for (int S = 0; S < f.nx_pts; ++S) {
      const double s = 2.0 * box.i_left - 1.0 + (S - 1.0) / box.factor;
      const double t = 2.0 * box.j_bottom - 1.0 + (T - 1.0) / box.factor;
      const auto z = map(s * h, t * h);
      e = std::max(e, std::hypot(f.x[f.at(S, T)] - z.real(), f.y[f.at(S, T)] - z.imag()));
    }
  return e;
}

}  // namespace

TEST(Refine, SizesAndParentPointsCopiedExactly) {
  const Grid2D p = parent(20, 16, 0.05);
  const RefineBox b{4, 12, 3, 9, 3};
  const int pad = 2;
  const Grid2D f = aq::curvilinear::refine_supergrid(p, b, pad);
  EXPECT_EQ(b.L(), 3 * 8 + 1);
  EXPECT_EQ(b.M(), 3 * 6 + 1);
  EXPECT_EQ(f.nx_pts, 2 * b.L() + 1 + 4 * pad);
  EXPECT_EQ(f.ny_pts, 2 * b.M() + 1 + 4 * pad);
  // Fine supergrid S (unpadded) = 1 + 3m is parent supergrid 2·I_left − 1 + m.
  int copied = 0;
  for (int T = -2 * pad; T <= 2 * b.M() + 2 * pad; ++T)
    for (int S = -2 * pad; S <= 2 * b.L() + 2 * pad; ++S) {
      if ((S - 1) % 3 != 0 || (T - 1) % 3 != 0) continue;
      const int s = 2 * b.i_left - 1 + (S - 1) / 3, t = 2 * b.j_bottom - 1 + (T - 1) / 3;
      const std::size_t k = f.at(S + 2 * pad, T + 2 * pad), q = p.at(s, t);
      ASSERT_EQ(f.x[k], p.x[q]) << S << " " << T;
      ASSERT_EQ(f.y[k], p.y[q]) << S << " " << T;
      ++copied;
    }
  EXPECT_GT(copied, 100);
  // The fine ψ corners are the parent's ψ corners (supergrid 2I − 1).
  const Grid2D g = aq::curvilinear::unpad_supergrid(f, pad);
  EXPECT_EQ(g.nx_pts, 2 * b.L() + 1);
  EXPECT_EQ(g.x[g.at(1, 1)], p.x[p.at(2 * b.i_left - 1, 2 * b.j_bottom - 1)]);
  EXPECT_EQ(g.y[g.at(2 * b.L() - 1, 2 * b.M() - 1)], p.y[p.at(2 * b.i_right - 1, 2 * b.j_top - 1)]);
}

TEST(Refine, FourthOrderOnAConformalMapAndOrthogonal) {
  // The same region of the plane at parent steps h and h/2 (the box doubles in index space).
  const double h = 0.04;
  const double e1 = refine_error(24, 20, h, RefineBox{5, 15, 5, 13, 5});
  const double e2 = refine_error(48, 40, h / 2, RefineBox{9, 29, 9, 25, 5});
  EXPECT_LT(e1, 1e-6);
  EXPECT_GT(e1 / e2, 10.0) << e1 << " " << e2;  // 16 for fourth order
  // The fine grid is orthogonal to the order of its parent.
  const Grid2D f = aq::curvilinear::refine_supergrid(parent(48, 40, h / 2), RefineBox{9, 29, 9, 25, 5}, 0);
  aq::curvilinear::CheckOptions co;
  co.dxi_over_deta = 1.0;
  const auto q = aq::curvilinear::check_grid(f, co);
  EXPECT_LT(q.ortho_50.worst, 1e-6);
}

TEST(Refine, SameResultOnOneAndTwoThreads) {
#ifdef _OPENMP
  const Grid2D p = parent(30, 24, 0.03);
  const RefineBox b{5, 25, 4, 20, 7};
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Grid2D a = aq::curvilinear::refine_supergrid(p, b, 4);
  omp_set_num_threads(2);
  const Grid2D c = aq::curvilinear::refine_supergrid(p, b, 4);
  omp_set_num_threads(saved);
  EXPECT_EQ(a.x, c.x);
  EXPECT_EQ(a.y, c.y);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(Refine, BoxLeavingTheParentIsRefused) {
  const Grid2D p = parent(10, 8, 0.05);
  // ψ I 1..10: 9..12 reaches past the east edge; a pad of 4 cells from I_left = 1 past the west.
  EXPECT_THROW((void)aq::curvilinear::refine_supergrid(p, RefineBox{9, 12, 2, 5, 3}, 0), aq::ConfigError);
  EXPECT_THROW((void)aq::curvilinear::refine_supergrid(p, RefineBox{1, 5, 2, 5, 3}, 4), aq::ConfigError);
  EXPECT_NO_THROW((void)aq::curvilinear::refine_supergrid(p, RefineBox{1, 10, 1, 8, 3}, 0));
  EXPECT_THROW((void)aq::curvilinear::refine_supergrid(p, RefineBox{2, 5, 2, 5, 2}, 0), aq::InternalError);
}

}  // namespace unit_curvilinear_refine_test

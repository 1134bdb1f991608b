// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the grid quality criteria: checkort forms (46), (50), (51), (52) and the Laplace
// residual (seed 000), and the seed-004 cell criteria f1–f4, on grids with known answers.
#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/conformal/laplace_fill.hpp"

namespace aq::curvilinear::unit_curvilinear_grid_checks_test {
namespace {

using Complex = std::complex<double>;

/// Grid with nodes P(i, j) = origin + i·a + j·b (a parallelogram lattice).
Grid2D lattice(int nx, int ny, Complex a, Complex b, Complex origin = {0.0, 0.0}) {
  Grid2D g(nx, ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Complex z = origin + static_cast<double>(i) * a + static_cast<double>(j) * b;
      g.x[g.at(i, j)] = z.real();
      g.y[g.at(i, j)] = z.imag();
    }
  }
  return g;
}

/// z = f(ζ) on [xi0, xi0+w] × [eta0, eta0+h] with nx × ny nodes.
Grid2D mapped(const std::function<Complex(Complex)>& f, double xi0, double eta0, double w, double h, int nx, int ny) {
  Grid2D g(nx, ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Complex z = f(Complex(xi0 + w * i / (nx - 1), eta0 + h * j / (ny - 1)));
      g.x[g.at(i, j)] = z.real();
      g.y[g.at(i, j)] = z.imag();
    }
  }
  return g;
}

TEST(GridChecks, UnitSquareCellsScoreOne) {
  const GridQuality q = check_grid(lattice(4, 3, {1.0, 0.0}, {0.0, 1.0}));
  EXPECT_DOUBLE_EQ(q.dxi_over_deta, 1.0);  // estimated
  for (const QualityField* f : {&q.f1, &q.f2, &q.f3, &q.f4}) {
    EXPECT_EQ(f->count, 6) << f->name;
    EXPECT_DOUBLE_EQ(f->worst, 1.0) << f->name;
    EXPECT_DOUBLE_EQ(f->average, 1.0) << f->name;
  }
  for (const QualityField* f : {&q.ortho_46, &q.ortho_50, &q.isotropy_51}) {
    EXPECT_EQ(f->worst, 0.0) << f->name;
    EXPECT_EQ(f->rms, 0.0) << f->name;
  }
  EXPECT_EQ(q.ortho_52.count, 2);  // interior nodes of a 4x3 grid
  EXPECT_LT(q.ortho_52.worst, 1e-15);
  EXPECT_EQ(q.non_convex_cells, 0);
}

TEST(GridChecks, TwoByOneRectangleHasAspectHalfAndIsotropyNeedsRho) {
  const Grid2D g = lattice(5, 4, {2.0, 0.0}, {0.0, 1.0});
  CheckOptions o;
  o.dxi_over_deta = 2.0;
  const GridQuality q = check_grid(g, o);
  EXPECT_DOUBLE_EQ(q.f4.worst, 0.5);
  EXPECT_DOUBLE_EQ(q.f2.worst, 1.0);
  EXPECT_DOUBLE_EQ(q.isotropy_51.worst, 0.0);
  EXPECT_DOUBLE_EQ(q.isotropy_ratio_min, 2.0);
  EXPECT_DOUBLE_EQ(q.isotropy_ratio_max, 2.0);
  EXPECT_DOUBLE_EQ(estimate_step_ratio(g), 2.0);
  o.dxi_over_deta = 1.6;  // claims a different computational grid: isotropy error 2/1.6 − 1
  EXPECT_NEAR(check_grid(g, o).isotropy_51.worst, 0.25, 1e-15);
}

TEST(GridChecks, ShearedGridGivesTheKnownSine) {
  // ξ lines along (1.3, 0), η lines along 0.8·(cos 60°, sin 60°): the angle is 60°, so the
  // orthogonality error ε = cos 60° = sin(90° − 60°) = 0.5 in every cell, and f2 = sin 60°.
  // (The origin is far away, as with a false easting: node round-off is ~1e-11 of a cell.)
  const double theta = 60.0 * kDegToRad;
  const Grid2D g = lattice(7, 5, {1.3, 0.0}, {0.8 * std::cos(theta), 0.8 * std::sin(theta)}, {1e5, -3e4});
  const GridQuality q = check_grid(g);
  for (const QualityField* f : {&q.ortho_46, &q.ortho_50}) {
    EXPECT_NEAR(f->worst, 0.5, 1e-10) << f->name;
    EXPECT_NEAR(f->average, 0.5, 1e-10) << f->name;
    EXPECT_NEAR(f->rms, 0.5, 1e-10) << f->name;
    EXPECT_NEAR(f->values[5], 0.5, 1e-10) << f->name;  // signed: acute angle → positive
  }
  EXPECT_NEAR(q.f2.worst, std::sin(theta), 1e-10);
  EXPECT_NEAR(q.f1.worst, 1.0, 1e-10);  // a parallelogram
  EXPECT_NEAR(q.f4.worst, 0.8 / 1.3, 1e-10);
  // (The spline form postulates orthogonality on the boundary, eq. (52), so on a lattice that is
  // not conformal it is not a measure of the 60°: not tested here.)

  // The mirror image (obtuse angle 120°) has ε = −0.5.
  const Grid2D m = lattice(7, 5, {1.3, 0.0}, {-0.8 * std::cos(theta), 0.8 * std::sin(theta)});
  const GridQuality qm = check_grid(m);
  EXPECT_NEAR(qm.ortho_50.values[0], -0.5, 1e-12);
  EXPECT_NEAR(qm.ortho_50.worst, 0.5, 1e-12);  // worst is max |ε|
}

TEST(GridChecks, F1DetectsANonConvexCellAndWhereItIs) {
  Grid2D g = lattice(6, 5, {1.0, 0.0}, {0.0, 1.0});
  // Push node (3, 2) deep into cell (2, 1)... past the diagonal from (2, 2) to (3, 1): the cells
  // around it become darts (non-convex) but keep a positive area.
  const std::size_t p = g.at(3, 2);
  g.x[p] = 2.3;
  g.y[p] = 1.3;
  const GridQuality q = check_grid(g);
  EXPECT_LT(q.f1.values[1 * 5 + 2], 0.0);  // cell (2, 1) has (3, 2) as its corner 3
  EXPECT_LT(q.f1.worst, 0.0);
  EXPECT_EQ(q.f1.worst_i, 2);
  EXPECT_EQ(q.f1.worst_j, 1);
  EXPECT_GE(q.non_convex_cells, 1);
  EXPECT_LT(q.f2.values[1 * 5 + 2], 0.0);  // a reflex angle has a negative sine
  EXPECT_GT(q.f1.values[0], 0.99);         // far cells unaffected
  // The other cells touching (3, 2) are convex but distorted.
  EXPECT_GT(q.f1.values[2 * 5 + 3], 0.0);
  EXPECT_LT(q.f1.values[2 * 5 + 3], 1.0);
}

TEST(GridChecks, InvertedCellsGetMinusInfinityInF1) {
  // Clockwise numbering (ξ along −x): every cell is inverted.
  const GridQuality q = check_grid(lattice(3, 3, {-1.0, 0.0}, {0.0, 1.0}));
  EXPECT_EQ(q.non_convex_cells, 4);
  EXPECT_TRUE(std::isinf(q.f1.worst) && q.f1.worst < 0.0);
  EXPECT_EQ(q.f3.worst, 0.0);
}

TEST(GridChecks, F3MeasuresTheAreaLaw) {
  // Two columns of cells, areas 1 and 3: C = mean area 2, f3 = min(S/C, C/S) = 0.5 and 2/3.
  Grid2D g(3, 2);
  const double xs[] = {0.0, 1.0, 4.0};
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) {
      g.x[g.at(i, j)] = xs[i];
      g.y[g.at(i, j)] = j;
    }
  }
  CheckOptions o;
  const GridQuality q = check_grid(g, o);
  EXPECT_DOUBLE_EQ(q.f3.values[0], 0.5);
  EXPECT_DOUBLE_EQ(q.f3.values[1], 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(q.f3.worst, 0.5);
  // With w = 1/x-ish weighting that makes wS constant, f3 = 1.
  o.weight = [](double x, double) { return x < 1.0 ? 3.0 : 1.0; };
  const GridQuality qw = check_grid(g, o);
  EXPECT_DOUBLE_EQ(qw.f3.worst, 1.0);
  o.weight = [](double, double) { return -1.0; };
  EXPECT_THROW(check_grid(g, o), InputError);
}

TEST(GridChecks, ExactConformalGridsHaveZeroOrthogonalityByTheirSymmetry) {
  // exp: every cell is an isosceles trapezoid: (46) and (50) vanish exactly, isotropy does not
  // (the harmonic mean of the two arcs is not the radial chord).
  const Grid2D g = mapped([](Complex z) { return std::exp(z); }, 0.0, 0.0, 1.5, 1.0, 40, 27);
  CheckOptions o;
  o.dxi_over_deta = (1.5 / 39) / (1.0 / 26);
  const GridQuality q = check_grid(g, o);
  EXPECT_LT(q.ortho_46.worst, 1e-13);
  EXPECT_LT(q.ortho_50.worst, 1e-13);
  EXPECT_GT(q.isotropy_51.worst, 1e-5);
  EXPECT_LT(q.isotropy_51.worst, 1e-2);
  EXPECT_NEAR(estimate_step_ratio(g), o.dxi_over_deta, 1e-3);
}

TEST(GridChecks, SplineFormIsHigherOrderThanTheFdForms) {
  // z = exp(2.5ζ)(1 + 0.3ζ) (conformal on the rectangle, not a polynomial: cubic splines would
  // reproduce a cubic map exactly): the FD forms are 2nd order, the spline form with the
  // conformal corner condition at least 4th.
  const auto f = [](Complex z) { return std::exp(2.5 * z) * (1.0 + 0.3 * z); };
  std::vector<double> e50;
  std::vector<double> e52;
  const std::vector<int> levels = {8, 16, 32, 64};
  for (const int n : levels) {
    const int nx = 3 * n / 2 + 2;  // Δξ ≠ Δη
    const Grid2D g = mapped(f, 1.0, 0.2, 0.6, 0.4, nx, n + 1);
    CheckOptions o;
    o.dxi_over_deta = (0.6 / (nx - 1)) / (0.4 / n);
    const GridQuality q = check_grid(g, o);
    e50.push_back(q.ortho_50.worst);
    e52.push_back(q.ortho_52.worst);
  }
  std::printf("  N    eps(50)    order   eps(52)    order\n");
  for (std::size_t k = 0; k < levels.size(); ++k) {
    std::printf("  %3d  %9.3e  %5.2f   %9.3e  %5.2f\n", levels[k], e50[k], k ? std::log2(e50[k - 1] / e50[k]) : 0.0,
                e52[k], k ? std::log2(e52[k - 1] / e52[k]) : 0.0);
  }
  for (std::size_t k = 1; k < levels.size(); ++k) {
    EXPECT_NEAR(std::log2(e50[k - 1] / e50[k]), 2.0, 0.25) << levels[k];
    EXPECT_GE(std::log2(e52[k - 1] / e52[k]), 3.7) << levels[k];
  }
  EXPECT_LT(e52.back(), 1e-3 * e50.back());
}

TEST(GridChecks, LaplaceResidualSeparatesHarmonicFromNonHarmonicGrids) {
  // A filled grid has round-off residual; a non-harmonic map (z + 0.1 |z|² ) does not.
  Grid2D g = mapped([](Complex z) { return std::exp(z); }, 0.0, 0.0, 1.3, 1.0, 27, 21);
  laplace_fill(g, 1.3 / 26, 1.0 / 20);
  CheckOptions o;
  o.dxi_over_deta = (1.3 / 26) / (1.0 / 20);
  EXPECT_LT(check_grid(g, o).laplace_residual.worst, 1e-13);
  const Grid2D h = mapped([](Complex z) { return z + 0.1 * std::norm(z); }, 0.0, 0.0, 1.3, 1.0, 27, 21);
  const GridQuality qh = check_grid(h, o);
  EXPECT_GT(qh.laplace_residual.worst, 1e-4);
  EXPECT_TRUE(std::isnan(qh.laplace_residual.values[0]));  // boundary: undefined
}

TEST(GridChecks, StatisticsAreBitIdenticalForOneAndTwoThreads) {
#ifdef _OPENMP
  const Grid2D g = mapped([](Complex z) { return std::sin(z) + 0.05 * std::norm(z); }, 0.1, 0.2, 1.3, 1.0, 131, 101);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const GridQuality a = check_grid(g);
  omp_set_num_threads(2);
  const GridQuality b = check_grid(g);
  omp_set_num_threads(saved);
  const auto fa = a.fields();
  const auto fb = b.fields();
  for (std::size_t k = 0; k < fa.size(); ++k) {
    ASSERT_EQ(fa[k]->values.size(), fb[k]->values.size());
    EXPECT_EQ(std::memcmp(fa[k]->values.data(), fb[k]->values.data(), fa[k]->values.size() * sizeof(double)), 0)
        << fa[k]->name;
    EXPECT_EQ(std::memcmp(&fa[k]->average, &fb[k]->average, sizeof(double)), 0) << fa[k]->name;
  }
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(GridChecks, BadGridsAreRefused) {
  EXPECT_THROW(check_grid(Grid2D(1, 5)), InputError);
  Grid2D g = lattice(3, 3, {1.0, 0.0}, {0.0, 1.0});
  g.y[g.at(1, 2)] = std::numeric_limits<double>::quiet_NaN();
  try {
    check_grid(g);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(1, 2)"), std::string::npos) << e.what();
  }
}

TEST(GridChecks, FieldsAreListedWithNamesAndLocations) {
  const GridQuality q = check_grid(lattice(4, 4, {1.0, 0.0}, {0.0, 1.0}));
  const auto f = q.fields();
  ASSERT_EQ(f.size(), 9u);
  EXPECT_EQ(f[0]->name, "ortho_err_46");
  EXPECT_EQ(f[1]->name, "ortho_err_50");
  EXPECT_EQ(f[2]->name, "ortho_err_52");
  EXPECT_EQ(f[2]->location, FieldLocation::kNode);
  EXPECT_EQ(f[3]->name, "isotropy_51");
  EXPECT_EQ(f[8]->name, "f4");
  EXPECT_EQ(f[1]->values.size(), 9u);
  EXPECT_EQ(f[2]->values.size(), 16u);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_grid_checks_test

namespace aq::curvilinear::unit_curvilinear_grid_checks_test {
namespace {

// Issue 11: a criterion that is NaN where it is defined fails the check and says where. Finite
// nodes of 1e200 overflow the products (inf / inf = NaN); the statistics skip NaN as undefined,
// so without GridQuality::non_finite the worst value would look fine.
TEST(GridChecks, NaNCriteriaFromFiniteNodesAreListedWithTheCell) {
  Grid2D g(3, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      g.x[g.at(i, j)] = 1e200 * i;
      g.y[g.at(i, j)] = 1e200 * j;
    }
  }
  const GridQuality q = check_grid(g);
  ASSERT_FALSE(q.non_finite.empty());
  EXPECT_NE(q.non_finite.front().find("ortho_err_50 (orthogonality error"), std::string::npos) << q.non_finite.front();
  EXPECT_NE(q.non_finite.front().find("nan at cell (0, 0) with south-west node at (0, 0)"), std::string::npos)
      << q.non_finite.front();
  Grid2D fine(3, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      fine.x[fine.at(i, j)] = i;
      fine.y[fine.at(i, j)] = j;
    }
  }
  EXPECT_TRUE(check_grid(fine).non_finite.empty());  // boundary NaN of the node fields is "undefined"
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_grid_checks_test

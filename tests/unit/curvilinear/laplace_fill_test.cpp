// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the mehrstellen Dirichlet fill (seed 000 eqs. (32)–(43)): weights, exactness on
// harmonic polynomials, SOR = DST, bit-identical threads, convergence order on analytic conformal
// maps (w = exp z, z²) with Δξ ≠ Δη, and timings at the Black Sea and Fig. 16 sizes.
#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/conformal/laplace_fill.hpp"

namespace aq::curvilinear::unit_curvilinear_laplace_fill_test {
namespace {

using Complex = std::complex<double>;
using Map = std::function<Complex(Complex)>;

/// The computational rectangle [xi0, xi0 + W] × [eta0, eta0 + H] sampled with nx × ny points.
struct Rect {
  double xi0, eta0, w, h;
  int nx, ny;
  [[nodiscard]] double dxi() const { return w / (nx - 1); }
  [[nodiscard]] double deta() const { return h / (ny - 1); }
};

/// The grid z = f(ζ) at every node; with `boundary_only` the interior is NaN (solvers must not
/// read it).
Grid2D sample(const Map& f, const Rect& r, bool boundary_only) {
  Grid2D g(r.nx, r.ny);
  for (int j = 0; j < r.ny; ++j) {
    for (int i = 0; i < r.nx; ++i) {
      const bool boundary = i == 0 || j == 0 || i == r.nx - 1 || j == r.ny - 1;
      const Complex z = f(Complex(r.xi0 + i * r.dxi(), r.eta0 + j * r.deta()));
      const std::size_t p = g.at(i, j);
      g.x[p] = boundary || !boundary_only ? z.real() : std::numeric_limits<double>::quiet_NaN();
      g.y[p] = boundary || !boundary_only ? z.imag() : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return g;
}

double max_node_difference(const Grid2D& a, const Grid2D& b) {
  double d = 0.0;
  for (std::size_t p = 0; p < a.x.size(); ++p)
    d = std::max({d, std::fabs(a.x[p] - b.x[p]), std::fabs(a.y[p] - b.y[p])});
  return d;
}

double extent(const Grid2D& g) {
  const auto [x0, x1] = std::minmax_element(g.x.begin(), g.x.end());
  const auto [y0, y1] = std::minmax_element(g.y.begin(), g.y.end());
  return std::max(*x1 - *x0, *y1 - *y0);
}

LaplaceOptions sor_options() {
  LaplaceOptions o;
  o.solver = LaplaceOptions::Solver::kSor;
  return o;
}

TEST(LaplaceWeights, MatchTheDigestNormalisation) {
  const StencilWeights w1 = laplace_weights(1.0);
  EXPECT_DOUBLE_EQ(w1.alpha, 4.0);
  EXPECT_DOUBLE_EQ(w1.beta, 4.0);
  EXPECT_DOUBLE_EQ(w1.gamma, 1.0);
  EXPECT_DOUBLE_EQ(w1.delta, -20.0);
  const double rho = 1.3;
  const StencilWeights w = laplace_weights(rho);
  EXPECT_DOUBLE_EQ(w.alpha, 6.0 - 2.0 * rho);
  EXPECT_DOUBLE_EQ(w.beta, 6.0 * rho * rho - 2.0 * rho);
  EXPECT_DOUBLE_EQ(w.gamma, rho);
  EXPECT_NEAR(w.delta, -(12.0 + 12.0 * rho * rho - 4.0 * rho), 1e-14);
  const StencilWeights w5 = laplace_weights(rho, true);
  EXPECT_DOUBLE_EQ(w5.alpha, 1.0);
  EXPECT_DOUBLE_EQ(w5.beta, rho * rho);
  EXPECT_DOUBLE_EQ(w5.gamma, 0.0);
  EXPECT_THROW(laplace_weights(0.0), NumericalError);
}

/// Fills the interior from the exact boundary of f and returns the largest interior error
/// relative to the grid's extent.
double fill_error(const Map& f, const Rect& r, bool five_point, LaplaceOptions::Solver solver) {
  const Grid2D exact = sample(f, r, false);
  Grid2D g = sample(f, r, true);
  LaplaceOptions o;
  o.solver = solver;
  o.five_point = five_point;
  laplace_fill(g, r.dxi(), r.deta(), o);
  return max_node_difference(g, exact) / extent(exact);
}

TEST(LaplaceFill, DstReproducesHarmonicCubicsForAnyStepRatio) {
  const Rect r{-0.7, 0.2, 1.9, 1.1, 23, 17};  // ρ = (1.9/22)/(1.1/16) ≈ 1.256
  ASSERT_GT(std::fabs(r.dxi() / r.deta() - 1.0), 0.2);
  const std::vector<Map> maps = {
      [](Complex z) { return 3.0 * z + Complex(1.0, -2.0); },
      [](Complex z) { return z * z; },
      [](Complex z) { return z * z * z; },
      [](Complex z) { return Complex(0.0, 1.0) * z * z * z + 0.5 * z * z; },
  };
  for (std::size_t k = 0; k < maps.size(); ++k) {
    EXPECT_LT(fill_error(maps[k], r, false, LaplaceOptions::Solver::kDst), 1e-14) << "map " << k;
    EXPECT_LT(fill_error(maps[k], r, true, LaplaceOptions::Solver::kDst), 1e-14) << "5-point, map " << k;
  }
}

TEST(LaplaceFill, NinePointIsExactForDegreeFourAndFiveOnlyWithEqualSteps) {
  const Map z4 = [](Complex z) { return z * z * z * z; };
  const Map z5 = [](Complex z) { return z * z * z * z * z - 2.0 * z * z * z * z; };
  const Rect square{-0.6, -0.4, 1.6, 1.2, 25, 19};  // Δξ = Δη = 1/15
  ASSERT_NEAR(square.dxi(), square.deta(), 1e-15);
  EXPECT_LT(fill_error(z4, square, false, LaplaceOptions::Solver::kDst), 2e-14);
  EXPECT_LT(fill_error(z5, square, false, LaplaceOptions::Solver::kDst), 2e-14);
  // The 5-point operator is only 2nd order: visibly wrong for z⁴.
  EXPECT_GT(fill_error(z4, square, true, LaplaceOptions::Solver::kDst), 1e-5);
  // With Δξ ≠ Δη the leftover −(Δξ−Δη)²/12 q_ξξηη is not zero.
  const Rect skew{-0.6, -0.4, 1.6, 1.2, 31, 19};
  EXPECT_GT(fill_error(z4, skew, false, LaplaceOptions::Solver::kDst), 1e-6);
}

TEST(LaplaceFill, SorAndDstAgreeOnAConformalBoundary) {
  // Black Sea size, ρ ≠ 1; boundary of w = exp(ζ)·(1 + ζ/5) (conformal where ζ ≠ -5).
  const Map f = [](Complex z) { return 100.0 * std::exp(z) * (1.0 + 0.2 * z); };
  const Rect r{-0.3, 0.1, 1.45, 1.0, 131, 101};  // ρ = 1.115
  const Grid2D boundary = sample(f, r, true);
  Grid2D dst = boundary;
  Grid2D sor = boundary;
  const LaplaceResult rd = laplace_fill(dst, r.dxi(), r.deta());
  const LaplaceResult rs = laplace_fill(sor, r.dxi(), r.deta(), sor_options());
  const double rel = max_node_difference(dst, sor) / extent(dst);
  std::printf(
      "131x101 rho=%.6f: |SOR - DST|/extent = %.2e; DST %.4f s (residual %.1e); SOR %.3f s, %d iterations "
      "(residual %.1e)\n",
      r.dxi() / r.deta(), rel, rd.seconds, rd.residual, rs.seconds, rs.iterations, rs.residual);
  EXPECT_LT(rel, 1e-12);
  EXPECT_LT(rd.residual, 1e-14);
  EXPECT_EQ(rd.iterations, 1);
  EXPECT_GT(rs.iterations, 50);
  EXPECT_EQ(rs.residual_history.size(), static_cast<std::size_t>(rs.iterations));
  EXPECT_LT(rs.residual_history.back(), LaplaceOptions{}.tolerance);
  // The boundary is not trivial: SOR's first iteration moved nodes far from the Coons guess.
  EXPECT_GT(rs.residual_history.front(), 1e-6);
}

TEST(LaplaceFill, BoundaryNodesAreNotChanged) {
  const Map f = [](Complex z) { return std::sin(z); };
  const Rect r{0.2, 0.3, 1.0, 0.7, 21, 13};
  for (const auto solver : {LaplaceOptions::Solver::kDst, LaplaceOptions::Solver::kSor}) {
    Grid2D g = sample(f, r, true);
    const Grid2D before = g;
    LaplaceOptions o;
    o.solver = solver;
    laplace_fill(g, r.dxi(), r.deta(), o);
    for (int j = 0; j < r.ny; ++j) {
      for (int i = 0; i < r.nx; ++i) {
        const std::size_t p = g.at(i, j);
        if (i == 0 || j == 0 || i == r.nx - 1 || j == r.ny - 1) {
          EXPECT_EQ(std::memcmp(&g.x[p], &before.x[p], sizeof(double)), 0);
          EXPECT_EQ(std::memcmp(&g.y[p], &before.y[p], sizeof(double)), 0);
        } else {
          EXPECT_TRUE(std::isfinite(g.x[p]) && std::isfinite(g.y[p]));
        }
      }
    }
  }
}

TEST(LaplaceFill, RectangleBoundaryGivesTheCartesianGrid) {
  // A rectangle with a false easting: x = 5e5 + 130 i, y = 4.2e6 + 100 j.
  const Map f = [](Complex z) { return Complex(5e5, 4.2e6) + 1000.0 * z; };
  const Rect r{0.0, 0.0, 13.0, 10.0, 131, 101};
  for (const auto solver : {LaplaceOptions::Solver::kDst, LaplaceOptions::Solver::kSor}) {
    const Grid2D exact = sample(f, r, false);
    Grid2D g = sample(f, r, true);
    LaplaceOptions o;
    o.solver = solver;
    laplace_fill(g, r.dxi(), r.deta(), o);
    EXPECT_LT(max_node_difference(g, exact), 1e-13 * extent(exact) * 10) << "solver " << static_cast<int>(solver);
    CheckOptions co;
    co.dxi_over_deta = r.dxi() / r.deta();
    const GridQuality q = check_grid(g, co);
    EXPECT_LT(q.ortho_46.worst, 1e-13);
    EXPECT_LT(q.ortho_50.worst, 1e-13);
    EXPECT_LT(q.ortho_52.worst, 1e-13);
    EXPECT_LT(q.isotropy_51.worst, 1e-12);
    EXPECT_NEAR(q.f2.worst, 1.0, 1e-13);
    EXPECT_NEAR(q.f1.worst, 1.0, 1e-9);
  }
}

TEST(LaplaceFill, SorIsBitIdenticalForOneAndTwoThreads) {
#ifdef _OPENMP
  // Large enough for the parallel path (half sweeps of >= 65536 nodes); a looser tolerance keeps
  // it quick; bit-identity does not depend on it.
  const Map f = [](Complex z) { return 50.0 * std::exp(Complex(0.0, 1.0) * z) + z * z; };
  const Rect r{0.0, 0.0, 12.6, 1.0, 1301, 103};
  std::vector<Grid2D> out;
  std::vector<int> iterations;
  const int saved = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    for (const auto solver : {LaplaceOptions::Solver::kSor, LaplaceOptions::Solver::kDst}) {
      Grid2D g = sample(f, r, true);
      LaplaceOptions o;
      o.solver = solver;
      o.tolerance = 1e-10;
      iterations.push_back(laplace_fill(g, r.dxi(), r.deta(), o).iterations);
      out.push_back(std::move(g));
    }
  }
  omp_set_num_threads(saved);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(iterations[k], iterations[k + 2]);
    EXPECT_EQ(std::memcmp(out[k].x.data(), out[k + 2].x.data(), out[k].x.size() * sizeof(double)), 0) << k;
    EXPECT_EQ(std::memcmp(out[k].y.data(), out[k + 2].y.data(), out[k].y.size() * sizeof(double)), 0) << k;
  }
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(LaplaceFill, SorThatCannotConvergeThrowsNamingResidualAndIterations) {
  const Map f = [](Complex z) { return std::exp(z); };
  const Rect r{0.0, 0.0, 1.3, 1.0, 41, 31};
  Grid2D g = sample(f, r, true);
  LaplaceOptions o = sor_options();
  o.max_iterations = 7;
  try {
    laplace_fill(g, r.dxi(), r.deta(), o);
    FAIL() << "no exception";
  } catch (const NumericalError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("after 7 iterations"), std::string::npos) << msg;
    EXPECT_NE(msg.find("max |dq|/extent"), std::string::npos) << msg;
  }
}

TEST(LaplaceFill, BadInputsAreRefused) {
  const Rect r{0.0, 0.0, 1.0, 1.0, 5, 5};
  Grid2D g = sample([](Complex z) { return z; }, r, true);
  EXPECT_THROW(laplace_fill(g, 0.0, 1.0), NumericalError);
  EXPECT_THROW(laplace_fill(g, 1.0, std::nan("")), NumericalError);
  g.x[g.at(2, 0)] = std::numeric_limits<double>::infinity();
  try {
    laplace_fill(g, 1.0, 1.0);
    FAIL() << "no exception";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("(2, 0)"), std::string::npos) << e.what();
  }
  Grid2D bad(4, 4);
  bad.x.pop_back();
  EXPECT_THROW(laplace_fill(bad, 1.0, 1.0), InternalError);
  Grid2D thin = sample([](Complex z) { return z; }, Rect{0.0, 0.0, 1.0, 1.0, 7, 2}, false);
  const Grid2D before = thin;
  EXPECT_EQ(laplace_fill(thin, 1.0, 1.0).iterations, 0);
  EXPECT_EQ(thin.x, before.x);
}

/// Least-squares slope of log(err) against log(N).
double fitted_order(const std::vector<int>& n, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(n.size());
  for (std::size_t k = 0; k < n.size(); ++k) {
    const double x = std::log(static_cast<double>(n[k]));
    const double y = std::log(err[k]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return -(m * sxy - sx * sy) / (m * sxx - sx * sx);
}

struct Convergence {
  std::vector<double> ortho;     ///< max ε(50) of the filled grid
  std::vector<double> change;    ///< max over cells |ε(50)(filled) − ε(50)(exact grid)|
  std::vector<double> position;  ///< max |z_fill − z_exact| / extent
};

/// Resolutions N = ny−1 = 16..128 with nx−1 = 1.5N+1 on a W/H = 1.5 rectangle: Δξ ≠ Δη at every
/// resolution, ρ = 1.5N/(1.5N+1) → 1 as the automatic nx rule guarantees.
const std::vector<int> kLevels = {16, 32, 64, 128};

Convergence convergence(const Map& f, double xi0, double eta0, bool five_point) {
  Convergence c;
  for (const int n : kLevels) {
    const Rect r{xi0, eta0, 1.5, 1.0, 3 * n / 2 + 2, n + 1};
    EXPECT_GT(std::fabs(r.dxi() / r.deta() - 1.0), 0.1 / n);
    const Grid2D exact = sample(f, r, false);
    Grid2D g = sample(f, r, true);
    LaplaceOptions o;
    o.five_point = five_point;
    laplace_fill(g, r.dxi(), r.deta(), o);
    CheckOptions co;
    co.dxi_over_deta = r.dxi() / r.deta();
    const GridQuality q = check_grid(g, co);
    const GridQuality qe = check_grid(exact, co);
    double e = 0.0;
    for (std::size_t k = 0; k < q.ortho_50.values.size(); ++k) {
      e = std::max(e, std::fabs(q.ortho_50.values[k] - qe.ortho_50.values[k]));
    }
    c.ortho.push_back(q.ortho_50.worst);
    c.change.push_back(e);
    c.position.push_back(max_node_difference(g, exact) / extent(exact));
  }
  return c;
}

double order(const std::vector<double>& e, std::size_t k) { return std::log2(e[k - 1] / e[k]); }

void print_convergence(const char* label, const Convergence& c) {
  std::printf("%s\n  N=ny-1  max eps(50)  order  max|change of (50)|  order  max|z-z_exact|/ext  order\n", label);
  for (std::size_t k = 0; k < kLevels.size(); ++k) {
    if (k == 0) {
      std::printf("  %6d  %11.3e         %11.3e                %11.3e\n", kLevels[k], c.ortho[k], c.change[k],
                  c.position[k]);
    } else {
      std::printf("  %6d  %11.3e  %5.2f  %11.3e         %5.2f  %11.3e        %5.2f\n", kLevels[k], c.ortho[k],
                  order(c.ortho, k), c.change[k], order(c.change, k), c.position[k], order(c.position, k));
    }
  }
  std::printf("  fitted orders: eps(50) %.2f, change of (50) %.2f, position %.2f\n", fitted_order(kLevels, c.ortho),
              fitted_order(kLevels, c.change), fitted_order(kLevels, c.position));
}

TEST(LaplaceFillConvergence, ExpAnnularSectorIsFourthOrderWithNinePoints) {
  // w = exp(ζ) on [0, 1.5] × [0, 1]: an annular sector, radii 1..4.48, 57°. Its exact cells are
  // isosceles trapezoids, for which (50) is exactly 0: what is measured is the fill's error.
  const Map f = [](Complex z) { return std::exp(z); };
  const Convergence c9 = convergence(f, 0.0, 0.0, false);
  const Convergence c5 = convergence(f, 0.0, 0.0, true);
  print_convergence("exp, 9-point mehrstellen:", c9);
  print_convergence("exp, 5-point (for comparison):", c5);
  EXPECT_GE(fitted_order(kLevels, c9.ortho), 3.5);
  EXPECT_GE(fitted_order(kLevels, c9.position), 3.5);
  for (std::size_t k = 1; k < kLevels.size(); ++k) EXPECT_GE(order(c9.ortho, k), 3.5) << kLevels[k];
  EXPECT_NEAR(fitted_order(kLevels, c5.ortho), 2.0, 0.3);
  EXPECT_LT(c9.ortho.back(), 1e-3 * c5.ortho.back());
}

TEST(LaplaceFillConvergence, ZSquaredIsReproducedAndItsFdOrthogonalityIsSecondOrder) {
  // w = ζ² on [1, 2.5] × [0.5, 1.5]. A quadratic is harmonic and reproduced exactly by both
  // stencils, so the fill adds nothing: what (50) shows is the FD measure's own O(h²) error
  // (digest §10: "the FD forms are stuck at 2nd order").
  const Map f = [](Complex z) { return z * z; };
  const Convergence c9 = convergence(f, 1.0, 0.5, false);
  print_convergence("z^2, 9-point mehrstellen:", c9);
  for (std::size_t k = 0; k < kLevels.size(); ++k) {
    EXPECT_LT(c9.position[k], 1e-14) << kLevels[k];
    EXPECT_LT(c9.change[k], 1e-12) << kLevels[k];
  }
  EXPECT_NEAR(fitted_order(kLevels, c9.ortho), 2.0, 0.2);
}

TEST(LaplaceFillConvergence, QuarticMapIsFourthOrderWithNinePoints) {
  // w = ζ⁴ − 3ζ on [1, 2.5] × [0.5, 1.5]: conformal there (w' ≠ 0), not reproduced by either
  // stencil. The change the fill makes to (50), and the node error, fall as h⁴.
  const Map f = [](Complex z) { return z * z * z * z - 3.0 * z; };
  const Convergence c9 = convergence(f, 1.0, 0.5, false);
  const Convergence c5 = convergence(f, 1.0, 0.5, true);
  print_convergence("z^4 - 3z, 9-point mehrstellen:", c9);
  print_convergence("z^4 - 3z, 5-point (for comparison):", c5);
  EXPECT_GE(fitted_order(kLevels, c9.change), 3.5);
  EXPECT_GE(fitted_order(kLevels, c9.position), 3.5);
  EXPECT_NEAR(fitted_order(kLevels, c5.position), 2.0, 0.3);
  EXPECT_NEAR(fitted_order(kLevels, c5.change), 2.0, 0.3);
}

TEST(LaplaceFillTiming, BlackSeaAndFig16Sizes) {
  const Map f = [](Complex z) { return 1e5 * std::exp(z) * (1.0 + 0.2 * z); };
  for (const auto& [nx, ny] : {std::pair{131, 101}, std::pair{1703, 913}}) {
    // W/H as the conformal map would give it; ρ = Δξ/Δη ≈ 1.0006 and 0.99998.
    const Rect r{-0.3, 0.1, nx == 131 ? 1.3008 : 1.8662, 1.0, nx, ny};
    Grid2D g = sample(f, r, true);
    const LaplaceResult res = laplace_fill(g, r.dxi(), r.deta());
    std::printf("DST %dx%d: %.4f s, residual %.2e\n", nx, ny, res.seconds, res.residual);
    EXPECT_LT(res.residual, 1e-13);
  }
  const Rect r{-0.3, 0.1, 1.3008, 1.0, 131, 101};
  Grid2D g = sample(f, r, true);
  const LaplaceResult res = laplace_fill(g, r.dxi(), r.deta(), sor_options());
  std::printf("SOR 131x101: %.4f s, %d iterations\n", res.seconds, res.iterations);
}

// The Fig. 16-size SOR takes about a minute: run with --gtest_also_run_disabled_tests.
TEST(LaplaceFillTiming, DISABLED_SorAtFig16Size) {
  const Map f = [](Complex z) { return 1e5 * std::exp(z) * (1.0 + 0.2 * z); };
  const Rect r{-0.3, 0.1, 1.8662, 1.0, 1703, 913};
  Grid2D g = sample(f, r, true);
  Grid2D d = g;
  const LaplaceResult rd = laplace_fill(d, r.dxi(), r.deta());
  const LaplaceResult res = laplace_fill(g, r.dxi(), r.deta(), sor_options());
  std::printf("SOR 1703x913: %.2f s, %d iterations; DST %.3f s; |SOR - DST|/extent = %.2e\n", res.seconds,
              res.iterations, rd.seconds, max_node_difference(g, d) / extent(d));
  EXPECT_LT(max_node_difference(g, d) / extent(d), 1e-11);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_laplace_fill_test

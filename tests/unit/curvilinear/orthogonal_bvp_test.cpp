// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the orthogonal-family method (seed 003; digest orthogonal_bvp_and_elliptic.md A,
// part D): exact answers (annular sector in the plane, latitude–longitude rectangle on the sphere)
// reproduced with second order over three resolutions, the reciprocity E(θ)·E(η) ≥ 1 → 1, the
// seed's right-cornered channel history (f_max from O(0.5) to O(1e-2) within 2–3 outer iterations,
// then levelling off), the TFI and level helpers, and bit-identical results on 1 and 2 threads.
#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/bvp/orthogonal_bvp.hpp"
#include "curvilinear/bvp/transfinite_interpolation.hpp"

namespace aq::curvilinear::unit_curvilinear_orthogonal_bvp_test {
namespace {

constexpr double kPi = std::numbers::pi;

// Boundary polylines from a map (u, v) in [0,1]² -> R³ sampled uniformly, then TFI.
template <class F>
SurfaceGrid tfi_of(F map, int nx, int ny) {
  std::vector<Vec3> s, e, n, w;
  for (int i = 0; i < nx; ++i) {
    const double u = static_cast<double>(i) / (nx - 1);
    s.push_back(map(u, 0.0));
    n.push_back(map(u, 1.0));
  }
  for (int j = 0; j < ny; ++j) {
    const double v = static_cast<double>(j) / (ny - 1);
    w.push_back(map(0.0, v));
    e.push_back(map(1.0, v));
  }
  return transfinite_interpolation(s, e, n, w);
}

// --- annular sector R1 <= r <= R2, 0 <= phi <= Phi; i along r (Γ1 = {r = R1}), j along phi -----
constexpr double kR1 = 1.0, kR2 = 2.0, kPhi = 0.5 * kPi;

Vec3 sector(double u, double v) {
  const double r = kR1 + (kR2 - kR1) * u, a = kPhi * v;
  return {r * std::cos(a), r * std::sin(a), 0.0};
}

void project_sector(SurfaceGrid& g) {
  for (int j = 0; j < g.ny_pts; ++j)
    for (int i : {0, g.nx_pts - 1}) {
      Vec3& p = g(i, j);
      const double r = i == 0 ? kR1 : kR2, l = std::hypot(p.x, p.y);
      p = {r * p.x / l, r * p.y / l, 0.0};
    }
  for (int i = 1; i + 1 < g.nx_pts; ++i) {
    g(i, 0).y = 0.0;  // the ray phi = 0
    Vec3& p = g(i, g.ny_pts - 1);
    p = {0.0, p.y, 0.0};  // the ray phi = pi/2
  }
}

double sector_error(const SurfaceGrid& g, const std::vector<double>& tl, const std::vector<double>& el) {
  double err = 0.0;
  for (int q = 0; q < g.ny_pts; ++q)
    for (int p = 0; p < g.nx_pts; ++p) {
      const double r = kR1 * std::pow(kR2 / kR1, tl[static_cast<std::size_t>(p)]);
      const double a = kPhi * el[static_cast<std::size_t>(q)];
      err = std::max(err, std::hypot(g(p, q).x - r * std::cos(a), g(p, q).y - r * std::sin(a)));
    }
  return err / kR2;
}

BvpOptions options(int n, int iterations, LevelInterpolation interp = LevelInterpolation::kLinear) {
  BvpOptions o;
  o.theta_levels = graded_levels(n);
  o.eta_levels = graded_levels(n);
  o.max_iterations = iterations;
  o.min_iterations = iterations;
  o.interpolation = interp;
  return o;
}

TEST(OrthogonalBvp, AnnularSectorSecondOrderInThePlane) {
  std::vector<double> errors;
  for (int n : {16, 32, 64}) {
    // One outer iteration: θ, η on the (non-polar) TFI grid, so discretisation and level-line
    // interpolation both enter. Later iterations converge to a polar grid of similar cells, on
    // which the Q1 solution is exact at the nodes for these uniform levels.
    BvpOptions o = options(n, 1);
    o.project = project_sector;
    const BvpResult r = orthogonal_bvp(tfi_of(sector, n + 1, n + 1), o);
    errors.push_back(sector_error(r.grid, o.theta_levels, o.eta_levels));
    // Reciprocity: the discrete energies are upper bounds, E(θ)·E(η) ≥ 1.
    for (double e : r.energy_product) EXPECT_GE(e, 1.0);
    // W/H of the conformal rectangle = ln(R2/R1)/Φ (θ along r).
    EXPECT_NEAR(r.aspect_ratio.back(), std::log(kR2 / kR1) / kPhi, 2.0 / (n * n));
    std::printf("sector n = %d: node error %.3e, f_max %.3e, f_avg %.3e, E product - 1 = %.2e\n", n, errors.back(),
                r.f_max.back(), r.f_avg.back(), r.energy_product.back() - 1.0);
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    std::printf("sector order %.2f\n", order);
    EXPECT_GT(order, 1.8) << "the Q1 discretisation promises second order";
  }
  EXPECT_LT(errors.back(), 2e-4);
}

TEST(OrthogonalBvp, CubicInterpolationAlsoConverges) {
  std::vector<double> errors;
  for (int n : {16, 32, 64}) {
    BvpOptions o = options(n, 1, LevelInterpolation::kCubic);
    o.project = project_sector;
    errors.push_back(sector_error(orthogonal_bvp(tfi_of(sector, n + 1, n + 1), o).grid, o.theta_levels, o.eta_levels));
    std::printf("sector cubic n = %d: node error %.3e\n", n, errors.back());
  }
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_GT(std::log2(errors[k - 1] / errors[k]), 1.8);
}

// --- latitude-longitude rectangle on the unit sphere; i along longitude, j along latitude -------
constexpr double kLon1 = 0.0, kLon2 = 0.6, kLat1 = 0.3, kLat2 = 0.8;

Vec3 on_sphere(double lon, double lat) {
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}
Vec3 latlon(double u, double v) { return on_sphere(kLon1 + (kLon2 - kLon1) * u, kLat1 + (kLat2 - kLat1) * v); }
double mercator(double lat) { return std::log(std::tan(0.25 * kPi + 0.5 * lat)); }

void project_latlon(SurfaceGrid& g) {
  for (int j = 0; j < g.ny_pts; ++j)
    for (int i = 0; i < g.nx_pts; ++i) {
      Vec3& p = g(i, j);
      double lon = std::atan2(p.y, p.x), lat = std::atan2(p.z, std::hypot(p.x, p.y));
      if (i == 0) lon = kLon1;
      if (i + 1 == g.nx_pts) lon = kLon2;
      if (j == 0) lat = kLat1;
      if (j + 1 == g.ny_pts) lat = kLat2;
      p = on_sphere(lon, lat);
    }
}

double latlon_error(const SurfaceGrid& g, const std::vector<double>& tl, const std::vector<double>& el) {
  double err = 0.0;
  const double m1 = mercator(kLat1), m2 = mercator(kLat2);
  for (int q = 0; q < g.ny_pts; ++q)
    for (int p = 0; p < g.nx_pts; ++p) {
      const double lon = kLon1 + (kLon2 - kLon1) * tl[static_cast<std::size_t>(p)];
      const double lat = 2.0 * std::atan(std::exp(m1 + (m2 - m1) * el[static_cast<std::size_t>(q)])) - 0.5 * kPi;
      err = std::max(err, norm(g(p, q) - on_sphere(lon, lat)));
    }
  return err;
}

TEST(OrthogonalBvp, LatitudeLongitudeRectangleSecondOrderOnTheSphere) {
  std::vector<double> errors;
  for (int n : {16, 32, 64}) {
    BvpOptions o = options(n, 3);
    o.project = project_latlon;
    SurfaceGrid g0 = tfi_of(latlon, n + 1, n + 1);
    project_latlon(g0);
    const BvpResult r = orthogonal_bvp(g0, o);
    errors.push_back(latlon_error(r.grid, o.theta_levels, o.eta_levels));
    std::printf("lat-lon n = %d: node error %.3e, f_max %.3e, f_avg %.3e\n", n, errors.back(), r.f_max.back(),
                r.f_avg.back());
    EXPECT_LT(r.f_max.back(), 1e-2);
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double order = std::log2(errors[k - 1] / errors[k]);
    std::printf("lat-lon order %.2f\n", order);
    EXPECT_GT(order, 1.8);
  }
}

// --- seed 003's right-cornered channel with two curved walls (Table 2), 51 × 51 -----------------
Vec3 channel(double u, double v) {
  const double x = 2.0 * u;
  const double bottom = 0.25 * (1.0 - std::cos(kPi * x)), top = 1.0 + 0.15 * (1.0 - std::cos(kPi * x));
  return {x, bottom + v * (top - bottom), 0.0};
}

void project_channel(SurfaceGrid& g) {
  for (int i = 0; i < g.nx_pts; ++i)
    for (int j : {0, g.ny_pts - 1}) {
      Vec3& p = g(i, j);
      p = channel(std::clamp(p.x / 2.0, 0.0, 1.0), j == 0 ? 0.0 : 1.0);
    }
  for (int j = 0; j < g.ny_pts; ++j) {
    g(0, j).x = 0.0;
    g(g.nx_pts - 1, j).x = 2.0;
  }
}

TEST(OrthogonalBvp, ChannelFmaxFallsWithinThreeIterationsThenLevelsOff) {
  BvpOptions o = options(50, 10);
  o.min_iterations = 2;
  o.project = project_channel;
  const BvpResult r = orthogonal_bvp(tfi_of(channel, 51, 51), o);
  for (std::size_t k = 0; k < r.f_max.size(); ++k)
    std::printf("channel k = %zu: f_max %.6g, f_avg %.6g\n", k, r.f_max[k], r.f_avg[k]);
  EXPECT_GT(r.f_max[0], 0.1);  // the TFI grid: O(0.5) in the paper (0.46)
  ASSERT_GE(r.f_max.size(), 4U);
  EXPECT_LT(std::min({r.f_max[1], r.f_max[2], r.f_max[3]}), 2e-2);  // O(1e-3 … 1e-2) within 3
  EXPECT_LT(r.f_avg[3], 3e-3);
  // Levels off: the last step changes f_max and f_avg by < 1 % (the stopping rule), before k = 10.
  EXPECT_LT(r.iterations, 10);
  const std::size_t n = r.f_max.size();
  EXPECT_LT(std::fabs(r.f_max[n - 1] - r.f_max[n - 2]), 1e-2 * r.f_max[n - 2]);
  // In the plane f_max is check_grid's (46) worst.
  Grid2D g2(r.grid.nx_pts, r.grid.ny_pts);
  for (std::size_t k = 0; k < r.grid.p.size(); ++k) {
    g2.x[k] = r.grid.p[k].x;
    g2.y[k] = r.grid.p[k].y;
  }
  EXPECT_NEAR(check_grid(g2).ortho_46.worst, r.f_max[static_cast<std::size_t>(r.best_iteration)], 1e-12);
}

TEST(OrthogonalBvp, ClusteredLevelsClusterTheNodesAndKeepOrthogonality) {
  BvpOptions o = options(32, 3);
  o.theta_levels = graded_levels(32, 4.0);  // steps grow 4× from r = R1 to r = R2
  o.project = project_sector;
  const BvpResult r = orthogonal_bvp(tfi_of(sector, 33, 33), o);
  EXPECT_LT(sector_error(r.grid, o.theta_levels, o.eta_levels), 2e-3);
  const double first = norm(r.grid(1, 10) - r.grid(0, 10)), last = norm(r.grid(32, 10) - r.grid(31, 10));
  EXPECT_GT(last / first, 4.0);  // 4× in θ, and r grows with θ
}

TEST(OrthogonalBvp, SameBytesOnOneAndTwoThreads) {
  std::vector<SurfaceGrid> grids;
  for ([[maybe_unused]] int threads : {1, 2}) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    BvpOptions o = options(40, 3);
    o.project = project_channel;
    grids.push_back(orthogonal_bvp(tfi_of(channel, 41, 41), o).grid);
  }
  ASSERT_EQ(grids[0].p.size(), grids[1].p.size());
  EXPECT_EQ(std::memcmp(grids[0].p.data(), grids[1].p.data(), grids[0].p.size() * sizeof(Vec3)), 0);
}

TEST(OrthogonalBvp, TransfiniteInterpolationReproducesBilinearAndLevelsAreChecked) {
  const SurfaceGrid g = tfi_of([](double u, double v) { return Vec3{2 * u + 0.3 * v, v + 0.1 * u * v, 0.0}; }, 5, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) {
      const double u = i / 4.0, v = j / 3.0;
      EXPECT_NEAR(g(i, j).x, 2 * u + 0.3 * v, 1e-15);
      EXPECT_NEAR(g(i, j).y, v + 0.1 * u * v, 1e-15);
    }
  const auto l = graded_levels(10, 3.0);
  EXPECT_EQ(l.front(), 0.0);
  EXPECT_EQ(l.back(), 1.0);
  EXPECT_NEAR((l[10] - l[9]) / (l[1] - l[0]), 3.0, 1e-12);
  EXPECT_THROW(graded_levels(0), InternalError);
  BvpOptions o = options(4, 1);
  o.theta_levels = {0.0, 0.5, 0.5, 1.0};
  EXPECT_THROW(orthogonal_bvp(tfi_of(sector, 5, 5), o), InternalError);
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_orthogonal_bvp_test

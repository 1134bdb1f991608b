// SPDX-License-Identifier: GPL-3.0-or-later
// The gradient limiter against the exact solution h′(x) = min over sources of (h_s + g·dist(s, x))
// computed by brute force with great-circle distances: on a near-planar equatorial patch, across
// the seam, over the pole of the lon-lat lattice, on the Mercator lattice of a rotated frame (with
// distances taken between the geographic positions, so the rotation is checked too), and for a
// field where every cell is a source. Also the distance transform and the sweep count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/rotation.hpp"
#include "core/types.hpp"
#include "size/limit_gradient.hpp"

namespace aq::size::unit_size_limit_gradient_test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double haversine_km(double lon1, double lat1, double lon2, double lat2) {
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad, dl = (lon2 - lon1) * kDegToRad;
  const double a = std::pow(std::sin((p2 - p1) / 2), 2) + std::cos(p1) * std::cos(p2) * std::pow(std::sin(dl / 2), 2);
  return 2.0 * kEarthRadiusKm * std::asin(std::min(1.0, std::sqrt(a)));
}

// The exact limited field by brute force; positions of cell centres given by `pos` (geographic).
template <typename Pos>
std::vector<double> brute_force(const FieldGrid& g, const std::vector<double>& h, double grad, const Pos& pos) {
  std::vector<double> out(h.size(), kInf);
  std::vector<std::int64_t> src;
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h[k] < kInf) src.push_back(static_cast<std::int64_t>(k));
  for (std::int64_t k = 0; k < g.cells(); ++k) {
    double lo = 0, la = 0;
    pos(k, lo, la);
    for (const std::int64_t s : src) {
      double slo = 0, sla = 0;
      pos(s, slo, sla);
      out[static_cast<std::size_t>(k)] =
          std::min(out[static_cast<std::size_t>(k)], h[static_cast<std::size_t>(s)] + grad * haversine_km(slo, sla, lo, la));
    }
  }
  return out;
}

// Largest |limited − exact| and whether limited >= exact everywhere (up to rounding).
void expect_matches(const std::vector<double>& got, const std::vector<double>& exact, double tol_km) {
  double worst = 0.0;
  std::int64_t below = 0;
  for (std::size_t k = 0; k < got.size(); ++k) {
    if (!std::isfinite(exact[k])) {
      EXPECT_FALSE(std::isfinite(got[k])) << k;
      continue;
    }
    worst = std::max(worst, std::fabs(got[k] - exact[k]));
    below += got[k] < exact[k] - 1e-6 ? 1 : 0;
  }
  EXPECT_EQ(below, 0);
  EXPECT_LE(worst, tol_km);
}

auto lattice_pos(const FieldGrid& g) {
  return [&g](std::int64_t k, double& lo, double& la) {
    lo = g.lon_deg(k % g.nx());
    la = g.lat_deg(k / g.nx());
  };
}

TEST(LimitGradient, FewSourcesOnAnEquatorialPatchAreTheExactMinimum) {
  const FieldGrid g(Lattice::make(10.0, 2, -180.0), 2);  // 144 x 72 cells of 2.5°
  std::vector<double> h(static_cast<std::size_t>(g.cells()), kInf);
  h[static_cast<std::size_t>(g.index(70, 36))] = 50.0;
  h[static_cast<std::size_t>(g.index(80, 34))] = 20.0;
  h[static_cast<std::size_t>(g.index(75, 40))] = 300.0;
  const std::vector<double> exact = brute_force(g, h, 0.2, lattice_pos(g));
  std::vector<std::int32_t> src;
  limit_gradient(g, h, 0.2, &src);
  // Within 1% of g·cell (278 km cells): a cell may take a neighbour's source where two weighted
  // Voronoi regions meet at a sliver.
  expect_matches(h, exact, 0.01 * 0.2 * 278.0);
  EXPECT_EQ(src[static_cast<std::size_t>(g.index(80, 34))], g.index(80, 34));
  // (70, 30) is 4.5 cells from the 50 km source: 50 + 0.2 · dist.
  EXPECT_NEAR(h[static_cast<std::size_t>(g.index(70, 30))], exact[static_cast<std::size_t>(g.index(70, 30))], 1e-6);
}

TEST(LimitGradient, EveryCellASourceRandomField) {
  const FieldGrid g(Lattice::make(20.0, 2, -180.0), 2);  // 72 x 36 cells of 5° (556 km)
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(10.0, 2000.0);
  std::vector<double> h(static_cast<std::size_t>(g.cells()));
  for (double& x : h) x = u(rng);
  const std::vector<double> exact = brute_force(g, h, 0.15, lattice_pos(g));
  limit_gradient(g, h, 0.15);
  // Cells whose weighted Voronoi region is thinner than a cell may take a neighbour's source.
  expect_matches(h, exact, 0.02 * 0.15 * 556.0);
}

TEST(LimitGradient, PropagatesAcrossTheSeam) {
  const FieldGrid g(Lattice::make(10.0, 2, -180.0), 2);
  std::vector<double> h(static_cast<std::size_t>(g.cells()), kInf);
  h[static_cast<std::size_t>(g.index(g.nx() - 1, 36))] = 10.0;  // just west of the seam
  h[static_cast<std::size_t>(g.index(3, 50))] = 10.0;            // just east of it
  const std::vector<double> exact = brute_force(g, h, 0.3, lattice_pos(g));
  limit_gradient(g, h, 0.3);
  expect_matches(h, exact, 1e-6);
  // One cell east of the seam is one cell (278 km) from the western source.
  EXPECT_NEAR(h[static_cast<std::size_t>(g.index(0, 36))], 10.0 + 0.3 * 277.9, 1.0);
}

TEST(LimitGradient, CrossesThePoleOfTheLonLatLattice) {
  const FieldGrid g(Lattice::make(10.0, 2, -180.0), 2);
  std::vector<double> h(static_cast<std::size_t>(g.cells()), kInf);
  h[static_cast<std::size_t>(g.index(0, g.ny() - 1))] = 5.0;  // 88.75°N, λ = -178.75°
  const std::vector<double> exact = brute_force(g, h, 0.25, lattice_pos(g));
  limit_gradient(g, h, 0.25);
  expect_matches(h, exact, 1e-6);
  // Across the pole (λ + 180°) the distance is 2.5° of latitude, not half the parallel.
  EXPECT_NEAR(h[static_cast<std::size_t>(g.index(g.nx() / 2, g.ny() - 1))], 5.0 + 0.25 * 2.5 * kDegToRad * kEarthRadiusKm,
              1e-6);
}

TEST(LimitGradient, RotatedMercatorFrameMatchesGeographicDistances) {
  const Lattice lat = Lattice::make_mercator(10.0, 2, -180.0, 80.0);
  const FieldGrid g(lat, 2);
  const PoleRotation rot(-44.858333, 78.141667);
  std::vector<double> h(static_cast<std::size_t>(g.cells()), kInf);
  h[static_cast<std::size_t>(g.index(10, 20))] = 30.0;
  h[static_cast<std::size_t>(g.index(100, 60))] = 15.0;
  h[static_cast<std::size_t>(g.index(140, 5))] = 60.0;
  const std::vector<double> exact = brute_force(g, h, 0.2, [&](std::int64_t k, double& lo, double& la) {
    rot.to_geographic(g.lon_deg(k % g.nx()), g.lat_deg(k / g.nx()), lo, la);
  });
  limit_gradient(g, h, 0.2);
  expect_matches(h, exact, 1e-6);
}

TEST(DistanceTo, ZeroAtSourcesAndGreatCircleElsewhere) {
  const FieldGrid g(Lattice::make(10.0, 2, -180.0), 2);
  std::vector<std::uint8_t> src(static_cast<std::size_t>(g.cells()), 0);
  src[static_cast<std::size_t>(g.index(20, 36))] = 1;
  std::vector<std::int32_t> nearest;
  const std::vector<double> d = distance_to(g, src, &nearest);
  EXPECT_EQ(d[static_cast<std::size_t>(g.index(20, 36))], 0.0);
  EXPECT_NEAR(d[static_cast<std::size_t>(g.index(20, 40))], 4 * 2.5 * kDegToRad * kEarthRadiusKm, 1e-6);
  EXPECT_EQ(nearest[static_cast<std::size_t>(g.index(50, 10))], g.index(20, 36));
  const std::vector<double> none = distance_to(g, std::vector<std::uint8_t>(src.size(), 0));
  EXPECT_FALSE(std::isfinite(none[0]));
}

}  // namespace
}  // namespace aq::size::unit_size_limit_gradient_test

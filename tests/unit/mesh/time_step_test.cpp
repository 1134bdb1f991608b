// SPDX-License-Identifier: GPL-3.0-or-later
// The time step per triangle (mesh/time_step.hpp) takes cos φ of each node once; its values stay
// those of the textbook haversine written out per edge, bit for bit (nodes anywhere on the sphere,
// at the poles, across the seam, pole-row edges shorter than a millimetre), the same on 1 and 2
// threads, and a 1° meridian edge over 100 m of water is 111.2 km / √(g·100). The smallest step
// found with lower bounds of the edges is the first smallest of every triangle's step, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/types.hpp"
#include "mesh/time_step.hpp"

namespace aq::mesh::unit_mesh_time_step_test {

namespace {

constexpr double kR = 6371008.8;
constexpr double kG = 9.81;

// The formula as it stood before cos φ was tabled per node: every sine and cosine per edge.
double haversine_m(double lon1, double lat1, double lon2, double lat2) {
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad;
  const double dp = p2 - p1, dl = (lon2 - lon1) * kDegToRad;
  const double a =
      std::sin(dp / 2) * std::sin(dp / 2) + std::cos(p1) * std::cos(p2) * std::sin(dl / 2) * std::sin(dl / 2);
  return 2.0 * kR * std::asin(std::min(1.0, std::sqrt(a)));
}

struct Nodes {
  std::vector<double> lon, lat, depth;
  std::vector<std::array<NodeId, 3>> tri;
};

Nodes random_nodes(unsigned seed, int n_nodes, int n_tri) {
  Nodes s;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> lon(-180.0, 180.0), lat(-90.0, 90.0), depth(-50.0, 6000.0);
  for (int k = 0; k < n_nodes; ++k) {
    s.lon.push_back(lon(rng));
    s.lat.push_back(lat(rng));
    s.depth.push_back(depth(rng));
  }
  // The poles, a pole row (nodes 1e-9° apart: an edge below kMinEdgeM) and the seam.
  for (const auto& [lo, la] : std::vector<std::array<double, 2>>{
           {0.0, 90.0}, {1e-9, 90.0}, {120.0, -90.0}, {179.999, 10.0}, {-179.999, 10.0}, {180.0, 10.001}}) {
    s.lon.push_back(lo);
    s.lat.push_back(la);
    s.depth.push_back(depth(rng));
  }
  std::uniform_int_distribution<NodeId> node(0, static_cast<NodeId>(s.lon.size() - 1));
  for (int t = 0; t < n_tri; ++t) s.tri.push_back({node(rng), node(rng), node(rng)});
  const auto last = static_cast<NodeId>(s.lon.size());
  s.tri.push_back({last - 6, last - 5, last - 4});  // both poles, a sub-millimetre edge
  s.tri.push_back({last - 3, last - 2, last - 1});  // across the seam
  return s;
}

}  // namespace

// A lon–lat lattice of nx × ny cells of `cell_deg` from (lon0, lat0), two triangles per cell,
// one depth everywhere but a deeper node at `deep` (-1: none): every triangle of a row has
// the same edges up to rounding, so the smallest dt has near-ties and exact ties.
Nodes lattice(int nx, int ny, double lon0, double lat0, double cell_deg, NodeId deep) {
  Nodes s;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      s.lon.push_back(lon0 + cell_deg * i);
      s.lat.push_back(std::min(90.0, lat0 + cell_deg * j));
      s.depth.push_back(static_cast<NodeId>(s.depth.size()) == deep ? 5000.0 : 4000.0);
    }
  const auto id = [nx](int i, int j) { return static_cast<NodeId>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      s.tri.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.tri.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

// Every triangle's dt against the haversine written out per edge, bit for bit.
void expect_haversine_bit_for_bit(const Nodes& s, double min_depth) {
  const std::vector<double> dt = triangle_time_steps(s.lon, s.lat, s.depth, s.tri, min_depth);
  ASSERT_EQ(dt.size(), s.tri.size());
  std::int64_t compared = 0;
  for (std::size_t t = 0; t < s.tri.size(); ++t) {
    double edge = std::numeric_limits<double>::infinity(), h = min_depth;
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(s.tri[t][static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::size_t>(s.tri[t][static_cast<std::size_t>((k + 1) % 3)]);
      const double len = haversine_m(s.lon[a], s.lat[a], s.lon[b], s.lat[b]);
      if (len > 1e-3) edge = std::min(edge, len);
      h = std::max(h, s.depth[a]);
    }
    const double want = edge / std::sqrt(kG * h);
    if (dt[t] == want || (std::isinf(dt[t]) && std::isinf(want)))
      ++compared;
    else
      ADD_FAILURE() << "triangle " << t << ": " << dt[t] << " != " << want;
  }
  EXPECT_EQ(compared, static_cast<std::int64_t>(s.tri.size()));
}

TEST(TimeStep, TriangleStepsAreThePerEdgeHaversineBitForBit) {
  // Random nodes (each of its own latitude), and lattices numbered by row (cos φ taken once per
  // row of nodes), one across the equator with −0 and +0 latitudes in its row.
  expect_haversine_bit_for_bit(random_nodes(7u, 5000, 20000), 10.0);
  expect_haversine_bit_for_bit(lattice(720, 30, -180.0, 75.0, 0.5, -1), 10.0);
  Nodes equator = lattice(400, 40, 0.0, -10.0, 0.5, -1);
  for (std::size_t k = 0; k < equator.lat.size(); k += 2)
    if (equator.lat[k] == 0.0) equator.lat[k] = -0.0;
  expect_haversine_bit_for_bit(equator, 10.0);
}

TEST(TimeStep, OneDegreeMeridianEdge) {
  // A right triangle of 1° legs on the equator; its shortest edges are the 1° legs (111.195 km).
  const std::vector<double> lon{0.0, 1.0, 0.0}, lat{0.0, 0.0, 1.0}, depth{100.0, 50.0, 20.0};
  const std::vector<std::array<NodeId, 3>> tri{{0, 1, 2}};
  const std::vector<double> dt = triangle_time_steps(lon, lat, depth, tri, 10.0);
  ASSERT_EQ(dt.size(), 1u);
  EXPECT_NEAR(dt[0], kR * kDegToRad / std::sqrt(kG * 100.0), 1e-6);
  EXPECT_NEAR(dt[0], 3550.1, 0.1);
}

// smallest_time_step against the first smallest of every triangle's dt, bit for bit.
void expect_smallest_of_all(const Nodes& s, double min_depth) {
  const std::vector<double> dt = triangle_time_steps(s.lon, s.lat, s.depth, s.tri, min_depth);
  const auto it = std::min_element(dt.begin(), dt.end());
  const SmallestTimeStep got = smallest_time_step(s.lon, s.lat, s.depth, s.tri, min_depth);
  EXPECT_EQ(got.triangle, it - dt.begin());
  EXPECT_EQ(std::bit_cast<std::uint64_t>(got.dt_s), std::bit_cast<std::uint64_t>(*it));
}

TEST(TimeStep, SmallestStepIsTheFirstSmallestOfEveryTriangleStep) {
  // Random triangles: long edges (sine arguments up to π/2 and beyond the bound's range), the
  // poles, the seam and a sub-millimetre edge.
  for (const unsigned seed : {3u, 4u, 5u}) expect_smallest_of_all(random_nodes(seed, 3000, 30000), 10.0);
  // Lattices from the equator to the pole row (edges of zero length), fine and coarse, with the
  // smallest step in the polar row, and with one deeper node moving it elsewhere.
  expect_smallest_of_all(lattice(720, 30, -180.0, 75.0, 0.5, -1), 10.0);
  expect_smallest_of_all(lattice(2000, 100, 10.0, 89.0, 0.01, -1), 10.0);
  expect_smallest_of_all(lattice(2000, 100, 10.0, -20.0, 0.01, 2000 * 50 + 700), 10.0);
  expect_smallest_of_all(lattice(400, 200, -180.0, -89.0, 4.0 / 15.0 / 60.0, -1), 4500.0);
  // No triangle with an edge over 1 mm: every dt is +inf, the first triangle holds the smallest.
  expect_smallest_of_all(lattice(10, 1, 0.0, 90.0, 1e-12, -1), 10.0);
}

TEST(TimeStep, SmallestStepWithoutTriangles) {
  const SmallestTimeStep none = smallest_time_step({0.0}, {0.0}, {10.0}, {}, 10.0);
  EXPECT_EQ(none.triangle, -1);
}

#ifdef _OPENMP
TEST(TimeStep, SmallestStepSameOnOneAndTwoThreads) {
  const Nodes s = lattice(3000, 200, -180.0, 60.0, 0.01, -1);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const SmallestTimeStep one = smallest_time_step(s.lon, s.lat, s.depth, s.tri, 10.0);
  omp_set_num_threads(2);
  const SmallestTimeStep two = smallest_time_step(s.lon, s.lat, s.depth, s.tri, 10.0);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.triangle, two.triangle);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(one.dt_s), std::bit_cast<std::uint64_t>(two.dt_s));
  expect_smallest_of_all(s, 10.0);
}

TEST(TimeStep, SameOnOneAndTwoThreads) {
  const Nodes s = random_nodes(11u, 50000, 200000);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<double> one = triangle_time_steps(s.lon, s.lat, s.depth, s.tri, 5.0);
  omp_set_num_threads(2);
  const std::vector<double> two = triangle_time_steps(s.lon, s.lat, s.depth, s.tri, 5.0);
  omp_set_num_threads(saved);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t t = 0; t < one.size(); ++t)
    if (!(one[t] == two[t] || (std::isinf(one[t]) && std::isinf(two[t])))) {
      ADD_FAILURE() << "triangle " << t << ": " << one[t] << " vs " << two[t];
      break;
    }
}
#endif

}  // namespace aq::mesh::unit_mesh_time_step_test

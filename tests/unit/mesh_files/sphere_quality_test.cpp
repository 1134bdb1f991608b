// SPDX-License-Identifier: GPL-3.0-or-later
// Shape quality on the sphere: order statistics against a sort, per-triangle values against
// closed forms and the spherical law of cosines (computed here independently), and the same
// values for 1 and 2 threads.
#include "mesh_files/sphere_quality.hpp"

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

#include "core/error.hpp"
#include "support/io_test_mesh.hpp"
#include "support/omp_threads.hpp"

namespace aq::io::unit_mesh_files_sphere_quality_test {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A mesh of the given lon/lat nodes and triangles.
mesh::Mesh nodes_and_triangles(const std::vector<std::array<double, 2>>& ll,
                               const std::vector<std::array<NodeId, 3>>& tris) {
  mesh::Mesh m;
  for (const auto& p : ll) {
    m.lon_deg.push_back(p[0]);
    m.lat_deg.push_back(p[1]);
  }
  m.triangles = tris;
  return m;
}

// Angle at vertex a of the spherical triangle a, b, c from its side lengths (law of cosines).
double law_of_cosines_deg(const std::array<double, 2>& a, const std::array<double, 2>& b,
                          const std::array<double, 2>& c) {
  auto dist = [](const std::array<double, 2>& p, const std::array<double, 2>& q) {
    const double s = std::sin(p[1] * kDeg) * std::sin(q[1] * kDeg) +
                     std::cos(p[1] * kDeg) * std::cos(q[1] * kDeg) * std::cos((p[0] - q[0]) * kDeg);
    return std::acos(std::clamp(s, -1.0, 1.0));
  };
  const double ab = dist(a, b), ac = dist(a, c), bc = dist(b, c);
  return std::acos((std::cos(bc) - std::cos(ab) * std::cos(ac)) / (std::sin(ab) * std::sin(ac))) / kDeg;
}

TEST(SphereQuality, OrderStatisticIsTheSortedValueOfRankFloorQTimesNMinus1) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 60.0f);
  for (const std::size_t n : {1u, 2u, 7u, 1000u, 300001u}) {
    std::vector<float> v(n);
    for (auto& x : v) x = u(rng);
    if (n > 10) {
      v[3] = 0.0f;  // ties, zero and infinity sort like numbers
      v[4] = v[5];
      v[6] = std::numeric_limits<float>::infinity();
    }
    std::vector<float> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    for (const double q : {0.0, 0.01, 0.05, 0.5, 0.99, 1.0}) {
      const auto rank = static_cast<std::size_t>(std::floor(q * static_cast<double>(n - 1)));
      EXPECT_EQ(order_statistic(v, q), sorted[rank]) << "n " << n << " q " << q;
    }
  }
  EXPECT_THROW((void)order_statistic({}, 0.5), InternalError);
}

TEST(SphereQuality, ClosedFormsForSmallTrianglesAndNeighbourRatios) {
  // Near the equator, legs of 0.01°: a right-isosceles triangle (45°, 45°, 90°; edge ratio √2)
  // and, sharing its hypotenuse, one with twice the area.
  const double h = 0.01;
  const auto m = nodes_and_triangles({{0, 0}, {h, 0}, {0, h}, {2 * h, 2 * h}}, {{0, 1, 2}, {1, 3, 2}});
  const TriangleShapes s = triangle_shapes(m);
  ASSERT_EQ(s.min_angle_deg.size(), 2u);
  EXPECT_NEAR(s.min_angle_deg[0], 45.0, 1e-3);
  EXPECT_NEAR(s.edge_ratio[0], std::sqrt(2.0), 1e-4);
  // Triangle 1 = (h,0), (2h,2h), (0,h): area 1.5 h² against 0.5 h².
  EXPECT_NEAR(s.neighbour_area_ratio[0], 3.0, 1e-3);
  EXPECT_NEAR(s.neighbour_area_ratio[1], 3.0, 1e-3);
  EXPECT_NEAR(s.size_km[0], (2.0 + std::sqrt(2.0)) / 3.0 * h * kDeg * 6371.0072, 1e-4);
  const SphereQuality q = summarize_quality(s);
  EXPECT_EQ(q.triangles, 2);
  EXPECT_NEAR(q.min_angle_p0_deg, std::min(s.min_angle_deg[0], s.min_angle_deg[1]), 1e-6);
  EXPECT_EQ(q.below_20_deg_percent, 0.0);
  // A triangle without neighbours has ratio 1; a zero-area one makes its neighbour's infinite.
  const auto lone = nodes_and_triangles({{0, 0}, {1, 0}, {0, 1}, {2, 0}}, {{0, 1, 2}, {1, 0, 3}});
  const TriangleShapes ls = triangle_shapes(lone);
  EXPECT_TRUE(std::isinf(ls.neighbour_area_ratio[0]));
  EXPECT_EQ(ls.min_angle_deg[1], 0.0f);
  EXPECT_EQ(summarize_quality(TriangleShapes{}).triangles, 0);
}

TEST(SphereQuality, MinAnglesAgreeWithTheLawOfCosinesOnLargeTriangles) {
  // The tiny test mesh: 22.5°–45° triangles up to 90° latitude, where the sphere matters.
  const auto m = testing::tiny_mesh();
  const TriangleShapes s = triangle_shapes(m);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    std::array<std::array<double, 2>, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto n = static_cast<std::size_t>(m.triangles[t][k]);
      p[k] = {m.lon_deg[n], m.lat_deg[n]};
    }
    const bool degenerate = (p[0][1] == 90.0 && p[1][1] == 90.0) || (p[1][1] == 90.0 && p[2][1] == 90.0) ||
                            (p[2][1] == 90.0 && p[0][1] == 90.0);
    if (degenerate) {
      EXPECT_LT(s.min_angle_deg[t], 1e-3) << t;  // two nodes on the pole: a zero angle
      continue;
    }
    const double want = std::min({law_of_cosines_deg(p[0], p[1], p[2]), law_of_cosines_deg(p[1], p[2], p[0]),
                                  law_of_cosines_deg(p[2], p[0], p[1])});
    EXPECT_NEAR(s.min_angle_deg[t], want, 1e-4) << t;
  }
}

// Several ranks at once, some equal, some in one bin of the high 16 bits (values packed into
// [30, 30.01)), on one and two threads: each the value of its rank in the sorted values.
TEST(SphereQuality, OrderStatisticsOfManyRanksAtOnceAreTheSortedValues) {
  std::mt19937 rng(34);
  std::uniform_real_distribution<float> narrow(30.0f, 30.01f), wide(0.0f, 180.0f);
  std::vector<float> v(300001);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = k % 3 == 0 ? wide(rng) : narrow(rng);
  std::vector<float> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  const std::vector<double> qs{0.5, 0.0, 0.99, 0.5, 0.4, 0.41, 0.6, 1.0, 0.01, 0.4000001};
  for (const int threads : {1, 2}) {
    const testing::ThreadCount use(threads);
    const std::vector<float> got = order_statistics(v, qs);
    ASSERT_EQ(got.size(), qs.size());
    for (std::size_t k = 0; k < qs.size(); ++k) {
      const auto rank = static_cast<std::size_t>(std::floor(qs[k] * static_cast<double>(v.size() - 1)));
      EXPECT_EQ(got[k], sorted[rank]) << "q " << qs[k] << ", " << threads << " threads";
    }
  }
}

// The per-triangle values depend on the triangles' corners only, not on the node numbering: the
// nodes in lattice row order (each row's cos φ and sin φ taken once, a row of the equator with
// −0 and +0 latitudes among it) and shuffled (every node's taken afresh) give the same bits.
TEST(SphereQuality, NodeOrderDoesNotChangeTheValues) {
  const Lattice lat = Lattice::make(4.0, 4, -180.0);
  mesh::Mesh rows = testing::regular_band_mesh(lat, 300, 420);  // the equator: J = 360
  std::int64_t signed_zeros = 0;
  for (std::size_t k = 0; k < rows.lat_deg.size(); ++k)
    if (rows.lat_deg[k] == 0.0 && k % 2 == 0) {
      rows.lat_deg[k] = -0.0;
      ++signed_zeros;
    }
  ASSERT_GT(signed_zeros, 100);
  std::vector<NodeId> to(rows.lon_deg.size());
  for (std::size_t k = 0; k < to.size(); ++k) to[k] = static_cast<NodeId>(k);
  std::shuffle(to.begin(), to.end(), std::mt19937(5));
  mesh::Mesh shuffled;
  shuffled.lon_deg.resize(to.size());
  shuffled.lat_deg.resize(to.size());
  for (std::size_t k = 0; k < to.size(); ++k) {
    shuffled.lon_deg[static_cast<std::size_t>(to[k])] = rows.lon_deg[k];
    shuffled.lat_deg[static_cast<std::size_t>(to[k])] = rows.lat_deg[k];
  }
  for (const auto& t : rows.triangles)
    shuffled.triangles.push_back(
        {to[static_cast<std::size_t>(t[0])], to[static_cast<std::size_t>(t[1])], to[static_cast<std::size_t>(t[2])]});
  const TriangleShapes a = triangle_shapes(rows), b = triangle_shapes(shuffled);
  const auto bits = [](const std::vector<float>& v) {
    std::vector<std::uint32_t> out(v.size());
    std::transform(v.begin(), v.end(), out.begin(), [](float x) { return std::bit_cast<std::uint32_t>(x); });
    return out;
  };
  EXPECT_EQ(bits(a.min_angle_deg), bits(b.min_angle_deg));
  EXPECT_EQ(bits(a.max_angle_deg), bits(b.max_angle_deg));
  EXPECT_EQ(bits(a.edge_ratio), bits(b.edge_ratio));
  EXPECT_EQ(bits(a.neighbour_area_ratio), bits(b.neighbour_area_ratio));
  EXPECT_EQ(bits(a.size_km), bits(b.size_km));
}

TEST(SphereQuality, SameValuesForOneAndTwoThreads) {
  // Enough triangles (~4e5) for the loops and histograms to run in parallel.
  const Lattice lat = Lattice::make(4.0, 4, -180.0);
  const auto m = testing::regular_band_mesh(lat, 100, 220);
#ifdef _OPENMP
  omp_set_num_threads(1);
#endif
  const TriangleShapes a = triangle_shapes(m);
  const auto qa = summarize_quality(a).json().dump();
#ifdef _OPENMP
  omp_set_num_threads(2);
#endif
  const TriangleShapes b = triangle_shapes(m);
  const auto qb = summarize_quality(b).json().dump();
  ASSERT_GT(a.min_angle_deg.size(), 300000u);
  EXPECT_EQ(a.min_angle_deg, b.min_angle_deg);
  EXPECT_EQ(a.neighbour_area_ratio, b.neighbour_area_ratio);
  EXPECT_EQ(a.edge_ratio, b.edge_ratio);
  EXPECT_EQ(qa, qb);
}

// Node ids are checked first, in parallel: the error names the first bad id in triangle order.
TEST(SphereQuality, ANodeOutOfRangeThrowsNamingTheFirstOne) {
  const Lattice lat = Lattice::make(4.0, 4, -180.0);
  auto m = testing::regular_band_mesh(lat, 100, 220);
  ASSERT_GT(m.triangles.size(), 300000u);  // the search runs on two threads
  const auto last = m.triangles.size() - 1;
  m.triangles[last][0] = -3;
  m.triangles[last / 4][2] = static_cast<NodeId>(m.lon_deg.size());
  for (const int threads : {1, 2}) {
    const testing::ThreadCount use(threads);
    try {
      (void)triangle_shapes(m);
      ADD_FAILURE() << "no error";
    } catch (const InternalError& e) {
      EXPECT_EQ(std::string(e.what()), "triangle_shapes: node " + std::to_string(m.lon_deg.size()) + " out of range")
          << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace aq::io::unit_mesh_files_sphere_quality_test

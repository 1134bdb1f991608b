// SPDX-License-Identifier: GPL-3.0-or-later
// The pole cap triangulation (mesh/pole_cap.hpp): conforming to ring 0, anticlockwise, nearly
// equilateral, modest valence, and exactly the area of the geodesic polygon of ring 0.
#include "mesh/pole_cap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"

namespace aq::mesh::unit_mesh_pole_cap_test {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 unit(double lon_deg, double lat_deg) {
  const double lo = lon_deg * kDegToRad, la = lat_deg * kDegToRad;
  return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 2.0 * std::atan2(dot(a, cross(b, c)), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
}
double angle_at(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 tq = cross(cross(p, q), p), tr = cross(cross(p, r), p);
  return std::atan2(std::sqrt(dot(cross(tq, tr), cross(tq, tr))), dot(tq, tr)) / kDegToRad;
}

struct CapFacts {
  double min_angle = 180.0, area_cap = 0.0, area_ring = 0.0, area_island = 0.0;
  std::int64_t island_edges_found = 0;
  int max_valence = 0;
  std::int64_t bad_edges = 0, boundary_edges = 0, wrong_boundary = 0, not_anticlockwise = 0;
};

CapFacts facts(const std::vector<double>& ring_lon, double ring_lat, bool north, const PoleCap& cap) {
  const auto n0 = static_cast<NodeId>(ring_lon.size());
  auto pos = [&](NodeId v) {
    if (v < n0) return unit(ring_lon[static_cast<std::size_t>(v)], ring_lat);
    return unit(cap.rlon_deg[static_cast<std::size_t>(v - n0)], cap.rlat_deg[static_cast<std::size_t>(v - n0)]);
  };
  CapFacts f;
  std::map<std::pair<NodeId, NodeId>, int> half;
  std::map<NodeId, int> valence;
  for (const auto& t : cap.triangles) {
    const Vec3 a = pos(t[0]), b = pos(t[1]), c = pos(t[2]);
    const double s = area(a, b, c);
    if (!(s > 0.0)) ++f.not_anticlockwise;
    f.area_cap += s;
    f.min_angle = std::min({f.min_angle, angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
    for (int e = 0; e < 3; ++e) {
      ++half[{t[e], t[(e + 1) % 3]}];
      ++valence[t[e]];
    }
  }
  for (const auto& [e, k] : half) {
    if (k != 1) ++f.bad_edges;
    if (half.count({e.second, e.first}) == 0) {
      ++f.boundary_edges;
      // The cap's boundary is ring 0, traversed so that the cap is on the left.
      const NodeId a = e.first, b = e.second;
      const bool ring_edge = a < n0 && b < n0 && (north ? b == (a + 1) % n0 : a == (b + 1) % n0);
      const bool island_edge = a >= n0 && b >= n0;
      if (!ring_edge && !island_edge) ++f.wrong_boundary;
    }
  }
  for (const auto& [v, k] : valence) f.max_valence = std::max(f.max_valence, k);
  // The geodesic polygon of ring 0 as a fan from the pole, and the island's (its loop runs
  // with the wet area on the left, so the fan turns the other way).
  const Vec3 pole = unit(0.0, north ? 90.0 : -90.0);
  for (NodeId k = 0; k < n0; ++k) {
    const Vec3 a = pos(k), b = pos((k + 1) % n0);
    f.area_ring += north ? area(a, b, pole) : area(b, a, pole);
  }
  const auto ni = cap.island.size();
  for (std::size_t k = 0; k < ni; ++k) f.area_island -= area(pos(cap.island[k]), pos(cap.island[(k + 1) % ni]), pole);
  // The boundary half-edges of the triangles that are not ring 0 are the island's loop.
  for (std::size_t k = 0; k < ni; ++k) {
    const auto e = std::make_pair(cap.island[k], cap.island[(k + 1) % ni]);
    if (half.count(e) == 1 && half.count({e.second, e.first}) == 0) ++f.island_edges_found;
  }
  return f;
}

std::vector<double> uniform_ring(int n, double lon0) {
  std::vector<double> v;
  for (int k = 0; k < n; ++k) v.push_back(lon0 + 360.0 * k / n);
  return v;
}

TEST(PoleCap, DefaultRunRingIsWellShaped) {
  // The seed's reference run: 90 level-0 squares (4°) on the row 86°N.
  const auto ring = uniform_ring(90, -180.0);
  const PoleCap cap = make_pole_cap(ring, 86.0, true);
  const CapFacts f = facts(ring, 86.0, true, cap);
  EXPECT_EQ(f.bad_edges, 0);
  EXPECT_EQ(f.boundary_edges, 90 + static_cast<std::int64_t>(cap.island.size()));
  EXPECT_EQ(f.wrong_boundary, 0);
  EXPECT_EQ(f.island_edges_found, static_cast<std::int64_t>(cap.island.size()));
  EXPECT_EQ(f.not_anticlockwise, 0);
  EXPECT_GE(f.min_angle, 35.0);
  EXPECT_LE(f.max_valence, 8);
  EXPECT_GE(cap.rings, 6);
  EXPECT_GE(cap.island.size(), 4U);
  EXPECT_LE(cap.island.size(), 7U);
  // The island is about one element across: well under the 4° of the row it sits in.
  EXPECT_GT(cap.island_radius_deg, 0.3);
  EXPECT_LT(cap.island_radius_deg, 1.5);
  EXPECT_NEAR(f.area_cap + f.area_island, f.area_ring, 1e-12 * f.area_ring);
  for (const double la : cap.rlat_deg) EXPECT_LT(la, 90.0 - 0.3);
}

TEST(PoleCap, SouthIsTheMirrorImage) {
  const auto ring = uniform_ring(90, -180.0);
  const PoleCap cap = make_pole_cap(ring, -86.0, false);
  const CapFacts f = facts(ring, -86.0, false, cap);
  EXPECT_EQ(f.bad_edges, 0);
  EXPECT_EQ(f.wrong_boundary, 0);
  EXPECT_EQ(f.not_anticlockwise, 0);
  EXPECT_EQ(f.island_edges_found, static_cast<std::int64_t>(cap.island.size()));
  EXPECT_GE(f.min_angle, 35.0);
  EXPECT_NEAR(f.area_cap + f.area_island, f.area_ring, 1e-12 * f.area_ring);
  for (const double la : cap.rlat_deg) EXPECT_GT(la, -90.0 + 0.3);
}

TEST(PoleCap, UnevenRingAcrossTheSeam) {
  // Level-0, level-1 and level-2 squares below the ring (spacings 4°, 2°, 1°), ring starting
  // east of the seam so the cap's angles run past λ0 + 360.
  std::vector<double> ring;
  double lon = -170.0;
  for (int k = 0; k < 60; ++k, lon += 4.0) ring.push_back(lon);
  for (int k = 0; k < 40; ++k, lon += 2.0) ring.push_back(lon);
  for (int k = 0; k < 40; ++k, lon += 1.0) ring.push_back(lon);
  ASSERT_NEAR(lon, 190.0, 1e-9);
  const PoleCap cap = make_pole_cap(ring, 86.0, true);
  const CapFacts f = facts(ring, 86.0, true, cap);
  EXPECT_EQ(f.bad_edges, 0);
  EXPECT_EQ(f.wrong_boundary, 0);
  EXPECT_EQ(f.not_anticlockwise, 0);
  EXPECT_GE(f.min_angle, 20.0);  // 4:1 spacing on ring 0
  EXPECT_LE(f.max_valence, 10);
  EXPECT_NEAR(f.area_cap + f.area_island, f.area_ring, 1e-12 * f.area_ring);
}

TEST(PoleCap, TooSmallARingIsAllIsland) {
  const auto ring = uniform_ring(5, 0.0);
  const PoleCap cap = make_pole_cap(ring, 30.0, true);
  EXPECT_EQ(cap.rings, 0);
  EXPECT_TRUE(cap.triangles.empty());
  EXPECT_EQ(cap.island, (std::vector<NodeId>{4, 3, 2, 1, 0}));
}

TEST(PoleCap, RefusesBadRings) {
  EXPECT_THROW(make_pole_cap({0.0, 10.0}, 80.0, true), InternalError);
  EXPECT_THROW(make_pole_cap({0.0, 20.0, 10.0}, 80.0, true), InternalError);
  EXPECT_THROW(make_pole_cap({0.0, 120.0, 240.0}, -80.0, true), InternalError);
  EXPECT_THROW(make_pole_cap({0.0, 120.0, 360.0}, 80.0, true), InternalError);
}

}  // namespace
}  // namespace aq::mesh::unit_mesh_pole_cap_test

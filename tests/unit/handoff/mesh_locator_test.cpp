// SPDX-License-Identifier: GPL-3.0-or-later
// Point location in a real global mesh (ETOPO60, Δ0 = 4°, L = 3): every triangle's centroid is
// found in that triangle, random points agree with a brute-force search over all triangles,
// barycentric weights reproduce the points to 1e-9° and lie in [0, 1] within 1e-12, points on
// the seam, on nodes, at the North pole and in a rotated-pole mesh, and land points outside; on
// the rotated Mercator lattice, plane centroids and random points against a brute-force search in
// the (λ', Mercator y) plane, whose weights reproduce the points (and φ'-linear ones would not).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "core/types.hpp"
#include "handoff/mesh_locator.hpp"
#include "unit/handoff/global_mesh_fixture.hpp"

namespace unit_handoff_mesh_locator_test {

namespace {

using aq::handoff::MeshLocation;
using aq::handoff::MeshLocator;
using aq::mesh::Mesh;

// Lattice-plane position of a node as drawn in the triangle (seam-unwrapped).
std::array<double, 2> node_deg(const Mesh& m, const std::array<aq::NodeId, 3>& t, aq::NodeId n) {
  return {m.lattice.lon_of(m.unwrapped_i(t, n)), m.lattice.lat_of(m.node_j[static_cast<std::size_t>(n)])};
}

// Σ w_k · node_k in the lattice plane.
std::array<double, 2> reproduce(const Mesh& m, const MeshLocation& loc) {
  std::array<double, 2> p{0.0, 0.0};
  for (std::size_t q = 0; q < 3; ++q) {
    const auto d = node_deg(m, loc.nodes, loc.nodes[q]);
    p[0] += loc.weights[q] * d[0];
    p[1] += loc.weights[q] * d[1];
  }
  return p;
}

double lon_diff(double a, double b) { return std::remainder(a - b, 360.0); }

void expect_weights_ok(const MeshLocation& loc) {
  double sum = 0.0;
  for (const double w : loc.weights) {
    EXPECT_GE(w, -1e-12);
    EXPECT_LE(w, 1.0 + 1e-12);
    sum += w;
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
}

// Whether the locator found a point exactly when a brute-force search over all triangles does:
// `best` is the largest smallest weight over them (a point within 1e-9 of an edge may go either way).
::testing::AssertionResult agrees_with_brute_force(const MeshLocation& l, double best) {
  if (best >= 1e-9 && !l.inside()) return ::testing::AssertionFailure() << "inside (weight " << best << ") not found";
  if (best < -1e-9 && l.inside()) return ::testing::AssertionFailure() << "outside (weight " << best << ") found";
  return ::testing::AssertionSuccess();
}

// Smallest barycentric weight of point (lon, lat) (lattice degrees, λ near the triangle) in t.
double min_weight(const Mesh& m, std::size_t t, double lon, double lat) {
  const auto& tri = m.triangles[t];
  std::array<std::array<double, 2>, 3> v{};
  for (std::size_t q = 0; q < 3; ++q) v[q] = node_deg(m, tri, tri[q]);
  const double x = v[0][0] + lon_diff(lon, v[0][0]);  // λ brought next to the triangle
  const double det = (v[1][1] - v[2][1]) * (v[0][0] - v[2][0]) + (v[2][0] - v[1][0]) * (v[0][1] - v[2][1]);
  const double w0 = ((v[1][1] - v[2][1]) * (x - v[2][0]) + (v[2][0] - v[1][0]) * (lat - v[2][1])) / det;
  const double w1 = ((v[2][1] - v[0][1]) * (x - v[2][0]) + (v[0][0] - v[2][0]) * (lat - v[2][1])) / det;
  return std::min({w0, w1, 1.0 - w0 - w1});
}

}  // namespace

TEST(MeshLocator, EveryCentroidIsInItsTriangle) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Mesh& m = f.mesh;
  ASSERT_GT(m.triangle_count(), 10000);
  const MeshLocator loc(m);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    double lon = 0.0, lat = 0.0;
    for (const auto n : tri) {
      const auto d = node_deg(m, tri, n);
      lon += d[0] / 3.0;
      lat += d[1] / 3.0;
    }
    const MeshLocation l = loc.locate_lattice(lon, lat);
    ASSERT_EQ(l.triangle, static_cast<aq::ElementId>(t)) << "centroid (" << lon << ", " << lat << ")";
    for (const double w : l.weights) EXPECT_NEAR(w, 1.0 / 3.0, 1e-12);
  }
}

TEST(MeshLocator, AgreesWithBruteForceAndReproducesPositions) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Mesh& m = f.mesh;
  const MeshLocator loc(m);
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> ulon(-180.0, 180.0), usin(-1.0, 1.0);
  int inside = 0, outside = 0;
  for (int k = 0; k < 1500; ++k) {
    const double lon = ulon(rng), lat = std::asin(usin(rng)) * aq::kRadToDeg;
    const MeshLocation l = loc.locate_geographic(lon, lat);
    double best = -1e300;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) best = std::max(best, min_weight(m, t, lon, lat));
    ASSERT_TRUE(agrees_with_brute_force(l, best)) << lon << ", " << lat;
    if (!l.inside()) {
      ++outside;
      continue;
    }
    ++inside;
    EXPECT_GE(min_weight(m, static_cast<std::size_t>(l.triangle), lon, lat), -1e-12);
    expect_weights_ok(l);
    const auto p = reproduce(m, l);
    EXPECT_NEAR(lon_diff(p[0], lon), 0.0, 1e-9);
    EXPECT_NEAR(p[1], lat, 1e-9);
    EXPECT_NEAR(p[0], l.lattice_lon_deg, 1e-9);
  }
  // About 70% of the globe is ocean.
  EXPECT_GT(inside, 900);
  EXPECT_GT(outside, 250);
}

TEST(MeshLocator, PointsJustOutsideTheCoastHaveWeightsInZeroOne) {
  // A regional block's outline runs along lattice lines, as the coast of the mesh does; after the
  // projection's round trip its points lie up to ~1e-11° off the line, possibly just outside the
  // wet mesh. They are still located (tolerance 1e-9 in weight), with weights clamped to [0, 1].
  const auto& f = aq::testing::etopo60_mesh(false);
  const Mesh& m = f.mesh;
  const MeshLocator loc(m);
  int tested = 0;
  for (std::size_t e = 0; e < m.boundary_edges.size(); e += 7) {
    const auto [a, b] = m.boundary_edges[e];
    const auto ia = m.node_i[static_cast<std::size_t>(a)], ib = m.node_i[static_cast<std::size_t>(b)];
    if (std::abs(ia - ib) > 1 || m.lattice.lat_of(m.node_j[static_cast<std::size_t>(a)]) > 89.0) continue;
    const double x0 = m.lattice.lon_of(ia), y0 = m.lattice.lat_of(m.node_j[static_cast<std::size_t>(a)]);
    const double x1 = m.lattice.lon_of(ib), y1 = m.lattice.lat_of(m.node_j[static_cast<std::size_t>(b)]);
    const double len = std::hypot(x1 - x0, y1 - y0);
    // Wet on the left of a -> b: the outward normal is on the right, (dy, -dx).
    const double nx = (y1 - y0) / len, ny = -(x1 - x0) / len;
    for (const double t : {0.3, 0.5}) {
      const double lon = x0 + t * (x1 - x0) + 3e-11 * nx, lat = y0 + t * (y1 - y0) + 3e-11 * ny;
      const MeshLocation l = loc.locate_geographic(lon, lat);
      ASSERT_TRUE(l.inside()) << lon << ", " << lat;
      ++tested;
      for (const double w : l.weights) {
        EXPECT_GE(w, 0.0);
        EXPECT_LE(w, 1.0);
      }
      const auto p = reproduce(m, l);
      EXPECT_NEAR(lon_diff(p[0], lon), 0.0, 1e-9);
      EXPECT_NEAR(p[1], lat, 1e-9);
    }
  }
  EXPECT_GT(tested, 500);
  // Farther out (1e-5°, about 2e-5 in weight) is outside.
  const auto [a, b] = m.boundary_edges[0];
  const double x0 = m.lattice.lon_of(m.node_i[static_cast<std::size_t>(a)]);
  const double y0 = m.lattice.lat_of(m.node_j[static_cast<std::size_t>(a)]);
  const double x1 = m.lattice.lon_of(m.node_i[static_cast<std::size_t>(b)]);
  const double y1 = m.lattice.lat_of(m.node_j[static_cast<std::size_t>(b)]);
  const double len = std::hypot(x1 - x0, y1 - y0);
  EXPECT_FALSE(loc.locate_geographic(0.5 * (x0 + x1) + 1e-5 * (y1 - y0) / len, 0.5 * (y0 + y1) - 1e-5 * (x1 - x0) / len)
                   .inside());
}

TEST(MeshLocator, PointsOnTheSeam) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Mesh& m = f.mesh;
  const MeshLocator loc(m);
  for (const double lat : {-60.0, -55.3, -10.1, 30.7}) {  // the antimeridian is open ocean here
    for (const double lon : {-180.0, 180.0, 179.9999999999, -179.9999999999, 540.0}) {
      const MeshLocation l = loc.locate_geographic(lon, lat);
      ASSERT_TRUE(l.inside()) << lon << ", " << lat;
      expect_weights_ok(l);
      const auto p = reproduce(m, l);
      EXPECT_NEAR(lon_diff(p[0], lon), 0.0, 1e-9) << lon << ", " << lat;
      EXPECT_NEAR(p[1], lat, 1e-9);
    }
    // East of the seam in the first column and west of it in the last: the elements differ,
    // both drawn without a jump of 360°.
    const MeshLocation e = loc.locate_geographic(-179.99, lat), w = loc.locate_geographic(179.99, lat);
    ASSERT_TRUE(e.inside() && w.inside());
    EXPECT_NE(e.triangle, w.triangle);
    EXPECT_NEAR(reproduce(m, w)[0], 179.99, 1e-9);
    EXPECT_NEAR(reproduce(m, e)[0], -179.99, 1e-9);
  }
}

TEST(MeshLocator, NodesPoleAndLand) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Mesh& m = f.mesh;
  const MeshLocator loc(m);
  // A node: one weight is 1.
  for (std::size_t n = 0; n < m.lon_deg.size(); n += 997) {
    const MeshLocation l = loc.locate_geographic(m.lon_deg[n], m.lat_deg[n]);
    ASSERT_TRUE(l.inside());
    const double wmax = std::max({l.weights[0], l.weights[1], l.weights[2]});
    EXPECT_NEAR(wmax, 1.0, 1e-12);
    expect_weights_ok(l);
  }
  // The North pole: ETOPO60's Arctic reaches 90°N (a pole loop of the unrotated mesh).
  const MeshLocation pole = loc.locate_geographic(10.0, 90.0);
  ASSERT_TRUE(pole.inside());
  EXPECT_NEAR(reproduce(m, pole)[1], 90.0, 1e-9);
  // Land: the Sahara, the interior of Antarctica, the Tibetan plateau.
  EXPECT_FALSE(loc.locate_geographic(20.0, 22.0).inside());
  EXPECT_FALSE(loc.locate_geographic(0.0, -85.0).inside());
  EXPECT_FALSE(loc.locate_geographic(88.0, 33.0).inside());
  EXPECT_EQ(loc.locate_geographic(20.0, 22.0).triangle, -1);
}

TEST(MeshLocator, RotatedPoleMesh) {
  const auto& f = aq::testing::etopo60_mesh(true);
  const Mesh& m = f.mesh;
  ASSERT_TRUE(m.rotation.enabled);
  const MeshLocator loc(m);
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> ulon(-180.0, 180.0), usin(-1.0, 1.0);
  int inside = 0;
  for (int k = 0; k < 600; ++k) {
    const double lon = ulon(rng), lat = std::asin(usin(rng)) * aq::kRadToDeg;
    const MeshLocation l = loc.locate_geographic(lon, lat);
    double rlon = 0, rlat = 0;
    f.rotation.to_rotated(lon, lat, rlon, rlat);
    double best = -1e300;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) best = std::max(best, min_weight(m, t, rlon, rlat));
    ASSERT_TRUE(agrees_with_brute_force(l, best)) << lon << ", " << lat;
    if (!l.inside()) continue;
    ++inside;
    expect_weights_ok(l);
    // Weights reproduce the point in the lattice (rotated) plane, and so, rotated back, on the Earth.
    const auto p = reproduce(m, l);
    EXPECT_NEAR(lon_diff(p[0], rlon), 0.0, 1e-9);
    EXPECT_NEAR(p[1], rlat, 1e-9);
    double glon = 0, glat = 0;
    f.rotation.to_geographic(p[0], p[1], glon, glat);
    EXPECT_NEAR(glat, lat, 1e-9);
    if (std::abs(lat) < 89.9) {
      EXPECT_NEAR(lon_diff(glon, lon), 0.0, 1e-9);
    }
  }
  EXPECT_GT(inside, 300);
  // The geographic North pole is ocean, and not a pole of the rotated lattice.
  const MeshLocation np = loc.locate_geographic(0.0, 90.0);
  ASSERT_TRUE(np.inside());
  double glon = 0, glat = 0;
  const auto p = reproduce(m, np);
  f.rotation.to_geographic(p[0], p[1], glon, glat);
  EXPECT_NEAR(glat, 90.0, 1e-9);
}

TEST(MeshLocator, FindSquareUsesTheLeafStructure) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Mesh& m = f.mesh;
  const MeshLocator loc(m);
  // Every filled pixel is in exactly the square that covers it; unfilled pixels in none.
  std::int64_t filled = 0;
  for (std::int64_t j = 0; j < m.lattice.ny; ++j) {
    for (std::int64_t i = 0; i < m.lattice.nx; ++i) {
      const aq::ElementId s = loc.find_square(i, j);
      ASSERT_EQ(s >= 0, f.area.filled.get(i, j)) << i << ", " << j;
      if (s < 0) continue;
      ++filled;
      const auto sw = static_cast<std::size_t>(m.squares[static_cast<std::size_t>(s)][0]);
      const std::int64_t size = m.lattice.pixels_per_square(m.square_level[static_cast<std::size_t>(s)]);
      EXPECT_TRUE(i >= m.node_i[sw] && i < m.node_i[sw] + size && j >= m.node_j[sw] && j < m.node_j[sw] + size);
    }
  }
  EXPECT_EQ(filled, f.area.filled.count());
  EXPECT_EQ(loc.find_square(m.lattice.nx + 3, 100), loc.find_square(3, 100));
  EXPECT_EQ(loc.find_square(0, -1), -1);
  EXPECT_EQ(loc.find_square(0, m.lattice.ny), -1);
}

// The Mercator lattice (rotated, as configs/global_mercator.toml): rows are evenly spaced in the
// Mercator ordinate y = ln tan(π/4 + φ'/2), so an element is a flat triangle in (λ', y), not in
// (λ', φ'). The geometry here is written out from the lattice's parameters (λ0, y0, Δ_L) and the
// Mercator formulas, independently of Lattice::lat_of_row / row_of_lat.
namespace {

double merc_y_deg(double lat_deg) {
  return std::log(std::tan(M_PI / 4.0 + 0.5 * lat_deg * aq::kDegToRad)) * aq::kRadToDeg;
}
double merc_lat_deg(double y_deg) {
  return (2.0 * std::atan(std::exp(y_deg * aq::kDegToRad)) - M_PI / 2.0) * aq::kRadToDeg;
}

// (λ', y) of a node as drawn in the triangle, from its integer lattice indices.
std::array<double, 2> node_plane(const Mesh& m, const std::array<aq::NodeId, 3>& t, aq::NodeId n) {
  const double d = m.lattice.pixel_deg();
  return {m.lattice.lon0_deg + static_cast<double>(m.unwrapped_i(t, n)) * d,
          m.lattice.y0_deg + static_cast<double>(m.node_j[static_cast<std::size_t>(n)]) * d};
}

// Barycentric weights of the plane point (x, y) (λ' brought next to the triangle) in triangle t.
std::array<double, 3> plane_weights(const Mesh& m, std::size_t t, double x, double y) {
  const auto& tri = m.triangles[t];
  std::array<std::array<double, 2>, 3> v{};
  for (std::size_t q = 0; q < 3; ++q) v[q] = node_plane(m, tri, tri[q]);
  x = v[0][0] + lon_diff(x, v[0][0]);
  const double det = (v[1][1] - v[2][1]) * (v[0][0] - v[2][0]) + (v[2][0] - v[1][0]) * (v[0][1] - v[2][1]);
  const double w0 = ((v[1][1] - v[2][1]) * (x - v[2][0]) + (v[2][0] - v[1][0]) * (y - v[2][1])) / det;
  const double w1 = ((v[2][1] - v[0][1]) * (x - v[2][0]) + (v[0][0] - v[2][0]) * (y - v[2][1])) / det;
  return {w0, w1, 1.0 - w0 - w1};
}

const aq::testing::GlobalMeshFixture& mercator_mesh() {
  return aq::testing::etopo60_mesh(true, aq::LatticeKind::kMercator);
}

}  // namespace

TEST(MeshLocatorMercator, EveryPlaneCentroidIsInItsTriangleWithWeightsOneThird) {
  const auto& f = mercator_mesh();
  const Mesh& m = f.mesh;
  ASSERT_TRUE(m.lattice.mercator());
  ASSERT_GT(m.triangle_count(), 10000);
  // The lattice's rows are the Mercator ordinates of their latitudes, evenly spaced.
  for (const std::int64_t j : {std::int64_t{0}, m.lattice.ny / 3, m.lattice.ny})
    EXPECT_NEAR(merc_y_deg(m.lattice.lat_of(j)), m.lattice.y0_deg + static_cast<double>(j) * m.lattice.pixel_deg(),
                1e-9);
  const MeshLocator loc(m);
  int phi_mean_off = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    double x = 0.0, y = 0.0, phi_mean = 0.0;
    for (const auto n : tri) {
      const auto p = node_plane(m, tri, n);
      x += p[0] / 3.0;
      y += p[1] / 3.0;
      phi_mean += merc_lat_deg(p[1]) / 3.0;
    }
    const MeshLocation l = loc.locate_lattice(x, merc_lat_deg(y));
    ASSERT_EQ(l.triangle, static_cast<aq::ElementId>(t)) << "centroid (" << x << ", " << y << ")";
    for (const double w : l.weights) EXPECT_NEAR(w, 1.0 / 3.0, 1e-10);
    expect_weights_ok(l);
    // The mean of the nodes' φ' is another point: a locator interpolating φ' linearly would take it.
    const MeshLocation p = loc.locate_lattice(x, phi_mean);
    if (p.inside() && std::abs(p.weights[0] - 1.0 / 3.0) + std::abs(p.weights[1] - 1.0 / 3.0) > 1e-6) ++phi_mean_off;
  }
  EXPECT_GT(phi_mean_off, static_cast<int>(m.triangles.size()) / 2);
}

TEST(MeshLocatorMercator, RandomPointsAgreeWithBruteForceInTheMercatorPlane) {
  const auto& f = mercator_mesh();
  const Mesh& m = f.mesh;
  ASSERT_TRUE(m.rotation.enabled);
  const MeshLocator loc(m);
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> ulon(-180.0, 180.0), usin(-1.0, 1.0);
  int inside = 0, outside = 0, phi_linear_off = 0;
  for (int k = 0; k < 800; ++k) {
    const double lon = ulon(rng), lat = std::asin(usin(rng)) * aq::kRadToDeg;
    const MeshLocation l = loc.locate_geographic(lon, lat);
    double rlon = 0, rlat = 0;
    f.rotation.to_rotated(lon, lat, rlon, rlat);
    const double y = merc_y_deg(rlat);
    double best = -1e300;
    std::size_t best_t = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const auto w = plane_weights(m, t, rlon, y);
      const double mw = std::min({w[0], w[1], w[2]});
      if (mw > best) {
        best = mw;
        best_t = t;
      }
    }
    ASSERT_TRUE(agrees_with_brute_force(l, best)) << lon << ", " << lat;
    if (best >= 1e-9) {
      EXPECT_EQ(l.triangle, static_cast<aq::ElementId>(best_t));
    }
    if (!l.inside()) {
      ++outside;
      continue;
    }
    ++inside;
    expect_weights_ok(l);
    const auto bw = plane_weights(m, static_cast<std::size_t>(l.triangle), rlon, y);
    for (std::size_t q = 0; q < 3; ++q) EXPECT_NEAR(l.weights[q], bw[q], 1e-9);
    // The weights reproduce (λ', y); y gives φ' and, rotated back, the geographic point.
    double px = 0.0, py = 0.0, phi_linear = 0.0;
    for (std::size_t q = 0; q < 3; ++q) {
      const auto p = node_plane(m, l.nodes, l.nodes[q]);
      px += l.weights[q] * p[0];
      py += l.weights[q] * p[1];
      phi_linear += l.weights[q] * merc_lat_deg(p[1]);
    }
    EXPECT_NEAR(lon_diff(px, rlon), 0.0, 1e-9);
    EXPECT_NEAR(py, y, 1e-9);
    double glon = 0, glat = 0;
    f.rotation.to_geographic(px, merc_lat_deg(py), glon, glat);
    EXPECT_NEAR(glat, lat, 1e-9);
    if (std::abs(lat) < 89.9) {
      EXPECT_NEAR(lon_diff(glon, lon), 0.0, 1e-9);
    }
    if (std::abs(phi_linear - rlat) > 1e-6) ++phi_linear_off;  // φ' is not linear in an element
  }
  EXPECT_GT(inside, 400);
  EXPECT_GT(outside, 150);
  EXPECT_GT(phi_linear_off, inside / 2);
}

}  // namespace unit_handoff_mesh_locator_test

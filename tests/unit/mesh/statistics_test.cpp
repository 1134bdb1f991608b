// Mesh statistics (statistics.hpp): exact areas on WGS84, memoised sizes equal direct
// GeographicLib computations, and every check fails on a deliberately broken mesh.
#include "mesh/statistics.hpp"

#include <gtest/gtest.h>
#include <GeographicLib/Ellipsoid.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <algorithm>

#include "quadtree/bits.hpp"
#include "unit/mesh/mesh_fixtures.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::mesh {
namespace {

using testing::build_all;
using testing::make_lattice;
using testing::random_mask;

Mesh small_mesh(std::uint32_t seed = 3u) {
  const Lattice lat = make_lattice(45.0, 3);
  const Bitmap m = random_mask(lat.nx, lat.ny, seed, 0.6, 0.01, 8);
  return build_all(m, lat, {}, {}, PoleRotation(), testing::synthetic_bathymetry()).mesh;
}

TEST(Statistics, FullGlobeFilledAreaIsTheEllipsoidArea) {
  const Lattice lat = make_lattice(45.0, 2);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j) quadtree::bits::set_range(m.row(j), 0, lat.nx);
  const Mesh mesh = build_all(m, lat, {}, {}, PoleRotation(), testing::synthetic_bathymetry()).mesh;
  const MeshStatistics s = compute_statistics(mesh);
  EXPECT_NEAR(s.filled_area_km2 / (GeographicLib::Ellipsoid::WGS84().Area() * 1e-6), 1.0, 1e-12);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.boundary_loops, 2);  // the two pole lines
  EXPECT_EQ(s.euler, 0);           // a cylinder (annulus)
  EXPECT_EQ(s.euler, s.euler_expected);
}

TEST(Statistics, MemoisedSizesEqualDirectComputation) {
  const Mesh mesh = small_mesh();
  const MeshStatistics s = compute_statistics(mesh);
  ASSERT_TRUE(s.failed_checks().empty());
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  double total = 0.0;
  for (const LevelStatistics& ls : s.levels) {
    std::vector<double> areas, lengths;
    for (std::int64_t t = 0; t < mesh.triangle_count(); ++t) {
      if (mesh.triangle_level[static_cast<std::size_t>(t)] != ls.level) continue;
      GeographicLib::PolygonArea poly(g);
      for (const NodeId v : mesh.triangles[static_cast<std::size_t>(t)]) {
        poly.AddPoint(mesh.lat_deg[static_cast<std::size_t>(v)], mesh.lon_deg[static_cast<std::size_t>(v)]);
      }
      double perimeter = 0, area = 0;
      poly.Compute(false, true, perimeter, area);
      areas.push_back(area);
      total += area;
    }
    std::sort(areas.begin(), areas.end());
    ASSERT_EQ(static_cast<std::int64_t>(areas.size()), ls.triangles);
    EXPECT_NEAR(ls.area_min_m2, areas.front(), 1e-6 * areas.back());
    EXPECT_NEAR(ls.area_max_m2, areas.back(), 1e-6 * areas.back());
    EXPECT_NEAR(ls.area_median_m2, areas[(areas.size() - 1) / 2], 1e-6 * areas.back());
    EXPECT_GT(ls.edge_max_m, ls.edge_min_m);
  }
  EXPECT_NEAR(s.triangle_area_km2, total * 1e-6, 1e-6 * s.triangle_area_km2);
  EXPECT_LT(s.area_relative_difference, s.area_tolerance);
}

TEST(Statistics, SimilarityClassesFollowTheLevels) {
  const Mesh mesh = small_mesh(5u);
  const MeshStatistics s = compute_statistics(mesh, StatisticsOptions{false, 0.0});
  std::int64_t sum = 0;
  for (const std::int64_t c : s.similarity) sum += c;
  EXPECT_EQ(sum, s.triangles);
  // Level-l squares give k = 2l (two-triangle template), 2l+1 and 2l+2 (centre templates).
  std::vector<std::int64_t> expect(s.similarity.size(), 0);
  for (std::size_t q = 0; q < mesh.squares.size(); ++q) {
    const int l = mesh.square_level[q];
    int code = 0;
    for (int side = 0; side < 4; ++side) code |= (mesh.square_midside[q][static_cast<std::size_t>(side)] >= 0) << side;
    if (code == 0) {
      expect[static_cast<std::size_t>(2 * l)] += 2;
    } else {
      const int k = std::popcount(static_cast<unsigned>(code));
      expect[static_cast<std::size_t>(2 * l + 1)] += 4 - k;
      expect[static_cast<std::size_t>(2 * l + 2)] += 2 * k;
    }
  }
  EXPECT_EQ(s.similarity, expect);
}

TEST(Statistics, ChecksFailOnBrokenMeshes) {
  const Mesh good = small_mesh();
  ASSERT_TRUE(compute_statistics(good, StatisticsOptions{false, 0.0}).failed_checks().empty());
  {
    Mesh m = good;  // a flipped triangle
    std::swap(m.triangles[10][1], m.triangles[10][2]);
    const MeshStatistics s = compute_statistics(m, StatisticsOptions{false, 0.0});
    EXPECT_EQ(s.clockwise, 1);
    EXPECT_GT(s.bad_edges, 0);
    EXPECT_FALSE(s.failed_checks().empty());
  }
  {
    Mesh m = good;  // a missing triangle: a hole
    m.triangles.pop_back();
    m.triangle_level.pop_back();
    m.triangle_square.pop_back();
    const MeshStatistics s = compute_statistics(m, StatisticsOptions{false, 0.0});
    EXPECT_GT(s.boundary_mismatch, 0);
    EXPECT_NE(s.twice_triangle_area_px2, 2 * s.filled_pixels);
    EXPECT_FALSE(s.failed_checks().empty());
  }
  {
    Mesh m = good;  // a duplicated triangle
    m.triangles.push_back(m.triangles[0]);
    m.triangle_level.push_back(m.triangle_level[0]);
    m.triangle_square.push_back(m.triangle_square[0]);
    const MeshStatistics s = compute_statistics(m, StatisticsOptions{false, 0.0});
    EXPECT_GT(s.bad_edges, 0);
    EXPECT_FALSE(s.failed_checks().empty());
  }
  {
    Mesh m = good;  // a boundary edge listed the wrong way round
    std::swap(m.boundary_edges[0][0], m.boundary_edges[0][1]);
    const MeshStatistics s = compute_statistics(m, StatisticsOptions{false, 0.0});
    EXPECT_EQ(s.boundary_mismatch, 2);
    EXPECT_FALSE(s.failed_checks().empty());
  }
  {
    Mesh m = good;  // a loop too many for Euler
    m.loops.push_back(m.loops.front());
    const MeshStatistics s = compute_statistics(m, StatisticsOptions{false, 0.0});
    EXPECT_NE(s.euler, s.euler_expected);
    EXPECT_FALSE(s.failed_checks().empty());
  }
}

TEST(Statistics, ReportSection) {
  const MeshStatistics s = compute_statistics(small_mesh());
  const Json j = statistics_json(s);
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_EQ(j["triangles"].get<std::int64_t>(), s.triangles);
  EXPECT_GT(j["total_wet_area_km2"].get<double>(), 0.0);
  EXPECT_EQ(j["levels"].size(), s.levels.size());
  EXPECT_EQ(j["right_isosceles"]["min_angle_deg"].get<double>(), 45.0);
}

}  // namespace
}  // namespace aq::mesh

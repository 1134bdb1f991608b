// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh statistics (statistics.hpp): exact areas on WGS84, memoised sizes equal direct
// GeographicLib computations, and every check fails on a deliberately broken mesh.
#include "mesh/statistics.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <GeographicLib/Ellipsoid.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"
#include "quadtree/bits.hpp"
#include "quadtree/parallel.hpp"
#include "support/omp_threads.hpp"
#include "unit/mesh/mesh_fixtures.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::mesh::unit_mesh_statistics_test {
namespace {

using testing::build_all;
using testing::make_lattice;
using testing::random_mask;

Mesh small_mesh(std::uint32_t seed = 3u) {
  const Lattice lat = make_lattice(45.0, 3);
  const Bitmap m = random_mask(lat.nx, lat.ny, seed, 0.6, 0.01, 8);
  return build_all(m, lat, {}, {}, PoleRotation(), testing::synthetic_bathymetry()).mesh;
}

// The per-level statistics of a run without rotation come from the memo tables' cells with their
// counts: the same min, median and max, bit for bit, as the values written out and selected.
TEST(Statistics, WeightedMinMedianMaxIsThatOfTheValuesWrittenOut) {
  std::mt19937_64 rng(21);
  std::uniform_int_distribution<int> count(1, 5), distinct(1, 300);
  std::uniform_real_distribution<double> value(0.0, 1e9);
  for (int round = 0; round < 200; ++round) {
    std::vector<std::pair<double, std::int64_t>> pairs;
    std::vector<double> written;
    const int n = round == 0 ? 1 : distinct(rng);
    for (int k = 0; k < n; ++k) {
      const double v = k == 0 && round % 3 == 0 ? 0.0 : value(rng);  // +0: the pole row's areas
      const int c = count(rng);
      pairs.emplace_back(v, c);
      written.insert(written.end(), static_cast<std::size_t>(c), v);
      if (round % 2 == 0) pairs.emplace_back(v, 1);  // a value both in a cell and on its own
      if (round % 2 == 0) written.push_back(v);
    }
    std::shuffle(pairs.begin(), pairs.end(), rng);
    std::shuffle(written.begin(), written.end(), rng);
    std::int64_t size = -1;
    const auto got = weighted_min_median_max(pairs, size);
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(size, static_cast<std::int64_t>(written.size()));
    const auto want = min_median_max(written);
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_EQ(std::bit_cast<std::uint64_t>((*got)[k]), std::bit_cast<std::uint64_t>(want[k])) << round << " " << k;
  }
  std::vector<std::pair<double, std::int64_t>> none;
  std::int64_t size = -1;
  EXPECT_EQ(weighted_min_median_max(none, size), (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(size, 0);
  for (const double bad :
       {-0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::vector<std::pair<double, std::int64_t>> v{{1.0, 2}, {bad, 1}, {3.0, 1}};
    EXPECT_FALSE(weighted_min_median_max(v, size).has_value()) << bad;
  }
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

// GeographicLib's area (PolygonArea) of every triangle of `level`, sorted; adds them to `total`.
std::vector<double> geodesic_areas(const Mesh& mesh, int level, double& total) {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  std::vector<double> areas;
  for (std::int64_t t = 0; t < mesh.triangle_count(); ++t) {
    if (mesh.triangle_level[static_cast<std::size_t>(t)] != level) continue;
    GeographicLib::PolygonArea poly(g);
    for (const NodeId v : mesh.triangles[static_cast<std::size_t>(t)])
      poly.AddPoint(mesh.lat_deg[static_cast<std::size_t>(v)], mesh.lon_deg[static_cast<std::size_t>(v)]);
    double perimeter = 0, area = 0;
    poly.Compute(false, true, perimeter, area);
    areas.push_back(area);
    total += area;
  }
  std::sort(areas.begin(), areas.end());
  return areas;
}

TEST(Statistics, MemoisedSizesEqualDirectComputation) {
  const Mesh mesh = small_mesh();
  const MeshStatistics s = compute_statistics(mesh);
  ASSERT_TRUE(s.failed_checks().empty());
  double total = 0.0;
  for (const LevelStatistics& ls : s.levels) {
    const std::vector<double> areas = geodesic_areas(mesh, ls.level, total);
    ASSERT_EQ(static_cast<std::int64_t>(areas.size()), ls.triangles);
    EXPECT_NEAR(ls.area_min_m2, areas.front(), 1e-6 * areas.back());
    EXPECT_NEAR(ls.area_max_m2, areas.back(), 1e-6 * areas.back());
    EXPECT_NEAR(ls.area_median_m2, areas[(areas.size() - 1) / 2], 1e-6 * areas.back());
    EXPECT_GT(ls.edge_max_m, ls.edge_min_m);
  }
  EXPECT_NEAR(s.triangle_area_km2, total * 1e-6, 1e-6 * s.triangle_area_km2);
  EXPECT_LT(s.area_relative_difference, s.area_tolerance);
}

// On a fine rotated lattice (3.75' pixels) the interior edges shorter than 45 km take closed forms
// (authalic-sphere S12, chord length with the normal-section curvature) instead of geodesics.
// Measured against GeographicLib on every triangle and edge: the total area equals PolygonArea's
// sum (the interior terms cancel; the boundary edges are geodesics), the smallest, median and
// largest triangle areas of every level are within 3e-6 of the geodesic ones, and the edge lengths
// within 1e-9. Water boxes at the geographic
// equator, next to the geographic North pole and across the antimeridian.
TEST(Statistics, ShortInteriorEdgesOfFineRotatedMeshesMatchGeodesics) {
  const Lattice lat = make_lattice(1.0, 4);  // 1° squares down to 3.75'
  const PoleRotation greenland(-44.858333, 78.141667);
  Bitmap m(lat.nx, lat.ny);
  for (const auto& [lon, la] : {std::pair{0.0, 0.0}, std::pair{20.0, 75.0}, std::pair{178.0, -20.0}}) {
    double rlon = 0.0, rlat = 0.0;
    greenland.to_rotated(lon, la, rlon, rlat);
    const auto i0 = static_cast<std::int64_t>((rlon - lat.lon0_deg) / lat.pixel_deg());
    const auto j0 = static_cast<std::int64_t>((rlat + 90.0) / lat.pixel_deg());
    for (std::int64_t j = j0 - 80; j < j0 + 80; ++j)
      for (std::int64_t i = i0 - 80; i < i0 + 80; ++i)
        if (std::sin(0.11 * static_cast<double>(i)) + std::cos(0.07 * static_cast<double>(j)) > -1.2)
          m.set(wrap_index(i, lat.nx), j);
  }
  Mesh mesh = build_all(m, lat, {}, {}, greenland, testing::synthetic_bathymetry()).mesh;
  mesh.rotation.enabled = true;
  mesh.rotation.pole_lon_deg = -44.858333;
  mesh.rotation.pole_lat_deg = 78.141667;
  const MeshStatistics s = compute_statistics(mesh);
  ASSERT_TRUE(s.failed_checks().empty());
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  double total = 0.0;
  std::int64_t checked_levels = 0;
  for (const LevelStatistics& ls : s.levels) {
    if (ls.triangles == 0) continue;
    const std::vector<double> areas = geodesic_areas(mesh, ls.level, total);
    ASSERT_EQ(static_cast<std::int64_t>(areas.size()), ls.triangles);
    EXPECT_NEAR(ls.area_min_m2, areas.front(), 3e-6 * areas.front()) << "level " << ls.level;
    EXPECT_NEAR(ls.area_max_m2, areas.back(), 3e-6 * areas.back()) << "level " << ls.level;
    EXPECT_NEAR(ls.area_median_m2, areas[(areas.size() - 1) / 2], 3e-6 * areas.back()) << "level " << ls.level;
    ++checked_levels;
  }
  EXPECT_GE(checked_levels, 4);
  EXPECT_NEAR(s.triangle_area_km2, total * 1e-6, 1e-10 * total * 1e-6);
  // Edge lengths per level (an edge's level: the finest of its triangles) against geodesics.
  std::map<std::pair<NodeId, NodeId>, int> edge_level;
  for (std::int64_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tr = mesh.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) {
      const NodeId a = tr[static_cast<std::size_t>(k)], b = tr[static_cast<std::size_t>((k + 1) % 3)];
      int& l = edge_level[{std::min(a, b), std::max(a, b)}];
      l = std::max(l, static_cast<int>(mesh.triangle_level[static_cast<std::size_t>(t)]));
    }
  }
  std::vector<std::vector<double>> lengths(s.levels.size() + 8);
  for (const auto& [e, l] : edge_level) {
    const auto a = static_cast<std::size_t>(e.first), b = static_cast<std::size_t>(e.second);
    double s12 = 0.0;
    g.Inverse(mesh.lat_deg[a], mesh.lon_deg[a], mesh.lat_deg[b], mesh.lon_deg[b], s12);
    lengths[static_cast<std::size_t>(l)].push_back(s12);
  }
  double len_min = 1e300;
  for (const LevelStatistics& ls : s.levels) {
    auto& v = lengths[static_cast<std::size_t>(ls.level)];
    if (v.empty()) continue;
    std::sort(v.begin(), v.end());
    ASSERT_EQ(static_cast<std::int64_t>(v.size()), ls.edges) << "level " << ls.level;
    EXPECT_NEAR(ls.edge_min_m, v.front(), 1e-9 * v.front()) << "level " << ls.level;
    EXPECT_NEAR(ls.edge_median_m, v[(v.size() - 1) / 2], 1e-9 * v.back()) << "level " << ls.level;
    EXPECT_NEAR(ls.edge_max_m, v.back(), 1e-9 * v.back()) << "level " << ls.level;
    len_min = std::min(len_min, v.front());
  }
  EXPECT_LT(len_min, 8000.0);  // the finest edges are in the closed-form range
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

// Issue 11: with the lattice's last row beyond the pole (Δ0 kept as typed, 0.2666666666666667, as
// Lattice::make used to do) the pole row's cell area is NaN; the area check compared NaN and
// passed ("all checks passed; wet area nan"). Every non-finite value now fails, naming where.
TEST(Statistics, ANonFiniteAreaFailsAndSaysWhere) {
  Lattice lat = make_lattice(0.26666666666666666, 0);
  lat.step0_deg = 0.2666666666666667;  // the old lattice: lat_of(ny) = 90.00000000000003
  ASSERT_GT(lat.lat_of(lat.ny), 90.0);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = lat.ny - 2; j < lat.ny; ++j) quadtree::bits::set_range(m.row(j), 0, lat.nx);
  const Mesh mesh = build_all(m, lat, {}, {}, PoleRotation(), testing::synthetic_bathymetry()).mesh;
  const MeshStatistics s = compute_statistics(mesh);
  const auto failed = s.failed_checks();
  ASSERT_FALSE(failed.empty());
  EXPECT_NE(failed.front().find("lattice row sine of latitude (cell areas) is nan at lattice row J = 675"),
            std::string::npos)
      << failed.front();
  EXPECT_FALSE(statistics_json(s)["ok"].get<bool>());
  {
    Mesh broken = small_mesh();  // a NaN node latitude
    broken.lat_deg[7] = std::nan("");
    const auto f = compute_statistics(broken).failed_checks();
    ASSERT_FALSE(f.empty());
    EXPECT_NE(f.front().find("node latitude is nan at node 7 (lattice I = "), std::string::npos) << f.front();
  }
  {
    // With rotation the areas and lengths come from the nodes' λ, φ: the NaN spreads to the areas
    // of the node's triangles and the lengths of its edges, each quantity reported once, at the
    // first triangle / edge (whether there is one is checked in parallel).
    const Lattice lattice = make_lattice(45.0, 3);
    const Bitmap mask = random_mask(lattice.nx, lattice.ny, 3u, 0.6, 0.01, 8);
    const PoleRotation greenland(-44.858333, 78.141667);
    Mesh broken = build_all(mask, lattice, {}, {}, greenland, testing::synthetic_bathymetry()).mesh;
    broken.rotation.enabled = true;
    broken.rotation.pole_lon_deg = -44.858333;
    broken.rotation.pole_lat_deg = 78.141667;
    ASSERT_TRUE(compute_statistics(broken).failed_checks().empty());
    const NodeId v = broken.triangles[40][1];
    broken.lat_deg[static_cast<std::size_t>(v)] = std::nan("");
    const auto f = compute_statistics(broken).failed_checks();
    // A failure that starts with `quantity` and says NaN (printed "nan" or "-nan") at `where`.
    const auto has = [&](const std::string& quantity, const std::string& where) {
      return std::any_of(f.begin(), f.end(), [&](const std::string& x) {
        return x.rfind(quantity + " is ", 0) == 0 && x.find("nan at " + where) != std::string::npos;
      });
    };
    EXPECT_TRUE(has("node latitude", fmt::format("node {} ", v))) << ::testing::PrintToString(f);
    EXPECT_TRUE(has("geodesic triangle area (m²)", "triangle ")) << ::testing::PrintToString(f);
    EXPECT_TRUE(has("geodesic edge length (m)", "edge ")) << ::testing::PrintToString(f);
    EXPECT_TRUE(has("total triangle area (km²)", "the sum over all triangles")) << ::testing::PrintToString(f);
  }
  {
    Mesh broken = small_mesh();  // a NaN depth
    broken.depth_m[3] = std::nan("");
    const auto f = compute_statistics(broken, StatisticsOptions{false, 0.0}).failed_checks();
    ASSERT_EQ(f.size(), 1U);
    EXPECT_NE(f.front().find("node depth is nan at node 3"), std::string::npos) << f.front();
  }
}

// With rotation each edge's geodesic is solved once and an element's area is the sum of its edges'
// ±S12 (reduced like PolygonArea): on the full globe in the Greenland frame (the triangles around
// the geographic poles count their prime-meridian crossings, others cross the antimeridian) every
// triangle's area equals PolygonArea's and the triangles tile the ellipsoid.
TEST(Statistics, RotatedPerEdgeAreasEqualPolygonArea) {
  const Lattice lat = make_lattice(45.0, 2);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j) quadtree::bits::set_range(m.row(j), 0, lat.nx);
  const PoleRotation greenland(-44.858333, 78.141667);
  Mesh mesh = build_all(m, lat, {}, {}, greenland, testing::synthetic_bathymetry()).mesh;
  mesh.rotation.enabled = true;
  mesh.rotation.pole_lon_deg = -44.858333;
  mesh.rotation.pole_lat_deg = 78.141667;
  const MeshStatistics s = compute_statistics(mesh);
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  double total = 0.0, largest = 0.0, smallest = 0.0;
  for (std::int64_t t = 0; t < mesh.triangle_count(); ++t) {
    GeographicLib::PolygonArea poly(g);
    for (const NodeId v : mesh.triangles[static_cast<std::size_t>(t)])
      poly.AddPoint(mesh.lat_deg[static_cast<std::size_t>(v)], mesh.lon_deg[static_cast<std::size_t>(v)]);
    double perimeter = 0, area = 0;
    poly.Compute(false, true, perimeter, area);
    smallest = std::min(smallest, area);
    total += area;
    largest = std::max(largest, area);
  }
  EXPECT_NEAR(s.triangle_area_km2, total * 1e-6, 1e-12 * total * 1e-6);
  EXPECT_NEAR(s.triangle_area_km2 / (GeographicLib::Ellipsoid::WGS84().Area() * 1e-6), 1.0, 1e-12);
  double level_min = largest, level_max = 0.0;
  for (const LevelStatistics& ls : s.levels) {
    if (ls.triangles == 0) continue;
    level_min = std::min(level_min, ls.area_min_m2);
    level_max = std::max(level_max, ls.area_max_m2);
  }
  EXPECT_NEAR(level_min, smallest, 1e-9 * largest);  // ~0: triangles with two vertices at a rotated pole
  EXPECT_NEAR(level_max, largest, 1e-12 * largest);
}

// The area tolerance bounds the lenses between boundary geodesics and lattice parallels: it
// shrinks like the pixel size squared, and the difference stays below it, with and without
// rotation (the rotated cells are integrated on the ellipsoid, not on the authalic sphere).
TEST(Statistics, AreaToleranceFollowsTheErrorModel) {
  const PoleRotation greenland(-44.858333, 78.141667);
  for (const bool rotated : {false, true}) {
    double previous = 0.0;
    for (const int levels : {1, 2, 3}) {
      const Lattice lat = make_lattice(5.0, levels);
      // The same set at every resolution: a band 15°S..30°N, 0..90°E and a polar cap 75..90°N.
      Bitmap m(lat.nx, lat.ny);
      const std::int64_t p = std::int64_t{1} << levels;  // pixels per 5°
      for (std::int64_t j = 15 * p; j < 24 * p; ++j) quadtree::bits::set_range(m.row(j), 36 * p, 54 * p);
      for (std::int64_t j = 33 * p; j < lat.ny; ++j) quadtree::bits::set_range(m.row(j), 0, lat.nx);
      Mesh mesh = build_all(m, lat, {}, {}, rotated ? greenland : PoleRotation(), testing::synthetic_bathymetry()).mesh;
      if (rotated) {
        mesh.rotation.enabled = true;
        mesh.rotation.pole_lon_deg = -44.858333;
        mesh.rotation.pole_lat_deg = 78.141667;
      }
      const MeshStatistics s = compute_statistics(mesh);
      EXPECT_TRUE(s.failed_checks().empty()) << rotated << " L = " << levels << ": " << s.failed_checks().front();
      EXPECT_LE(s.area_relative_difference, s.area_tolerance);
      if (previous > 0.0) {
        EXPECT_NEAR(s.area_tolerance / previous, 0.25, 0.1) << rotated << " L = " << levels;
      }
      previous = s.area_tolerance;
    }
  }
}

// With rotation a lattice cell's area is a 3×3 Gauss–Legendre quadrature of the ellipsoid's area
// density in (λ', sin φ'); compute_statistics tables the nodes' cos/sin λ' and sin/cos φ' per level.
// Here every square is integrated on its own, the geographic latitude of each node from
// PoleRotation::to_geographic: the totals agree to rounding, on a Mercator and a lon-lat lattice.
TEST(Statistics, RotatedCellAreasAreTheirGaussLegendreQuadratures) {
  const PoleRotation greenland(-44.858333, 78.141667);
  const GeographicLib::Ellipsoid& ell = GeographicLib::Ellipsoid::WGS84();
  const double a = ell.EquatorialRadius(), e2 = ell.EccentricitySq(), deg = std::acos(-1.0) / 180.0;
  for (const bool mercator : {false, true}) {
    const Lattice lat = mercator ? Lattice::make_mercator(10.0, 3, -180.0, 80.0) : make_lattice(10.0, 3);
    const Bitmap m = random_mask(lat.nx, lat.ny, 9u, 0.6, 0.02, 6);
    Mesh mesh = build_all(m, lat, {}, {}, greenland, testing::synthetic_bathymetry()).mesh;
    mesh.rotation.enabled = true;
    mesh.rotation.pole_lon_deg = -44.858333;
    mesh.rotation.pole_lat_deg = 78.141667;
    const MeshStatistics s = compute_statistics(mesh);
    const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double total_m2 = 0.0;
    std::int64_t levels_seen = 0;
    for (std::size_t q = 0; q < mesh.squares.size(); ++q) {
      const std::int64_t side = lat.pixels_per_square(mesh.square_level[q]);
      levels_seen |= std::int64_t{1} << mesh.square_level[q];
      const auto sw = static_cast<std::size_t>(mesh.squares[q][0]);
      const double i0 = static_cast<double>(mesh.node_i[sw]);
      const double s0 = std::sin(lat.lat_of(mesh.node_j[sw]) * deg);
      const double s1 = std::sin(lat.lat_of(mesh.node_j[sw] + side) * deg);
      double sum = 0.0;
      for (int u = 0; u < 3; ++u) {
        for (int v = 0; v < 3; ++v) {
          const double rlon = lat.lon0_deg + (i0 + 0.5 * static_cast<double>(side) * (1.0 + g[u])) * lat.pixel_deg();
          const double rlat = std::asin(0.5 * (s0 + s1) + 0.5 * (s1 - s0) * g[v]) / deg;
          double lon = 0.0, la = 0.0;
          greenland.to_geographic(rlon, rlat, lon, la);
          const double d = 1.0 - e2 * std::sin(la * deg) * std::sin(la * deg);
          sum += w[u] * w[v] * a * a * (1.0 - e2) / (d * d);
        }
      }
      total_m2 += sum * 0.25 * static_cast<double>(side) * lat.pixel_deg() * deg * (s1 - s0);
    }
    EXPECT_GE(std::popcount(static_cast<std::uint64_t>(levels_seen)), 3) << mercator;
    EXPECT_NEAR(s.filled_area_km2 / (total_m2 * 1e-6), 1.0, 1e-12) << mercator;
  }
}

// Found by the sweep: `mesh.elements = "squares"` always failed the checks ("nodes are in no
// triangle", "triangle area 0 px²"). A squares-only mesh is now checked on its squares.
TEST(Statistics, SquaresOnlyMeshIsCheckedOnItsSquares) {
  const PoleRotation greenland(-44.858333, 78.141667);
  for (const bool rotated : {false, true}) {
    const Lattice lat = make_lattice(45.0, 4);
    const Bitmap m = random_mask(lat.nx, lat.ny, 5u, 0.6, 0.01, 8);
    config::MeshOptions squares, triangles;
    squares.elements = config::ElementKinds::kSquares;
    const PoleRotation rot = rotated ? greenland : PoleRotation();
    const Mesh sq = build_all(m, lat, {}, squares, rot, testing::synthetic_bathymetry()).mesh;
    const Mesh tr = build_all(m, lat, {}, triangles, rot, testing::synthetic_bathymetry()).mesh;
    ASSERT_TRUE(sq.triangles.empty());
    const MeshStatistics s = compute_statistics(sq), t = compute_statistics(tr);
    EXPECT_TRUE(s.failed_checks().empty()) << s.failed_checks().front();
    EXPECT_EQ(s.used_nodes, s.nodes);
    EXPECT_EQ(s.euler, s.euler_expected);
    EXPECT_EQ(s.components, t.components);
    EXPECT_EQ(s.boundary_edges, t.boundary_edges);
    EXPECT_EQ(s.twice_triangle_area_px2, 2 * s.filled_pixels);
    EXPECT_EQ(s.filled_area_km2, t.filled_area_km2);
    EXPECT_NEAR(s.triangle_area_km2 / t.triangle_area_km2, 1.0, 1e-9);  // the same geodesic boundary
    Mesh broken = sq;                                                   // a square turned clockwise
    std::swap(broken.squares[4][1], broken.squares[4][3]);
    std::swap(broken.square_midside[4][0], broken.square_midside[4][3]);
    std::swap(broken.square_midside[4][1], broken.square_midside[4][2]);
    EXPECT_FALSE(compute_statistics(broken).failed_checks().empty());
  }
}

// The faces joined across interior edges, counted here by a plain serial union–find over an ordered
// map of the edges (compute_statistics joins them concurrently while it walks the edge buckets).
std::int64_t edge_connected_pieces(const Mesh& mesh) {
  std::vector<std::int64_t> parent(static_cast<std::size_t>(mesh.triangle_count()));
  for (std::size_t t = 0; t < parent.size(); ++t) parent[t] = static_cast<std::int64_t>(t);
  const auto root = [&](std::int64_t x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)];
    return x;
  };
  std::map<std::pair<NodeId, NodeId>, std::vector<std::int64_t>> faces;
  for (std::int64_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tr = mesh.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) {
      const NodeId a = tr[static_cast<std::size_t>(k)], b = tr[static_cast<std::size_t>((k + 1) % 3)];
      faces[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  }
  for (const auto& [edge, f] : faces)
    if (f.size() == 2) parent[static_cast<std::size_t>(root(f[0]))] = root(f[1]);
  std::int64_t pieces = 0;
  for (std::size_t t = 0; t < parent.size(); ++t)
    pieces += root(static_cast<std::int64_t>(t)) == static_cast<std::int64_t>(t);
  return pieces;
}

// Many separate basins: the component count equals the independent count above, with one thread
// and with two (the mesh is large enough for the edge walk to run in parallel).
TEST(Statistics, ComponentsAreTheEdgeConnectedPiecesForAnyThreadCount) {
  const Lattice lat = make_lattice(10.0, 4);  // 576 × 288 pixels
  const Bitmap m = random_mask(lat.nx, lat.ny, 11u, 0.3, 0.02, 5);
  const Mesh mesh = build_all(m, lat, {}, {}, PoleRotation(), testing::synthetic_bathymetry()).mesh;
  ASSERT_GE(mesh.node_count() * 16, quadtree::kParallelMinWork);
  const std::int64_t want = edge_connected_pieces(mesh);
  ASSERT_GT(want, 20);
  for (const int threads : {1, 2}) {
    const MeshStatistics s = [&] {
      const testing::ThreadCount use(threads);
      return compute_statistics(mesh, StatisticsOptions{false, 0.0});
    }();
    EXPECT_EQ(s.components, want) << threads << " threads";
    EXPECT_EQ(s.euler, s.euler_expected) << threads << " threads";
  }
}

// Node and square ids are checked before anything else, in parallel: the error names the first bad
// id in triangle order, for one thread and for two.
TEST(Statistics, OutOfRangeIdsThrowNamingTheFirstOne) {
  const Lattice lat = make_lattice(5.0, 4);
  const Bitmap m = random_mask(lat.nx, lat.ny, 7u, 0.6, 0.01, 8);
  const Mesh good = build_all(m, lat, {}, {}, PoleRotation(), testing::synthetic_bathymetry()).mesh;
  ASSERT_GE(good.triangle_count(), quadtree::kParallelMinWork);  // the searches run on two threads
  Mesh bad_node = good, bad_square = good;
  const auto last = static_cast<std::size_t>(good.triangle_count() - 1);
  bad_node.triangles[last][1] = good.node_count() + 7;  // in the second thread's half
  bad_node.triangles[last / 3][2] = -5;                 // the first in triangle order
  bad_square.triangle_square[last] = -1;
  bad_square.triangle_square[last / 2] = good.square_count();
  for (const int threads : {1, 2}) {
    const testing::ThreadCount use(threads);
    try {
      (void)compute_statistics(bad_node);
      ADD_FAILURE() << "no error for a node id out of range";
    } catch (const InternalError& e) {
      EXPECT_STREQ(e.what(), "mesh statistics: node id -5 out of range") << threads << " threads";
    }
    try {
      (void)compute_statistics(bad_square);
      ADD_FAILURE() << "no error for a square id out of range";
    } catch (const InternalError& e) {
      EXPECT_EQ(std::string(e.what()), fmt::format("mesh statistics: square id {} out of range", good.square_count()))
          << threads << " threads";
    }
  }
}

#ifdef _OPENMP
// Every parallel loop (edge table, union–find, cell and element areas, per-level medians) must give
// the report of the serial run, bit for bit: with and without rotation, triangles and squares, on
// meshes large enough for the loops to run on two threads.
TEST(Statistics, SameReportForOneAndTwoThreads) {
  const PoleRotation greenland(-44.858333, 78.141667);
  const Lattice lat = make_lattice(10.0, 4);  // 576 × 288 pixels
  const Bitmap m = random_mask(lat.nx, lat.ny, 7u, 0.6, 0.01, 8);
  for (const bool rotated : {false, true}) {
    for (const config::ElementKinds elements : {config::ElementKinds::kTriangles, config::ElementKinds::kSquares}) {
      config::MeshOptions mo;
      mo.elements = elements;
      Mesh mesh = build_all(m, lat, {}, mo, rotated ? greenland : PoleRotation(), testing::synthetic_bathymetry()).mesh;
      if (rotated) {
        mesh.rotation.enabled = true;
        mesh.rotation.pole_lon_deg = -44.858333;
        mesh.rotation.pole_lat_deg = 78.141667;
      }
      ASSERT_GE(mesh.node_count() * 4, quadtree::kParallelMinWork);
      const MeshStatistics one = [&] {
        const testing::ThreadCount use(1);
        return compute_statistics(mesh);
      }();
      const MeshStatistics two = [&] {
        const testing::ThreadCount use(2);
        return compute_statistics(mesh);
      }();
      EXPECT_TRUE(one.failed_checks().empty()) << rotated << " " << name_of(elements);
      EXPECT_EQ(statistics_json(one).dump(), statistics_json(two).dump()) << rotated << " " << name_of(elements);
    }
  }
}
#endif

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
}  // namespace aq::mesh::unit_mesh_statistics_test

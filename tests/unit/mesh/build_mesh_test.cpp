// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh stage (build_mesh.hpp): whole-mesh invariants on random and drawn filled sets,
// coordinates and depths, options, determinism across thread counts, and emission speed.
#include "mesh/build_mesh.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <set>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.hpp"
#include "core/timer.hpp"
#include "mesh/statistics.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/nodes.hpp"
#include "unit/mesh/mesh_fixtures.hpp"
#include "unit/quadtree/mask_fixtures.hpp"

namespace aq::mesh::unit_mesh_build_mesh_test {
namespace {

using testing::build_all;
using testing::draw;
using testing::make_lattice;
using testing::random_mask;

/// Asserts every invariant of a triangle mesh built from `filled`.
void check_mesh(const Mesh& m, const Bitmap& filled, bool geodesic = false) {
  const MeshStatistics s = compute_statistics(m, StatisticsOptions{geodesic, 0.0});
  EXPECT_TRUE(s.failed_checks().empty()) << fmt::format("{}", fmt::join(s.failed_checks(), "; "));
  EXPECT_EQ(s.bad_edges, 0);
  EXPECT_EQ(s.boundary_mismatch, 0);
  EXPECT_EQ(s.interior_edges + s.boundary_edges, s.edges);
  EXPECT_EQ(s.boundary_edges, static_cast<std::int64_t>(m.boundary_edges.size()));
  EXPECT_EQ(s.euler, s.euler_expected);
  EXPECT_EQ(s.components, testing::components4(filled));
  EXPECT_EQ(s.used_nodes - s.edges + s.triangles, 2 * s.components - s.boundary_loops - s.pinch_nodes);
  EXPECT_EQ(s.twice_triangle_area_px2, 2 * filled.count());
  EXPECT_EQ(s.clockwise, 0);
  EXPECT_EQ(s.not_right_isosceles, 0);
  EXPECT_EQ(s.pinch_nodes, static_cast<std::int64_t>(quadtree::find_pinches(filled).size()));
  // Seam: lattice positions are unique modulo nx.
  std::set<std::pair<std::int64_t, std::int64_t>> pos;
  for (std::int64_t n = 0; n < m.node_count(); ++n) {
    ASSERT_LT(m.node_i[static_cast<std::size_t>(n)], m.lattice.nx);
    pos.insert({m.node_i[static_cast<std::size_t>(n)], m.node_j[static_cast<std::size_t>(n)]});
  }
  EXPECT_EQ(static_cast<std::int64_t>(pos.size()), m.node_count());
}

struct Case {
  std::uint32_t seed;
  int band;
  config::BalanceMode balance;
  config::Diagonal diagonal;
};
constexpr auto kFace = config::BalanceMode::kFace, kCorner = config::BalanceMode::kCorner;
constexpr auto kNe = config::Diagonal::kNE, kNw = config::Diagonal::kNW, kAlt = config::Diagonal::kAlternate;

class MeshRandom : public ::testing::TestWithParam<Case> {};

TEST_P(MeshRandom, WholeMeshInvariants) {
  const Case c = GetParam();
  const Lattice lat = make_lattice(45.0, 4);  // 128 × 64 pixels
  const Bitmap m = random_mask(lat.nx, lat.ny, c.seed, 0.6, 0.01, 12);
  config::QuadtreeOptions q;
  q.coast_band = c.band;
  q.balance = c.balance;
  config::MeshOptions mo;
  mo.diagonal = c.diagonal;
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  const testing::Built b = build_all(m, lat, q, mo, PoleRotation(), bathy);
  check_mesh(b.mesh, m, c.seed == 1);
  EXPECT_GT(b.mesh.pinch_nodes.size(), 0u);
  EXPECT_GT(b.mesh.loops.size(), 1u);
  // Templates with midside nodes occur, and all squares are leaves.
  EXPECT_GT(b.mesh.triangle_count(), 2 * b.mesh.square_count());
  EXPECT_EQ(b.mesh.square_count(), static_cast<std::int64_t>(b.leaves.size()));
}

INSTANTIATE_TEST_SUITE_P(Seeds, MeshRandom,
                         ::testing::Values(Case{1, 0, kFace, kNe}, Case{2, 0, kFace, kNw}, Case{3, 2, kFace, kAlt},
                                           Case{4, 2, kCorner, kNe}, Case{5, 1, kCorner, kAlt},
                                           Case{6, 3, kFace, kNe}));

TEST(Mesh, DrawnPinchAndSeamCrossing) {
  // 16 × 8 pixels (L = 2): a region across the seam (columns 13..15 and 0..5), and a pinch at
  // vertex (6, 4) between it and a block to the north-east. rows[0] is the north.
  // clang-format off
  const Bitmap m = draw({"................",
                         "................",
                         "......###.......",
                         "......###.......",
                         "######........##",
                         "####.........###",
                         "###...........##",
                         "................"});
  // clang-format on
  const Lattice lat = make_lattice(90.0, 2);
  config::QuadtreeOptions q;
  q.coast_band = 0;
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  const testing::Built b = build_all(m, lat, q, config::MeshOptions{}, PoleRotation(), bathy);
  check_mesh(b.mesh, m, true);
  ASSERT_EQ(b.mesh.pinch_nodes.size(), 1u);
  const NodeId pinch = b.mesh.pinch_nodes[0];
  EXPECT_EQ(b.mesh.node_i[static_cast<std::size_t>(pinch)], 6);
  EXPECT_EQ(b.mesh.node_j[static_cast<std::size_t>(pinch)], 4);
  int crossing = 0;
  for (const auto& t : b.mesh.triangles) crossing += b.mesh.crosses_seam(t);
  EXPECT_GT(crossing, 0);
  // Seam nodes are shared: the node (0, 2) is used by triangles on both sides of λ = lon0.
  bool east = false, west = false;
  for (const auto& t : b.mesh.triangles) {
    for (const NodeId v : t) {
      if (b.mesh.node_i[static_cast<std::size_t>(v)] != 0 || b.mesh.node_j[static_cast<std::size_t>(v)] != 2) continue;
      (b.mesh.crosses_seam(t) ? east : west) = true;
    }
  }
  EXPECT_TRUE(east && west);
  for (std::int64_t n = 0; n < b.mesh.node_count(); ++n) {
    const auto p = static_cast<std::size_t>(n);
    EXPECT_EQ((b.mesh.node_flags[p] & kNodeSeam) != 0, b.mesh.node_i[p] == 0);
  }
  // Two loops: the seam region and the block are separate (left turns at the pinch).
  EXPECT_EQ(b.mesh.loops.size(), 2u);
}

TEST(Mesh, LevelZeroAndOneLattices) {
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  for (const int levels : {0, 1}) {
    const Lattice lat = make_lattice(30.0, levels);  // 12 × 6 or 24 × 12 pixels
    const Bitmap m = random_mask(lat.nx, lat.ny, 31u, 0.6, 0.0, 3);
    const testing::Built b = build_all(m, lat, {}, {}, PoleRotation(), bathy);
    check_mesh(b.mesh, m);
    if (levels == 0) {
      EXPECT_EQ(b.mesh.triangle_count(), 2 * b.mesh.square_count());  // no midside nodes anywhere
    } else {
      EXPECT_GT(b.mesh.triangle_count(), 2 * b.mesh.square_count());
    }
  }
}

TEST(Mesh, CoordinatesDepthsAndRotation) {
  const Lattice lat = make_lattice(45.0, 3, -30.0);
  const Bitmap m = random_mask(lat.nx, lat.ny, 8u, 0.6, 0.01, 8);
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  for (const bool rotated : {false, true}) {
    const PoleRotation rot = rotated ? PoleRotation(-44.858333, 78.141667) : PoleRotation();
    const testing::Built b = build_all(m, lat, config::QuadtreeOptions{}, config::MeshOptions{}, rot, bathy);
    const Mesh& mesh = b.mesh;
    EXPECT_EQ(mesh.rotation.enabled, rotated);
    if (rotated) {
      EXPECT_NEAR(mesh.rotation.pole_lon_deg, -44.858333, 1e-9);
      EXPECT_NEAR(mesh.rotation.pole_lat_deg, 78.141667, 1e-9);
    }
    for (std::int64_t n = 0; n < mesh.node_count(); n += 7) {
      const auto p = static_cast<std::size_t>(n);
      EXPECT_DOUBLE_EQ(mesh.rlon_deg[p], -30.0 + static_cast<double>(mesh.node_i[p]) * lat.pixel_deg());
      EXPECT_DOUBLE_EQ(mesh.rlat_deg[p], -90.0 + static_cast<double>(mesh.node_j[p]) * lat.pixel_deg());
      double lon = 0, la = 0;
      rot.to_geographic(mesh.rlon_deg[p], mesh.rlat_deg[p], lon, la);
      EXPECT_NEAR(mesh.lat_deg[p], la, 1e-12);
      EXPECT_GE(mesh.lon_deg[p], -30.0);
      EXPECT_LT(mesh.lon_deg[p], 330.0);
      if (std::abs(la) < 89.999) {
        EXPECT_NEAR(std::remainder(mesh.lon_deg[p] - lon, 360.0), 0.0, 1e-9);
      }
      const double d = bathy.sample(mesh.lon_deg[p], mesh.lat_deg[p]);
      EXPECT_EQ(mesh.depth_m[p], d);
    }
    check_mesh(mesh, m, true);
  }
}

TEST(Mesh, PoleRowWithoutRotationIsAPoleLoop) {
  const Lattice lat = make_lattice(45.0, 3);
  Bitmap m(lat.nx, lat.ny);
  for (std::int64_t j = lat.ny - 6; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i)
      if (j != lat.ny - 6 || i % 9 != 0) m.set(i, j);
  std::vector<std::string> warnings;
  const Logger log([&](LogLevel l, std::string_view s) {
    if (l == LogLevel::kWarning) warnings.emplace_back(s);
  });
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  const std::vector<quadtree::Leaf> leaves = quadtree::build_leaves(m, lat, {}, PoleRotation(), &bathy, log, nullptr);
  const Mesh mesh = build_mesh(leaves, lat, PoleRotation(), bathy, {}, log, nullptr);
  check_mesh(mesh, m, true);
  int poles = 0;
  for (const BoundaryLoop& loop : mesh.loops) {
    if (!loop.pole) continue;
    ++poles;
    for (const NodeId n : loop.nodes) {
      EXPECT_EQ(mesh.node_j[static_cast<std::size_t>(n)], lat.ny);
      EXPECT_TRUE(mesh.node_flags[static_cast<std::size_t>(n)] & kNodePole);
      EXPECT_DOUBLE_EQ(mesh.lat_deg[static_cast<std::size_t>(n)], 90.0);
    }
  }
  EXPECT_EQ(poles, 1);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings.front().find("rotation"), std::string::npos);
}

TEST(Mesh, SquaresOnlyAndBoth) {
  const Lattice lat = make_lattice(45.0, 3);
  const Bitmap m = random_mask(lat.nx, lat.ny, 12u);
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  config::MeshOptions squares, both;
  squares.elements = config::ElementKinds::kSquares;
  both.elements = config::ElementKinds::kBoth;
  const testing::Built s = build_all(m, lat, {}, squares, PoleRotation(), bathy);
  const testing::Built t = build_all(m, lat, {}, both, PoleRotation(), bathy);
  EXPECT_TRUE(s.mesh.triangles.empty());
  EXPECT_EQ(s.mesh.squares.size(), t.mesh.squares.size());
  std::int64_t centres = 0;
  for (const std::uint8_t f : t.mesh.node_flags) centres += (f & kNodeCentre) != 0;
  EXPECT_GT(centres, 0);
  EXPECT_EQ(s.mesh.node_count() + centres, t.mesh.node_count());
  // Square corners are anticlockwise SW, SE, NE, NW and midside nodes sit on the sides.
  for (std::size_t k = 0; k < s.mesh.squares.size(); ++k) {
    const auto& c = s.mesh.squares[k];
    const auto I = [&](NodeId n) { return s.mesh.unwrapped_i(c, n); };
    const auto J = [&](NodeId n) { return s.mesh.node_j[static_cast<std::size_t>(n)]; };
    const std::int64_t side = lat.pixels_per_square(s.mesh.square_level[k]);
    EXPECT_EQ(I(c[1]) - I(c[0]), side);
    EXPECT_EQ(J(c[3]) - J(c[0]), side);
    EXPECT_EQ(I(c[2]), I(c[1]));
    EXPECT_EQ(J(c[2]), J(c[3]));
    const NodeId ms = s.mesh.square_midside[k][0];
    if (ms >= 0) {
      EXPECT_EQ(J(ms), J(c[0]));
    }
  }
}

TEST(Mesh, ReportSections) {
  const Lattice lat = make_lattice(45.0, 3);
  const Bitmap m = random_mask(lat.nx, lat.ny, 13u);
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  Report report;
  const testing::Built b = build_all(m, lat, {}, {}, PoleRotation(), bathy, &report);
  EXPECT_EQ(report["mesh"]["triangles"].get<std::int64_t>(), b.mesh.triangle_count());
  EXPECT_EQ(report["mesh"]["nodes"].get<std::int64_t>(), b.mesh.node_count());
  EXPECT_EQ(report["quadtree"]["leaves"].get<std::int64_t>(), b.mesh.square_count());
  EXPECT_EQ(report["quadtree"]["balance_violations"].get<std::int64_t>(), 0);
  const Json st = statistics_json(compute_statistics(b.mesh));
  EXPECT_TRUE(st["ok"].get<bool>()) << st.dump(2);
  EXPECT_EQ(st["euler"]["ok"].get<bool>(), true);
}

#ifdef _OPENMP
TEST(Mesh, IdenticalForOneAndTwoThreads) {
  const Lattice lat = make_lattice(30.0, 4);  // 192 × 96
  const Bitmap m = random_mask(lat.nx, lat.ny, 21u, 0.6, 0.01, 10);
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  config::MeshOptions mo;
  mo.diagonal = config::Diagonal::kAlternate;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const testing::Built one = build_all(m, lat, {}, mo, PoleRotation(-44.858333, 78.141667), bathy);
  const MeshStatistics s1 = compute_statistics(one.mesh);
  omp_set_num_threads(2);
  const testing::Built two = build_all(m, lat, {}, mo, PoleRotation(-44.858333, 78.141667), bathy);
  const MeshStatistics s2 = compute_statistics(two.mesh);
  omp_set_num_threads(saved);
  EXPECT_EQ(one.leaves, two.leaves);
  testing::expect_same_mesh(one.mesh, two.mesh);
  EXPECT_EQ(statistics_json(s1).dump(), statistics_json(s2).dump());
}
#endif

TEST(MeshPerf, TenMillionTriangles) {
  // Δ0 = 1°, L = 4: 5760 × 2880 pixels; a ragged filled set keeps most leaves at level L.
  using clock = std::chrono::steady_clock;
  const auto secs = [](clock::time_point a) { return std::chrono::duration<double>(clock::now() - a).count(); };
  const Lattice lat = make_lattice(1.0, 4);
  const Bitmap m = random_mask(lat.nx, lat.ny, 99u, 0.45, 0.05, 40);
  const raster::Bathymetry bathy = testing::synthetic_bathymetry();
  config::QuadtreeOptions q;
  auto t0 = clock::now();
  const std::vector<quadtree::Leaf> leaves =
      quadtree::build_leaves(m, lat, q, PoleRotation(), &bathy, Logger::null(), nullptr);
  const double leaves_s = secs(t0);
  t0 = clock::now();
  quadtree::LevelMasks masks = quadtree::make_level_masks(m, lat, q.coast_band);
  const double masks_s = secs(t0);
  t0 = clock::now();
  quadtree::balance(masks, quadtree::BalanceMode::kFace);
  const double balance_s = secs(t0);
  t0 = clock::now();
  quadtree::QuadNodes nodes = quadtree::build_nodes(leaves, lat, quadtree::NodeOptions{true});
  const double nodes_s = secs(t0);
  Mesh mesh;
  mesh.lattice = lat;
  mesh.squares = nodes.corners;
  mesh.square_midside = nodes.midside;
  t0 = clock::now();
  const double cpu0 = process_cpu_seconds();
  emit_triangles(leaves, nodes.midside_code, nodes.centre, Diagonal::kNE, mesh);
  const double emit_s = secs(t0), emit_cpu_s = process_cpu_seconds() - cpu0;
  // Again into memory already touched: the emission itself, without first-touch page faults.
  t0 = clock::now();
  mesh.triangles.clear();
  mesh.triangle_level.clear();
  mesh.triangle_square.clear();
  emit_triangles(leaves, nodes.midside_code, nodes.centre, Diagonal::kNE, mesh);
  const double warm_s = secs(t0);
  t0 = clock::now();
  const Mesh full = build_mesh(leaves, lat, PoleRotation(), bathy, {}, Logger::null(), nullptr);
  const double build_s = secs(t0);
  t0 = clock::now();
  const MeshStatistics st = compute_statistics(full);
  const double stats_s = secs(t0);
  std::printf("  lattice %lld × %lld, %zu leaves, %lld nodes, %lld triangles\n", static_cast<long long>(lat.nx),
              static_cast<long long>(lat.ny), leaves.size(), static_cast<long long>(full.node_count()),
              static_cast<long long>(full.triangle_count()));
  std::printf("  build_leaves %.3f s (masks %.3f s, balance %.3f s); build_nodes %.3f s\n", leaves_s, masks_s,
              balance_s, nodes_s);
  const double mt = static_cast<double>(mesh.triangle_count()) * 1e-6;
  std::printf(
      "  emit_triangles %.3f s wall (%.3f s CPU) = %.1f million triangles/s; into touched memory %.3f s = %.1f "
      "million triangles/s\n",
      emit_s, emit_cpu_s, mt / emit_s, warm_s, mt / warm_s);
  std::printf("  build_mesh %.3f s; statistics %.3f s (WGS84 sizes included)\n", build_s, stats_s);
  EXPECT_EQ(mesh.triangles, full.triangles);
  EXPECT_TRUE(st.failed_checks().empty()) << fmt::format("{}", fmt::join(st.failed_checks(), "; "));
}

}  // namespace
}  // namespace aq::mesh::unit_mesh_build_mesh_test

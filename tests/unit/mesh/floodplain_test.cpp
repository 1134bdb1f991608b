// SPDX-License-Identifier: GPL-3.0-or-later
// The floodplain of a surge mesh (mesh/floodplain.hpp) and the time step with wetting and drying
// (mesh/time_step.hpp): triangles cut by the 0 m line of their linear elevation surface keep the
// corner above the datum (1/4 of a triangle whose one node is +1 and the others -1, 7/16 with two
// nodes +1 and one -3), nodes at exactly 0 m are not floodplain, and the flooded time step takes
// H = z - elevation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh/floodplain.hpp"
#include "mesh/time_step.hpp"

namespace aq::mesh::unit_mesh_floodplain_test {

namespace {

// One right triangle of legs `leg_deg` at (lon0, lat0) with node elevations z.
Mesh triangle(double lon0, double lat0, double leg_deg, std::array<double, 3> z) {
  Mesh m;
  m.lon_deg = {lon0, lon0 + leg_deg, lon0};
  m.lat_deg = {lat0, lat0, lat0 + leg_deg};
  m.depth_m = {z[0], z[1], z[2]};
  m.triangles = {{0, 1, 2}};
  m.boundary_edges = {{0, 1}, {1, 2}, {2, 0}};
  return m;
}

// Its area (km²) on a sphere of the authalic radius (the small triangle is almost plane); WGS84's
// area element differs from it by up to 0.67 % (-0.45 % at the equator).
double sphere_area_km2(double lat0, double leg_deg) {
  constexpr double kR = 6371.0072;  // authalic radius of WGS84
  const double d = std::numbers::pi / 180.0;
  return 0.5 * kR * kR * leg_deg * d * (std::sin((lat0 + leg_deg) * d) - std::sin(lat0 * d));
}

TEST(Floodplain, WholeTriangleAboveTheDatum) {
  const Floodplain f = floodplain(triangle(10.0, 30.0, 0.1, {1.0, 2.0, 3.0}), 5.0);
  EXPECT_EQ(f.nodes, 3);
  EXPECT_EQ(f.triangles, 1);
  EXPECT_NEAR(f.area_km2 / sphere_area_km2(30.0, 0.1), 1.0, 7e-3);  // WGS84 against the sphere
  EXPECT_DOUBLE_EQ(f.highest_node_m, 3.0);
  EXPECT_EQ(f.land_boundary_nodes, 3);
  EXPECT_EQ(f.land_boundary_nodes_above, 3);
  EXPECT_DOUBLE_EQ(f.top_m, 5.0);
}

TEST(Floodplain, OneNodeAboveKeepsAQuarterTwoNodesSevenSixteenths) {
  const double whole = floodplain(triangle(-90.0, 29.0, 0.05, {1.0, 1.0, 1.0}), 10.0).area_km2;
  ASSERT_GT(whole, 0.0);
  // Each node in turn is the one above: the 0 m line halves its two edges.
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> z{-1.0, -1.0, -1.0};
    z[static_cast<std::size_t>(k)] = 1.0;
    const Floodplain f = floodplain(triangle(-90.0, 29.0, 0.05, z), 10.0);
    EXPECT_EQ(f.nodes, 1);
    EXPECT_EQ(f.triangles, 1);
    EXPECT_NEAR(f.area_km2 / whole, 0.25, 1e-3) << "node " << k;
  }
  // Two above (+1), one at -3: the cut is 3/4 of the way from the low node, which keeps 9/16 below.
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> z{1.0, 1.0, 1.0};
    z[static_cast<std::size_t>(k)] = -3.0;
    const Floodplain f = floodplain(triangle(-90.0, 29.0, 0.05, z), 10.0);
    EXPECT_EQ(f.nodes, 2);
    EXPECT_NEAR(f.area_km2 / whole, 7.0 / 16.0, 1e-3) << "node " << k;
  }
}

TEST(Floodplain, NodesAtTheDatumAreNotFloodplain) {
  for (const auto z : {std::array<double, 3>{0.0, 0.0, 0.0}, std::array<double, 3>{0.0, -1.0, -2.0}}) {
    const Floodplain f = floodplain(triangle(0.0, 0.0, 0.1, z), 5.0);
    EXPECT_EQ(f.nodes, 0);
    EXPECT_EQ(f.triangles, 0);
    EXPECT_EQ(f.area_km2, 0.0);
    EXPECT_EQ(f.land_boundary_nodes_above, 0);
  }
}

TEST(Floodplain, OpenBoundaryNodesAreNotLandBoundary) {
  Mesh m = triangle(0.0, 0.0, 0.1, {2.0, -1.0, 3.0});
  m.typed = true;
  m.boundary_edge_type = {BoundaryType::kOpen, BoundaryType::kMainland, BoundaryType::kMainland};
  const Floodplain f = floodplain(m, 5.0);
  EXPECT_EQ(f.land_boundary_nodes, 3);  // the open edge's nodes are on land edges too
  m.boundary_edge_type = {BoundaryType::kOpen, BoundaryType::kOpen, BoundaryType::kMainland};
  const Floodplain g = floodplain(m, 5.0);
  EXPECT_EQ(g.land_boundary_nodes, 2);        // nodes 2 and 0 of the land edge 2-0
  EXPECT_EQ(g.land_boundary_nodes_above, 2);  // +3 and +2
}

TEST(Floodplain, TriangleAcrossTheSeam) {
  // The same triangle at 179.95..180.05°E written with the east nodes at -179.95°.
  Mesh m = triangle(179.95, 10.0, 0.1, {1.0, 1.0, 1.0});
  const double east = floodplain(m, 5.0).area_km2;
  m.lon_deg[1] = -179.95;
  EXPECT_NEAR(floodplain(m, 5.0).area_km2, east, 1e-9 * east);
  EXPECT_NEAR(east / sphere_area_km2(10.0, 0.1), 1.0, 7e-3);
}

TEST(TimeStep, WettingAndDryingFloodsEveryNodeToTheTop) {
  // A deep triangle (50 m, legs 0.1°) and a floodplain one (+1..+3 m, legs 0.01°) side by side.
  Mesh m;
  m.lon_deg = {0.0, 0.1, 0.0, 1.0, 1.01, 1.0};
  m.lat_deg = {0.0, 0.0, 0.1, 0.0, 0.0, 0.01};
  m.depth_m = {-50.0, -50.0, -50.0, 1.0, 2.0, 3.0};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const TimeStep dry = time_step(m, 1.0, 0.0, 0.5);
  EXPECT_EQ(dry.wetting_drying.flood_level_m, 0.0);  // none asked
  const TimeStep wd = time_step(m, 1.0, 0.0, 0.5, 10.0);
  const double g = 9.81, leg_deep = 0.1 * 6371008.8 * std::numbers::pi / 180.0;
  // At rest the floodplain takes the 1 m floor: its short edge limits (1.1 km at √(g·1): 355 s, against
  // 11 km at √(g·50): 503 s).
  EXPECT_EQ(dry.limiting_triangle, 1);
  EXPECT_NEAR(dry.limiting_depth_m, 1.0, 1e-12);
  // Flooded to +10 m: H = 10 - 1 = 9 m on the floodplain (its lowest node), 60 m at sea.
  const TimeStep::WettingDrying& w = wd.wetting_drying;
  EXPECT_DOUBLE_EQ(w.flood_level_m, 10.0);
  EXPECT_EQ(w.limiting_triangle, 1);
  EXPECT_NEAR(w.limiting_depth_m, 9.0, 1e-12);
  EXPECT_DOUBLE_EQ(w.limiting_elevation_m, 3.0);
  EXPECT_NEAR(w.max_stable_dt_s, w.limiting_edge_m / std::sqrt(g * 9.0), 1e-9);
  EXPECT_LT(w.max_stable_dt_s, dry.max_stable_dt_s);
  // The deep triangle alone: H = 60 m.
  Mesh deep = m;
  deep.triangles = {{0, 1, 2}};
  EXPECT_NEAR(time_step(deep, 1.0, 0.0, 0.5, 10.0).wetting_drying.max_stable_dt_s, leg_deep / std::sqrt(g * 60.0),
              1e-6 * leg_deep);
  const Json j = time_step_json(wd);
  ASSERT_TRUE(j.contains("wetting_drying"));
  EXPECT_DOUBLE_EQ(j["wetting_drying"]["flood_level_m"].get<double>(), 10.0);
  EXPECT_FALSE(time_step_json(dry).contains("wetting_drying"));
}

}  // namespace

}  // namespace aq::mesh::unit_mesh_floodplain_test

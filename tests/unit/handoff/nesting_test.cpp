// SPDX-License-Identifier: GPL-3.0-or-later
// Nesting data: the ROMS boundary point layout, a regional grid in the open South Atlantic located
// in the real global mesh (weights reproduce the boundary points to 1e-9°, refinement ratio
// from the element and cell sizes), a grid over the coast (points outside flagged and counted),
// the same on the rotated Mercator lattice (weights in the λ', Mercator-y plane, element sizes
// with the Mercator scale cos φ'), and the netCDF round trip.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <variant>

#include "core/types.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "grid_files/nesting_netcdf.hpp"
#include "handoff/nesting.hpp"
#include "support/temp_dir.hpp"
#include "support/uniform_grid.hpp"
#include "unit/handoff/global_mesh_fixture.hpp"

namespace unit_handoff_nesting_test {

namespace {

using aq::curvilinear::Grid2D;
using aq::curvilinear::Projection;
using aq::curvilinear::ProjectionParams;
using aq::handoff::CPointType;
using aq::handoff::RomsBoundary;

// A uniform planar supergrid of L x M cells spanning [-w, w] x [-h, h] plane units.
Grid2D plane_grid(int L, int M, double w, double h) { return aq::testing::uniform_supergrid(L, M, w, h); }

Projection mercator_at(double lon, double lat) {
  ProjectionParams p;
  p.rlon_deg = lon;
  p.rlat_deg = lat;
  p.uscale = 0.001;
  return Projection(p);
}

std::int64_t attribute_int(const aq::io::NestingFile& f, const std::string& key) {
  for (const auto& [k, v] : f.attributes)
    if (k == key) return std::get<std::int64_t>(v);
  ADD_FAILURE() << key << " missing";
  return -1;
}

}  // namespace

TEST(BoundaryPoints, RomsLayout) {
  const auto p = aq::handoff::boundary_points(3, 2);
  // Per boundary: west/east (M+1) ρ + (M+1) u + M v = 8, south/north (L+1) + L + (L+1) = 11.
  ASSERT_EQ(p.size(), 38u);
  EXPECT_EQ(p[0].type, CPointType::kRho);
  EXPECT_EQ(p[0].boundary, RomsBoundary::kWest);
  // West u points are ROMS's u(1, j): file index 0, supergrid column 1.
  EXPECT_EQ(p[3].type, CPointType::kU);
  EXPECT_EQ(p[3].xi, 0);
  EXPECT_EQ(p[3].si, 1);
  EXPECT_EQ(p[3].sj, 0);
  // North v points: file row M - 1, supergrid row 2M - 1.
  const auto& last = p.back();
  EXPECT_EQ(last.type, CPointType::kV);
  EXPECT_EQ(last.boundary, RomsBoundary::kNorth);
  EXPECT_EQ(last.xi, 3);
  EXPECT_EQ(last.eta, 1);
  EXPECT_EQ(last.si, 6);
  EXPECT_EQ(last.sj, 3);
  // East ρ: column L; east u: file column L - 1 (supergrid 2L - 1).
  int east_rho = 0, east_u = 0;
  for (const auto& q : p) {
    if (q.boundary != RomsBoundary::kEast) continue;
    if (q.type == CPointType::kRho) {
      ++east_rho;
      EXPECT_EQ(q.si, 6);
    }
    if (q.type == CPointType::kU) {
      ++east_u;
      EXPECT_EQ(q.xi, 2);
      EXPECT_EQ(q.si, 5);
    }
  }
  EXPECT_EQ(east_rho, 3);
  EXPECT_EQ(east_u, 3);
}

TEST(GlobalNesting, OpenOceanGridReproducesBoundaryPoints) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Projection proj = mercator_at(-25.0, -40.0);
  const Grid2D g = plane_grid(10, 8, 50.0, 40.0);  // ±0.05 x ±0.04 rad: about 5.7° x 4.6°
  const auto cg = aq::curvilinear::build_cgrid(g, proj);
  aq::handoff::NestingSummary sum;
  const aq::io::NestingFile n = aq::handoff::global_nesting(g, cg, f.mesh, &sum);
  ASSERT_EQ(n.size(), aq::handoff::boundary_points(10, 8).size());
  EXPECT_EQ(sum.points, static_cast<std::int64_t>(n.size()));
  EXPECT_EQ(sum.outside, 0);
  EXPECT_EQ(attribute_int(n, "points_outside"), 0);
  const auto& m = f.mesh;
  for (std::size_t k = 0; k < n.size(); ++k) {
    ASSERT_GE(n.element[k], 0);
    double lon = 0.0, lat = 0.0, sum_w = 0.0;
    const auto& tri = m.triangles[static_cast<std::size_t>(n.element[k])];
    for (std::size_t q = 0; q < 3; ++q) {
      EXPECT_EQ(n.element_nodes[k][q], tri[q]);
      const double w = n.weights[k][q];
      EXPECT_GE(w, -1e-12);
      EXPECT_LE(w, 1.0 + 1e-12);
      sum_w += w;
      lon += w * m.lattice.lon_of(m.unwrapped_i(tri, tri[q]));
      lat += w * m.lattice.lat_of(m.node_j[static_cast<std::size_t>(tri[q])]);
    }
    EXPECT_NEAR(sum_w, 1.0, 1e-14);
    EXPECT_NEAR(std::remainder(lon - n.lon[k], 360.0), 0.0, 1e-9);
    EXPECT_NEAR(lat, n.lat[k], 1e-9);
    // The boundary point is where the supergrid says.
    const auto g_ll = proj.inverse(n.x[k], n.y[k]);
    EXPECT_NEAR(std::remainder(g_ll.lon_deg - n.lon[k], 360.0), 0.0, 1e-9);
    EXPECT_NEAR(g_ll.lat_deg, n.lat[k], 1e-9);
    // Ratio = sizes; the open ocean is covered by coarse elements (legs of 4° or 2√2°).
    EXPECT_DOUBLE_EQ(n.refinement_ratio[k], n.global_element_size_m[k] / n.regional_cell_size_m[k]);
    EXPECT_GT(n.global_element_size_m[k], 2.8 * 111e3 * std::sqrt(std::cos(46.0 * aq::kDegToRad)) * 0.99);
  }
  // Regional cells: 0.1 rad / 10 cells x 6371 km ≈ 63.7 km (Mercator scale ≈ 1 near the centre).
  EXPECT_NEAR(n.regional_cell_size_m[0], 63.71e3, 0.03 * 63.71e3);
  EXPECT_GT(sum.ratio_median, 3.0);
  EXPECT_LT(sum.ratio_median, 8.0);
}

TEST(GlobalNesting, PointsOverLandAreFlaggedAndCounted) {
  const auto& f = aq::testing::etopo60_mesh(false);
  // Straddling the coast of West Africa at 20°N, 17°W (half of it over the Sahara).
  const Projection proj = mercator_at(-14.0, 20.0);
  const Grid2D g = plane_grid(12, 12, 80.0, 80.0);
  const auto cg = aq::curvilinear::build_cgrid(g, proj);
  aq::handoff::NestingSummary sum;
  const aq::io::NestingFile n = aq::handoff::global_nesting(g, cg, f.mesh, &sum);
  std::int64_t minus_one = 0;
  for (std::size_t k = 0; k < n.size(); ++k) {
    if (n.element[k] >= 0) continue;
    ++minus_one;
    EXPECT_EQ(n.element_nodes[k][0], -1);
    EXPECT_EQ(n.weights[k][0], 0.0);
    EXPECT_EQ(n.element_level[k], -1);
    EXPECT_TRUE(std::isnan(n.refinement_ratio[k]));
  }
  EXPECT_GT(minus_one, 10);
  EXPECT_LT(minus_one, static_cast<std::int64_t>(n.size()) - 10);
  EXPECT_EQ(sum.outside, minus_one);
  EXPECT_EQ(attribute_int(n, "points_outside"), minus_one);
}

TEST(NestingNetcdf, RoundTrip) {
  const auto& f = aq::testing::etopo60_mesh(false);
  const Projection proj = mercator_at(-14.0, 20.0);
  const Grid2D g = plane_grid(6, 5, 80.0, 60.0);
  const auto cg = aq::curvilinear::build_cgrid(g, proj);
  aq::io::NestingFile n = aq::handoff::global_nesting(g, cg, f.mesh);
  n.history = "test";
  aq::testing::TempDir dir;
  const auto path = dir / "t_nesting.nc";
  aq::io::write_nesting(path, n);
  const aq::io::NestingFile r = aq::io::read_nesting(path);
  EXPECT_EQ(r.point_type, n.point_type);
  EXPECT_EQ(r.boundary, n.boundary);
  EXPECT_EQ(r.xi_index, n.xi_index);
  EXPECT_EQ(r.eta_index, n.eta_index);
  EXPECT_EQ(r.lon, n.lon);
  EXPECT_EQ(r.lat, n.lat);
  EXPECT_EQ(r.element, n.element);
  EXPECT_EQ(r.element_nodes, n.element_nodes);
  EXPECT_EQ(r.weights, n.weights);
  EXPECT_EQ(r.element_level, n.element_level);
  EXPECT_EQ(r.history, "test");
  EXPECT_EQ(attribute_int(r, "points_total"), static_cast<std::int64_t>(n.size()));
  EXPECT_EQ(attribute_int(r, "global_mesh_triangles"), f.mesh.triangle_count());
}

TEST(GlobalNesting, RotatedMercatorMeshWeightsAreInTheMercatorPlane) {
  const auto& f = aq::testing::etopo60_mesh(true, aq::LatticeKind::kMercator);
  const auto& m = f.mesh;
  ASSERT_TRUE(m.lattice.mercator());
  const Projection proj = mercator_at(-25.0, -40.0);  // the open South Atlantic
  const Grid2D g = plane_grid(10, 8, 50.0, 40.0);
  const auto cg = aq::curvilinear::build_cgrid(g, proj);
  aq::handoff::NestingSummary sum;
  const aq::io::NestingFile n = aq::handoff::global_nesting(g, cg, m, &sum);
  EXPECT_EQ(sum.outside, 0);
  std::string kind;
  for (const auto& [key, v] : n.attributes)
    if (key == "lattice_kind") kind = std::get<std::string>(v);
  EXPECT_EQ(kind, "mercator");
  const double d = m.lattice.pixel_deg();
  for (std::size_t k = 0; k < n.size(); ++k) {
    ASSERT_GE(n.element[k], 0);
    double rlon = 0.0, rlat = 0.0;
    f.rotation.to_rotated(n.lon[k], n.lat[k], rlon, rlat);
    const double y = std::log(std::tan(M_PI / 4.0 + 0.5 * rlat * aq::kDegToRad)) * aq::kRadToDeg;
    const auto& tri = m.triangles[static_cast<std::size_t>(n.element[k])];
    double px = 0.0, py = 0.0, sum_w = 0.0, area2 = 0.0;
    std::array<std::array<double, 2>, 3> v{};
    for (std::size_t q = 0; q < 3; ++q) {
      const double w = n.weights[k][q];
      EXPECT_GE(w, 0.0);
      EXPECT_LE(w, 1.0);
      sum_w += w;
      v[q] = {static_cast<double>(m.unwrapped_i(tri, tri[q])),
              static_cast<double>(m.node_j[static_cast<std::size_t>(tri[q])])};
      px += w * (m.lattice.lon0_deg + v[q][0] * d);
      py += w * (m.lattice.y0_deg + v[q][1] * d);
    }
    EXPECT_NEAR(sum_w, 1.0, 1e-14);
    EXPECT_NEAR(std::remainder(px - rlon, 360.0), 0.0, 1e-9);
    EXPECT_NEAR(py, y, 1e-9);
    // Element size: leg √(2·area) pixels of Δ_L·cos φ' on the sphere (a Mercator pixel is square).
    area2 = std::abs((v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[2][0] - v[0][0]) * (v[1][1] - v[0][1]));
    const double size =
        std::sqrt(area2) * d * aq::kDegToRad * cg.options.earth_radius_m * std::cos(rlat * aq::kDegToRad);
    EXPECT_NEAR(n.global_element_size_m[k], size, 1e-6 * size);
  }
}

}  // namespace unit_handoff_nesting_test

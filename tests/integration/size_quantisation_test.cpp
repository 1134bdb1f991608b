// SPDX-License-Identifier: GPL-3.0-or-later
// Quantisation of the size field into quadtree levels (ARCHITECTURE §4.10), on synthetic data
// with a known answer:
//  * the grading: a continent forces the finest level on its coast (the D_l rule) while the field
//    asks a constant coarse size; with size.gradation = g the levels must step only after runs
//    long enough for g (achieved grading <= g, and a(x) <= 2·a(y) + √2·g·d(x, y) for every pair of
//    leaves), and every leaf is at most √2 × the field at its centre;
//  * the CFL bound: an all-water globe (nothing forces a level) with a shallow shelf that the
//    wavelength term refines: at size.cfl.dt_s every triangle of the mesh built from the leaves
//    keeps Cr <= Cr_max (the 2:1 balance and the grading included), counted by mesh::time_step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/rotation.hpp"
#include "mesh/build_mesh.hpp"
#include "mesh/time_step.hpp"
#include "quadtree/balance.hpp"
#include "quadtree/bits.hpp"
#include "quadtree/grading.hpp"
#include "quadtree/leaves.hpp"
#include "raster/bathymetry.hpp"
#include "size/size_field.hpp"

namespace aq::integration_size_quantisation_test {
namespace {

constexpr double kRad = 3.14159265358979323846 / 180.0;

// Unit vector of the lattice-frame centre of a leaf.
void centre_unit(const Lattice& lat, const quadtree::Leaf& f, double* u) {
  const double lon = lat.lon0_deg + (static_cast<double>(f.a) + 0.5) * lat.step0_deg / static_cast<double>(1 << f.level);
  const double la = lat.lat_of_row(quadtree::leaf_centre_row(lat, f));
  u[0] = std::cos(la * kRad) * std::cos(lon * kRad);
  u[1] = std::cos(la * kRad) * std::sin(lon * kRad);
  u[2] = std::sin(la * kRad);
}

struct Built {
  std::vector<quadtree::Leaf> leaves;
  size::SizeField field;
};

Built build(const Bitmap& filled, const Lattice& lat, const config::GlobalConfig& c, const raster::Bathymetry* bathy,
            bool grade) {
  Built b;
  b.field = size::build_size_field(filled, lat, c, PoleRotation(), bathy, Logger::null(), nullptr);
  quadtree::LevelMasks m = quadtree::make_level_masks(filled, lat, 0);
  quadtree::apply_size_field(m, lat, b.field);
  if (grade) quadtree::grade_levels(m, lat, b.field);
  quadtree::balance(m, quadtree::BalanceMode::kFace);
  b.leaves = quadtree::extract_leaves(m, lat);
  return b;
}

// A Mercator lattice (Δ0 = 15°, L = 5) all water but a round continent of 25° radius.
Bitmap continent(const Lattice& lat) {
  Bitmap filled(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j)
    for (std::int64_t i = 0; i < lat.nx; ++i) {
      const double lon = lat.lon_of(i) + 0.5 * lat.pixel_deg(), la = lat.lat_of_row(static_cast<double>(j) + 0.5);
      const double cosd = std::cos(la * kRad) * std::cos(lon * kRad);  // centre (0°, 0°)
      if (std::acos(std::clamp(cosd, -1.0, 1.0)) > 25.0 * kRad) filled.set(i, j);
    }
  return filled;
}

TEST(SizeQuantisation, LevelsKeepTheGradingAroundTheFinestLevelTheCoastForces) {
  const Lattice lat = Lattice::make_mercator(15.0, 5, -180.0, 80.0);
  const Bitmap filled = continent(lat);
  config::GlobalConfig c;
  c.quadtree.size_km = 1500.0;  // coarse everywhere: only the coast asks level L
  c.size.gradation = 0.2;
  const Built graded = build(filled, lat, c, nullptr, true);
  const quadtree::Grading g = quadtree::achieved_grading(graded.leaves, lat, lat.levels);
  ASSERT_GT(g.runs, 100);
  EXPECT_LE(g.max, 0.2 + 1e-9);
  // Without the quantisation rule the 2:1 balance alone steps one level per square: 0.71.
  const Built balanced = build(filled, lat, c, nullptr, false);
  EXPECT_GT(quadtree::achieved_grading(balanced.leaves, lat, lat.levels).max, 0.7);
  EXPECT_GT(graded.leaves.size(), balanced.leaves.size());

  // Every leaf at most √2 × the field at its centre (splits only ever make leaves smaller).
  std::vector<double> a(graded.leaves.size());
  std::vector<std::array<double, 3>> u(graded.leaves.size());
  for (std::size_t k = 0; k < graded.leaves.size(); ++k) {
    const quadtree::Leaf& f = graded.leaves[k];
    a[k] = quadtree::square_size_km(lat, f.level, quadtree::leaf_centre_row(lat, f));
    const std::int64_t s = quadtree::leaf_size(lat, f);
    const double h = graded.field.at_pixel(quadtree::leaf_i0(lat, f) + s / 2, quadtree::leaf_j0(lat, f) + s / 2);
    EXPECT_LE(a[k], std::sqrt(2.0) * h * (1.0 + 1e-9)) << k;
    centre_unit(lat, f, u[k].data());
  }
  // a(x) <= 2·a(y) + √2·g·d(x, y) for every pair (d: great circle between the centres).
  std::int64_t bad = 0;
  for (std::size_t x = 0; x < a.size(); ++x)
    for (std::size_t y = 0; y < a.size(); ++y) {
      if (a[x] <= 2.0 * a[y]) continue;
      const double dot = u[x][0] * u[y][0] + u[x][1] * u[y][1] + u[x][2] * u[y][2];
      const double d = 6371.0088 * std::acos(std::clamp(dot, -1.0, 1.0));
      if (a[x] > (2.0 * a[y] + std::sqrt(2.0) * 0.2 * d) * (1.0 + 1e-9)) ++bad;
    }
  EXPECT_EQ(bad, 0);
}

TEST(SizeQuantisation, EveryTriangleKeepsTheCourantBoundWhereNothingForcesALevel) {
  const Lattice lat = Lattice::make_mercator(15.0, 5, -180.0, 80.0);
  Bitmap filled(lat.nx, lat.ny);
  for (std::int64_t j = 0; j < lat.ny; ++j) quadtree::bits::set_range(filled.row(j), 0, lat.nx);
  // Deep ocean, 4000 m, with a 30 m shelf between 10° and 30° N and 60° W and 0°, on a 0.5° grid.
  const std::int64_t nc = 720, nr = 361;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t q = 0; q < nc; ++q) {
      const double lon = -180.0 + 0.5 * static_cast<double>(q), la = -90.0 + 0.5 * static_cast<double>(r);
      v[static_cast<std::size_t>(r * nc + q)] = (la >= 10.0 && la <= 30.0 && lon >= -60.0 && lon <= 0.0) ? -30.0F : -4000.0F;
    }
  const raster::Bathymetry bathy = raster::Bathymetry::from_grid(v, nc, nr, -180.0, -90.0, 0.5, 0.5);
  config::GlobalConfig c;
  c.size.wavelength.wl = 30.0;
  c.size.gradation = 0.2;
  c.size.cfl.dt_s = 200.0;  // deep water asks edges of 79 km at Cr 0.5
  const Built b = build(filled, lat, c, &bathy, true);
  config::MeshOptions mo;
  const mesh::Mesh m = mesh::build_mesh(b.leaves, lat, PoleRotation(), bathy, mo, Logger::null(), nullptr);
  const mesh::TimeStep ts = mesh::time_step(m, c.size.min_depth_m, c.size.cfl.dt_s, c.size.cfl.courant_max);
  ASSERT_EQ(ts.courant_percentiles.size(), 5u);
  EXPECT_EQ(ts.above_courant_max, 0) << "max Cr " << ts.courant_percentiles[4];
  EXPECT_LE(ts.courant_percentiles[4], c.size.cfl.courant_max);
  EXPECT_GT(ts.courant_percentiles[4], 0.1);
  // Not vacuous: the same field without the CFL bound has triangles above Cr_max at that step.
  config::GlobalConfig free = c;
  free.size.cfl.dt_s = 0.0;
  const Built f = build(filled, lat, free, &bathy, true);
  const mesh::Mesh mf = mesh::build_mesh(f.leaves, lat, PoleRotation(), bathy, mo, Logger::null(), nullptr);
  EXPECT_GT(mesh::time_step(mf, c.size.min_depth_m, c.size.cfl.dt_s, c.size.cfl.courant_max).above_courant_max, 100);
}

}  // namespace
}  // namespace aq::integration_size_quantisation_test

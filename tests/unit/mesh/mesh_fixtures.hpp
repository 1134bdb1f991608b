// SPDX-License-Identifier: GPL-3.0-or-later
// Fixtures of the mesh tests: a synthetic global raster and the quadtree -> mesh pipeline on a
// filled set, plus field-by-field mesh comparison.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "config/options.hpp"
#include "core/log.hpp"
#include "mesh/build_mesh.hpp"
#include "quadtree/build_leaves.hpp"
#include "raster/bathymetry.hpp"

namespace aq::testing {

/// A global 1° raster: elevation = -1000 - 20·φ + 300·sin(λ) metres (sample points on whole degrees).
inline raster::Bathymetry synthetic_bathymetry() {
  const std::int64_t nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r) {
    for (std::int64_t c = 0; c < nc; ++c) {
      const double lon = -180.0 + static_cast<double>(c), lat = -90.0 + static_cast<double>(r);
      v[static_cast<std::size_t>(r * nc + c)] =
          static_cast<float>(-1000.0 - 20.0 * lat + 300.0 * std::sin(lon * 3.14159265358979 / 180.0));
    }
  }
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, 1.0, 1.0);
}

/// Leaves and mesh of a filled set with the given options.
struct Built {
  std::vector<quadtree::Leaf> leaves;
  mesh::Mesh mesh;
};
inline Built build_all(const Bitmap& filled, const Lattice& lat, const config::QuadtreeOptions& q,
                       const config::MeshOptions& mo, const PoleRotation& rot, const raster::Bathymetry& bathy,
                       Report* report = nullptr) {
  Built b;
  b.leaves = quadtree::build_leaves(filled, lat, q, rot, &bathy, Logger::null(), report);
  b.mesh = mesh::build_mesh(b.leaves, lat, rot, bathy, mo, Logger::null(), report);
  return b;
}

/// Same doubles bit for bit (NaN equals NaN).
inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

inline void expect_same_mesh(const mesh::Mesh& a, const mesh::Mesh& b) {
  EXPECT_EQ(a.node_i, b.node_i);
  EXPECT_EQ(a.node_j, b.node_j);
  EXPECT_TRUE(same_bits(a.lon_deg, b.lon_deg));
  EXPECT_TRUE(same_bits(a.lat_deg, b.lat_deg));
  EXPECT_TRUE(same_bits(a.rlon_deg, b.rlon_deg));
  EXPECT_TRUE(same_bits(a.rlat_deg, b.rlat_deg));
  EXPECT_TRUE(same_bits(a.depth_m, b.depth_m));
  EXPECT_EQ(a.node_flags, b.node_flags);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_level, b.triangle_level);
  EXPECT_EQ(a.triangle_square, b.triangle_square);
  EXPECT_EQ(a.squares, b.squares);
  EXPECT_EQ(a.square_level, b.square_level);
  EXPECT_EQ(a.square_midside, b.square_midside);
  EXPECT_EQ(a.boundary_edges, b.boundary_edges);
  EXPECT_EQ(a.boundary_edge_loop, b.boundary_edge_loop);
  ASSERT_EQ(a.loops.size(), b.loops.size());
  for (std::size_t l = 0; l < a.loops.size(); ++l) {
    EXPECT_EQ(a.loops[l].nodes, b.loops[l].nodes);
    EXPECT_EQ(a.loops[l].outer, b.loops[l].outer);
    EXPECT_EQ(a.loops[l].pole, b.loops[l].pole);
  }
  EXPECT_EQ(a.pinch_nodes, b.pinch_nodes);
}

}  // namespace aq::testing

// SPDX-License-Identifier: GPL-3.0-or-later
// Hand-made meshes for the writer tests (tests/unit/io, tests/clients). A mesh is built from a
// list of quadtree leaves on a tiny lattice the way ARCHITECTURE §4.5–4.6 describes (corner
// nodes, midside nodes where a finer leaf's corner sits on a side, centre-node templates,
// "ne" diagonals, boundary edges with the wet area on the left, loops), so the writers can be
// tested before and independently of the real mesh builder.
//
// tiny_mesh(): lattice Δ0 = 45°, L = 1 (pixels of 22.5°, nx = 16, ny = 8, λ0 = -180):
//
//   J=8  . . . . . . . p-p-p . . . . . .     P, P2: level 1 at I 7..9, J 7..8, touching the
//   J=7  . . . . . . . +-+-+ . . . . . .            North-pole row (3 pole nodes)
//   J=4  . . +---+-+ . . . . . . . . . .
//   J=3  . . | c m-+ . . . . . . . . . .     A: level 0 at I 2..4, J 2..4 with a hanging node
//   J=2  . . +---+-+ . . . . . . . . . .        m = (4,3) (B1, B2: level 1 east of it), centre c
//   J=3  +-+ . . . . . . . . . . . . . +     C: level 1 at I 15..16 (crosses the seam), and
//   J=2  +-+ . . . . . . . . . . . . . +     D: level 1 at I 0..1 (shares the seam nodes with C)
//        I=0                           I=15
//
// Counts: 21 nodes, 17 triangles, 7 squares, 19 boundary edges in 3 loops (the A+B loop, 7 edges,
// is the outer one), 2 seam duplicates ((0,2), (0,3)), 3 pole nodes (2 merged away in 3-D, which
// drops 2 triangles and turns P, P2 into triangles). Elevation at (I, J) is -(100 + 10 I + J) m.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "mesh/mesh.hpp"

namespace aq::testing {

struct LeafSpec {
  int level;
  std::int64_t i, j;  ///< lower-left lattice vertex
};

/// Elevation the test meshes put at lattice vertex (I, J).
inline double test_elevation_m(std::int64_t i, std::int64_t j) {
  return -(100.0 + 10.0 * static_cast<double>(i) + static_cast<double>(j));
}

inline mesh::Mesh make_leaf_mesh(const Lattice& lattice, const std::vector<LeafSpec>& leaves,
                                 bool with_triangles = true, const mesh::RotationInfo& rotation = {}) {
  using Vertex = std::pair<std::int64_t, std::int64_t>;  // (J, I): sorts like the node numbering
  auto wrap = [&](std::int64_t i) { return ((i % lattice.nx) + lattice.nx) % lattice.nx; };
  auto vtx = [&](std::int64_t i, std::int64_t j) { return Vertex{j, wrap(i)}; };

  std::set<Vertex> corners;
  for (const auto& l : leaves) {
    const std::int64_t s = lattice.pixels_per_square(l.level);
    for (const auto& v : {vtx(l.i, l.j), vtx(l.i + s, l.j), vtx(l.i + s, l.j + s), vtx(l.i, l.j + s)})
      corners.insert(v);
  }
  struct Leaf {
    std::array<Vertex, 4> c;
    std::array<bool, 4> has_mid{};
    std::array<Vertex, 4> mid;
    Vertex centre;
    int level;
  };
  std::vector<Leaf> ls;
  std::set<Vertex> all = corners, mids, centres;
  for (const auto& l : leaves) {
    const std::int64_t s = lattice.pixels_per_square(l.level), h = s / 2;
    Leaf f;
    f.level = l.level;
    f.c = {vtx(l.i, l.j), vtx(l.i + s, l.j), vtx(l.i + s, l.j + s), vtx(l.i, l.j + s)};
    f.mid = {vtx(l.i + h, l.j), vtx(l.i + s, l.j + h), vtx(l.i + h, l.j + s), vtx(l.i, l.j + h)};
    f.centre = vtx(l.i + h, l.j + h);
    bool any = false;
    for (int k = 0; k < 4; ++k) {
      f.has_mid[k] = s >= 2 && corners.count(f.mid[k]) > 0;
      if (f.has_mid[k]) mids.insert(f.mid[k]);
      any = any || f.has_mid[k];
    }
    if (any && with_triangles) {
      all.insert(f.centre);
      centres.insert(f.centre);
    }
    ls.push_back(f);
  }

  mesh::Mesh m;
  m.lattice = lattice;
  m.rotation = rotation;
  std::map<Vertex, NodeId> id;
  for (const auto& v : all) {
    const auto n = static_cast<NodeId>(id.size());
    id[v] = n;
    m.node_i.push_back(v.second);
    m.node_j.push_back(v.first);
    const double rlon = lattice.lon_of(v.second), rlat = lattice.lat_of(v.first);
    m.rlon_deg.push_back(rlon);
    m.rlat_deg.push_back(rlat);
    double lon = rlon, lat = rlat;
    if (rotation.enabled)
      PoleRotation(rotation.pole_lon_deg, rotation.pole_lat_deg).to_geographic(rlon, rlat, lon, lat);
    m.lon_deg.push_back(lon);
    m.lat_deg.push_back(lat);
    m.depth_m.push_back(test_elevation_m(v.second, v.first));
    std::uint8_t flags = 0;
    if (mids.count(v)) flags |= mesh::kNodeMidside;
    if (centres.count(v)) flags |= mesh::kNodeCentre;
    if (v.first == 0 || v.first == lattice.ny) flags |= mesh::kNodePole;
    if (v.second == 0) flags |= mesh::kNodeSeam;
    m.node_flags.push_back(flags);
  }

  std::vector<std::array<NodeId, 3>> tris;
  for (std::size_t s = 0; s < ls.size(); ++s) {
    const Leaf& f = ls[s];
    std::array<NodeId, 4> c{}, ms{-1, -1, -1, -1};
    for (int k = 0; k < 4; ++k) {
      c[k] = id.at(f.c[k]);
      if (f.has_mid[k]) ms[k] = id.at(f.mid[k]);
    }
    m.squares.push_back(c);
    m.square_level.push_back(static_cast<std::uint8_t>(f.level));
    m.square_midside.push_back(ms);
    const bool any = f.has_mid[0] || f.has_mid[1] || f.has_mid[2] || f.has_mid[3];
    auto add = [&](NodeId a, NodeId b, NodeId cc) {
      tris.push_back({a, b, cc});
      m.triangle_level.push_back(static_cast<std::uint8_t>(f.level));
      m.triangle_square.push_back(static_cast<ElementId>(s));
    };
    if (!any) {
      add(c[0], c[1], c[2]);
      add(c[0], c[2], c[3]);
    } else {
      const NodeId ctr = with_triangles ? id.at(f.centre) : -1;
      for (int k = 0; k < 4; ++k) {
        if (ms[k] >= 0) {
          add(c[k], ms[k], ctr);
          add(ms[k], c[(k + 1) % 4], ctr);
        } else {
          add(c[k], c[(k + 1) % 4], ctr);
        }
      }
    }
  }

  // Boundary: the polygon half-edges of the squares (conforming through midside nodes) that
  // have no opposite half-edge, chained into loops.
  std::set<std::pair<NodeId, NodeId>> half;
  for (std::size_t s = 0; s < m.squares.size(); ++s) {
    std::vector<NodeId> poly;
    for (int k = 0; k < 4; ++k) {
      poly.push_back(m.squares[s][k]);
      if (m.square_midside[s][k] >= 0) poly.push_back(m.square_midside[s][k]);
    }
    for (std::size_t k = 0; k < poly.size(); ++k) half.insert({poly[k], poly[(k + 1) % poly.size()]});
  }
  std::vector<std::pair<NodeId, NodeId>> bnd;
  for (const auto& e : half)
    if (!half.count({e.second, e.first})) bnd.push_back(e);
  std::vector<bool> used(bnd.size(), false);
  for (std::size_t start = 0; start < bnd.size(); ++start) {
    if (used[start]) continue;
    mesh::BoundaryLoop loop;
    const auto loop_id = static_cast<std::int32_t>(m.loops.size());
    std::size_t cur = start;
    while (!used[cur]) {
      used[cur] = true;
      loop.nodes.push_back(bnd[cur].first);
      m.boundary_edges.push_back({bnd[cur].first, bnd[cur].second});
      m.boundary_edge_loop.push_back(loop_id);
      for (std::size_t k = 0; k < bnd.size(); ++k) {
        if (!used[k] && bnd[k].first == bnd[cur].second) {
          cur = k;
          break;
        }
      }
    }
    m.loops.push_back(loop);
  }
  std::size_t outer = 0;
  for (std::size_t l = 0; l < m.loops.size(); ++l)
    if (m.loops[l].nodes.size() > m.loops[outer].nodes.size()) outer = l;
  if (!m.loops.empty()) m.loops[outer].outer = true;
  for (const auto& e : m.boundary_edges) {
    m.node_flags[e[0]] |= mesh::kNodeBoundary;
    m.node_flags[e[1]] |= mesh::kNodeBoundary;
  }
  if (with_triangles) {
    m.triangles = tris;
  } else {
    m.triangle_level.clear();
    m.triangle_square.clear();
  }
  return m;
}

/// The lattice of tiny_mesh(): Δ0 = 45°, L = 1, λ0 = -180.
inline Lattice tiny_lattice() { return Lattice::make(45.0, 1, -180.0); }

/// The hand-made mesh drawn at the top of this file.
inline mesh::Mesh tiny_mesh(bool with_triangles = true, const mesh::RotationInfo& rotation = {}) {
  return make_leaf_mesh(tiny_lattice(), {{0, 2, 2}, {1, 4, 2}, {1, 4, 3}, {1, 15, 2}, {1, 0, 2}, {1, 7, 7}, {1, 8, 7}},
                        with_triangles, rotation);
}

/// Δ0 = 10°, L = 1 (5° pixels): level-0 squares on the rows 70–80°N and 80–90°N all round, one of
/// the lower ones split into four level-1 squares (so ring 0 of a pole cap has a midside node);
/// without `full_band` the polar row has a gap at I = 40..41 (so the pole row is merged instead).
inline mesh::Mesh arctic_mesh(bool full_band = true) {
  const Lattice lat = Lattice::make(10.0, 1, -180.0);
  std::vector<LeafSpec> leaves;
  for (std::int64_t i = 0; i < lat.nx; i += 2) {
    if (i == 20) {
      for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}}) leaves.push_back({1, i + di, 32 + dj});
    } else {
      leaves.push_back({0, i, 32});
    }
    if (full_band || i != 40) leaves.push_back({0, i, 34});
  }
  return make_leaf_mesh(lat, leaves);
}

/// A larger mesh for timing and real-reader tests: every level-L pixel of the lattice rows
/// j0 <= J < j1 (all columns, so elements cross the seam), at level L.
inline mesh::Mesh band_mesh(const Lattice& lattice, std::int64_t j0, std::int64_t j1) {
  std::vector<LeafSpec> leaves;
  for (std::int64_t j = j0; j < j1; ++j)
    for (std::int64_t i = 0; i < lattice.nx; ++i) leaves.push_back({lattice.levels, i, j});
  return make_leaf_mesh(lattice, leaves);
}

/// A large regular mesh built straight into the arrays (for timing writers on ~10^7 triangles):
/// every level-L pixel of rows j0 <= J < j1 around the globe, split by the "ne" diagonal. Two
/// boundary loops (the row J = j0, outer, and the row J = j1, the pole loop when j1 = ny).
inline mesh::Mesh regular_band_mesh(const Lattice& lattice, std::int64_t j0, std::int64_t j1) {
  mesh::Mesh m;
  m.lattice = lattice;
  const std::int64_t nx = lattice.nx, rows = j1 - j0 + 1;
  auto id = [&](std::int64_t i, std::int64_t j) { return (j - j0) * nx + ((i % nx) + nx) % nx; };
  const auto n = static_cast<std::size_t>(rows * nx);
  m.node_i.resize(n);
  m.node_j.resize(n);
  m.lon_deg.resize(n);
  m.lat_deg.resize(n);
  m.depth_m.resize(n);
  m.node_flags.resize(n);
  for (std::int64_t j = j0; j <= j1; ++j)
    for (std::int64_t i = 0; i < nx; ++i) {
      const auto k = static_cast<std::size_t>(id(i, j));
      m.node_i[k] = i;
      m.node_j[k] = j;
      m.lon_deg[k] = lattice.lon_of(i);
      m.lat_deg[k] = lattice.lat_of(j);
      m.depth_m[k] = test_elevation_m(i, j);
      m.node_flags[k] =
          static_cast<std::uint8_t>((j == j0 || j == j1 ? mesh::kNodeBoundary : 0) |
                                    (j == 0 || j == lattice.ny ? mesh::kNodePole : 0) | (i == 0 ? mesh::kNodeSeam : 0));
    }
  m.rlon_deg = m.lon_deg;
  m.rlat_deg = m.lat_deg;
  const auto level = static_cast<std::uint8_t>(lattice.levels);
  const auto sq = static_cast<std::size_t>((j1 - j0) * nx);
  m.squares.reserve(sq);
  m.triangles.reserve(2 * sq);
  for (std::int64_t j = j0; j < j1; ++j)
    for (std::int64_t i = 0; i < nx; ++i) {
      const std::array<NodeId, 4> c{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      m.triangles.push_back({c[0], c[1], c[2]});
      m.triangles.push_back({c[0], c[2], c[3]});
      m.triangle_square.push_back(static_cast<ElementId>(m.squares.size()));
      m.triangle_square.push_back(static_cast<ElementId>(m.squares.size()));
      m.squares.push_back(c);
    }
  m.square_level.assign(sq, level);
  m.square_midside.assign(sq, {-1, -1, -1, -1});
  m.triangle_level.assign(2 * sq, level);
  mesh::BoundaryLoop bottom, top;
  bottom.outer = true;
  top.pole = j1 == lattice.ny;
  for (std::int64_t i = 0; i < nx; ++i) {
    m.boundary_edges.push_back({id(i, j0), id(i + 1, j0)});
    m.boundary_edge_loop.push_back(0);
    bottom.nodes.push_back(id(i, j0));
  }
  for (std::int64_t i = nx; i > 0; --i) {
    m.boundary_edges.push_back({id(i, j1), id(i - 1, j1)});
    m.boundary_edge_loop.push_back(1);
    top.nodes.push_back(id(i, j1));
  }
  m.loops = {bottom, top};
  return m;
}

}  // namespace aq::testing

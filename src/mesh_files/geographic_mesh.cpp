// SPDX-License-Identifier: GPL-3.0-or-later
// The geographic mesh: pole cap or pole merge (see geographic_mesh.hpp).
#include "mesh_files/geographic_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/rotation.hpp"
#include "core/types.hpp"
#include "mesh/boundaries.hpp"
#include "mesh/pole_cap.hpp"
#include "mesh_files/pole_merge.hpp"

namespace aq::io {

namespace {

using Vec3 = std::array<double, 3>;

// One pole of the lattice system: its row, the level-0 row next to it and the test of whether
// a square lies in that row.
struct PoleRows {
  bool north = true;
  std::int64_t pole_j = 0;     // J of the pole row
  std::int64_t ring_j = 0;     // J of ring 0: the far side of the level-0 row at the pole
  std::int64_t outside_j = 0;  // the pixel row just outside the level-0 row
  [[nodiscard]] bool in_band(std::int64_t j_lo, std::int64_t side) const {
    return north ? j_lo >= ring_j : j_lo + side <= ring_j;
  }
  [[nodiscard]] bool beyond_ring(std::int64_t j) const { return north ? j > ring_j : j < ring_j; }
};

PoleRows pole_rows(const Lattice& lat, bool north) {
  const std::int64_t p = lat.pixels_per_square(0);
  if (north) return {true, lat.ny, lat.ny - p, lat.ny - p - 1};
  return {false, 0, p, p};
}

// Why the cap cannot be used at this pole (empty: it can).
std::string cap_obstacle(const mesh::Mesh& m, const PoleRows& r) {
  const Lattice& lat = m.lattice;
  if (m.triangles.empty()) return "the mesh has no triangles";
  if (lat.ny < 2 * lat.pixels_per_square(0) + 1) return "the lattice has fewer than three level-0 rows";
  std::int64_t band_px = 0, outside_px = 0;
  for (ElementId s = 0; s < m.square_count(); ++s) {
    const auto su = static_cast<std::size_t>(s);
    const std::int64_t side = lat.pixels_per_square(m.square_level[su]);
    const std::int64_t j_lo = m.node_j[static_cast<std::size_t>(m.squares[su][0])];
    if (r.in_band(j_lo, side)) band_px += side * side;
    if (j_lo <= r.outside_j && r.outside_j < j_lo + side) outside_px += side;
  }
  const std::int64_t band_want = lat.nx * lat.pixels_per_square(0);
  if (band_px != band_want)
    return fmt::format("the level-0 row at the pole is not all ocean ({} of {} pixels)", band_px, band_want);
  if (outside_px != lat.nx)
    return fmt::format("the pixel row next to the level-0 row at the pole is not all ocean ({} of {} pixels)",
                       outside_px, lat.nx);
  for (const auto& e : m.boundary_edges) {
    const std::int64_t ja = m.node_j[static_cast<std::size_t>(e[0])], jb = m.node_j[static_cast<std::size_t>(e[1])];
    if ((r.beyond_ring(ja) || r.beyond_ring(jb)) && !(ja == r.pole_j && jb == r.pole_j))
      return "a coast reaches the level-0 row at the pole";
  }
  return {};
}

}  // namespace

GeographicMesh::GeographicMesh(const mesh::Mesh& lm, ElementKinds kinds, const ElevationSampler& elevation)
    : lattice_(lm) {
  const bool squares_out = kinds != ElementKinds::kTriangles;
  const Lattice& lat = lm.lattice;
  const auto nn = static_cast<std::size_t>(lm.node_count());

  // Which poles have a pole row, and what is done there.
  std::vector<PoleRows> caps;
  bool merge = false;
  for (const bool north : {false, true}) {
    const PoleRows r = pole_rows(lat, north);
    bool has_row = false;
    for (std::size_t n = 0; n < nn && !has_row; ++n) has_row = lm.node_j[n] == r.pole_j;
    if (!has_row) continue;
    PoleChange c;
    c.north = north;
    c.reason = squares_out ? fmt::format(
                                 "mesh.elements = \"{}\" writes the squares, which a cap of triangles "
                                 "cannot replace",
                                 kinds)
                           : cap_obstacle(lm, r);
    c.method = c.reason.empty() ? PoleMethod::kCap : PoleMethod::kMerge;
    if (c.reason.empty()) {
      caps.push_back(r);
    } else {
      merge = true;
    }
    poles_.push_back(c);
  }
  if (poles_.empty()) return;
  auto change_of = [&](bool north) -> PoleChange& {
    for (auto& c : poles_)
      if (c.north == north) return c;
    throw InternalError("geographic mesh: pole without a change record");
  };

  // Triangles inside a capped band, and the nodes the kept triangles use.
  std::vector<std::int8_t> tri_cap(lm.triangles.size(), -1);  // index into caps, or -1
  std::vector<char> used(nn, 0);
  for (std::size_t t = 0; t < lm.triangles.size(); ++t) {
    const auto sq = static_cast<std::size_t>(lm.triangle_square[t]);
    const std::int64_t side = lat.pixels_per_square(lm.square_level[sq]);
    const std::int64_t j_lo = lm.node_j[static_cast<std::size_t>(lm.squares[sq][0])];
    for (std::size_t k = 0; k < caps.size(); ++k)
      if (caps[k].in_band(j_lo, side)) tri_cap[t] = static_cast<std::int8_t>(k);
    if (tri_cap[t] < 0)
      for (const NodeId v : lm.triangles[t]) used[static_cast<std::size_t>(v)] = 1;
  }
  // Node representative: itself, -1 when removed by a cap, or the merged pole node.
  std::vector<NodeId> rep(nn);
  std::optional<PoleMerge> pole_merge;
  if (merge) pole_merge.emplace(lm);
  for (std::size_t n = 0; n < nn; ++n) {
    rep[n] = static_cast<NodeId>(n);
    const std::int64_t j = lm.node_j[n];
    for (const auto& r : caps)
      if ((r.north ? j >= r.ring_j : j <= r.ring_j) && used[n] == 0) rep[n] = -1;
    if (rep[n] >= 0 && pole_merge && (j == 0 || j == lat.ny)) {
      rep[n] = pole_merge->source(pole_merge->map(static_cast<NodeId>(n)));
      if (rep[n] != static_cast<NodeId>(n)) ++change_of(j == lat.ny).removed_nodes;
    }
    if (rep[n] < 0) ++change_of(j >= lat.ny / 2).removed_nodes;
  }
  // The caps' rings (old ids, ascending I: the node order is by (J, I)) and triangulations, first:
  // the arrays below are reserved for exactly the kept and the added nodes and triangles (a
  // capacity of the lattice mesh's counts, which the cap exceeds, doubled every array at the
  // first cap node: 2.1 GB more at 15").
  std::vector<std::vector<NodeId>> rings(caps.size());
  std::vector<mesh::PoleCap> cap_meshes;
  std::size_t added_nodes = 0, added_triangles = 0;
  for (std::size_t k = 0; k < caps.size(); ++k) {
    const PoleRows& r = caps[k];
    for (std::size_t n = 0; n < nn; ++n)
      if (lm.node_j[n] == r.ring_j && used[n] != 0) rings[k].push_back(static_cast<NodeId>(n));
    std::vector<double> ring_lon;
    for (const NodeId n : rings[k]) ring_lon.push_back(lat.lon_of(lm.node_i[static_cast<std::size_t>(n)]));
    cap_meshes.push_back(mesh::make_pole_cap(ring_lon, lat.lat_of(r.ring_j), r.north));
    added_nodes += cap_meshes.back().rlon_deg.size();
    added_triangles += cap_meshes.back().triangles.size();
  }
  std::size_t kept_nodes = 0, kept_triangles = added_triangles;  // at most: a merge drops a few more
  for (std::size_t n = 0; n < nn; ++n) kept_nodes += rep[n] == static_cast<NodeId>(n);
  for (const std::int8_t c : tri_cap) kept_triangles += c < 0;
  std::vector<NodeId> new_id(nn, -1);
  mesh::Mesh g;
  g.lattice = lm.lattice;
  g.rotation = lm.rotation;
  g.floodplain_top_m = lm.floodplain_top_m;
  for (auto* v : {&g.node_i, &g.node_j}) v->reserve(kept_nodes + added_nodes);
  for (auto* v : {&g.lon_deg, &g.lat_deg, &g.rlon_deg, &g.rlat_deg, &g.depth_m}) v->reserve(kept_nodes + added_nodes);
  g.node_flags.reserve(kept_nodes + added_nodes);
  g.triangles.reserve(kept_triangles);
  g.triangle_level.reserve(kept_triangles);
  if (squares_out) g.triangle_square.reserve(kept_triangles);  // triangles alone have no squares to point to
  source_triangle_.reserve(kept_triangles);
  auto push_node = [&](std::int64_t i, std::int64_t j, double lon, double lat_deg, double rlon, double rlat,
                       double depth, std::uint8_t flags) {
    g.node_i.push_back(i);
    g.node_j.push_back(j);
    g.lon_deg.push_back(lon);
    g.lat_deg.push_back(lat_deg);
    g.rlon_deg.push_back(rlon);
    g.rlat_deg.push_back(rlat);
    g.depth_m.push_back(depth);
    g.node_flags.push_back(flags);
  };
  for (std::size_t n = 0; n < nn; ++n) {
    if (rep[n] != static_cast<NodeId>(n)) continue;
    new_id[n] = static_cast<NodeId>(g.node_i.size());
    push_node(lm.node_i[n], lm.node_j[n], lm.lon_deg[n], lm.lat_deg[n], lm.rlon_deg[n], lm.rlat_deg[n], lm.depth_m[n],
              lm.node_flags[n]);
  }
  for (std::size_t n = 0; n < nn; ++n)
    if (rep[n] >= 0 && rep[n] != static_cast<NodeId>(n)) new_id[n] = new_id[static_cast<std::size_t>(rep[n])];
  std::vector<NodeId>().swap(rep);  // new_id says it all now

  // Kept triangles (those a merge makes degenerate are dropped).
  for (std::size_t t = 0; t < lm.triangles.size(); ++t) {
    const auto& tr = lm.triangles[t];
    const std::array<NodeId, 3> o{new_id[static_cast<std::size_t>(tr[0])], new_id[static_cast<std::size_t>(tr[1])],
                                  new_id[static_cast<std::size_t>(tr[2])]};
    if (tri_cap[t] >= 0) {
      ++change_of(caps[static_cast<std::size_t>(tri_cap[t])].north).removed_triangles;
      continue;
    }
    if (o[0] == o[1] || o[1] == o[2] || o[2] == o[0]) {
      ++change_of(lm.node_j[static_cast<std::size_t>(tr[0])] >= lat.ny / 2).removed_triangles;
      continue;
    }
    g.triangles.push_back(o);
    g.triangle_level.push_back(lm.triangle_level[t]);
    if (squares_out) g.triangle_square.push_back(lm.triangle_square[t]);
    source_triangle_.push_back(static_cast<ElementId>(t));
  }
  // Squares (written only with mesh.elements = squares or both, where the poles are merged): a
  // square on a pole row keeps its four corner slots with the merged pole node twice (it is a
  // triangle on the Earth); a midside node merged into a corner is no longer a hanging node.
  if (squares_out) {
    g.squares.reserve(lm.squares.size());
    for (std::size_t s = 0; s < lm.squares.size(); ++s) {
      std::array<NodeId, 4> c{};
      for (std::size_t k = 0; k < 4; ++k) c[k] = new_id[static_cast<std::size_t>(lm.squares[s][k])];
      g.squares.push_back(c);
      g.square_level.push_back(lm.square_level[s]);
      if (lm.square_midside.empty()) continue;
      std::array<NodeId, 4> mid{};
      for (std::size_t k = 0; k < 4; ++k) {
        const NodeId m = lm.square_midside[s][k];
        mid[k] = m < 0 ? -1 : new_id[static_cast<std::size_t>(m)];
        if (mid[k] == c[k] || mid[k] == c[(k + 1) % 4]) mid[k] = -1;
      }
      g.square_midside.push_back(mid);
    }
  }

  // The caps.
  const PoleRotation rotation =
      lm.rotation.enabled ? PoleRotation(lm.rotation.pole_lon_deg, lm.rotation.pole_lat_deg) : PoleRotation();
  std::vector<char> cap_node;  // node of a cap or of its ring 0, by new id
  std::vector<mesh::BoundaryLoop> island_loops;
  std::vector<std::array<NodeId, 2>> island_edges;  // in loop order, loop after loop
  for (std::size_t k = 0; k < caps.size(); ++k) {
    const PoleRows& r = caps[k];
    PoleChange& c = change_of(r.north);
    const std::vector<NodeId>& ring = rings[k];
    const mesh::PoleCap& cap = cap_meshes[k];
    const auto first = static_cast<NodeId>(g.node_i.size());
    const std::size_t added = cap.rlon_deg.size();
    std::vector<double> lon(added), la(added), elev(added, 0.0);
    for (std::size_t a = 0; a < added; ++a) {
      double x = cap.rlon_deg[a], y = cap.rlat_deg[a];
      if (!rotation.identity()) rotation.to_geographic(cap.rlon_deg[a], cap.rlat_deg[a], x, y);
      lon[a] = wrap_lon_deg(x, lat.lon0_deg);
      la[a] = y;
    }
    elevation(lon, la, elev);
    for (std::size_t a = 0; a < added; ++a) {
      push_node(-1, -1, lon[a], la[a], wrap_lon_deg(cap.rlon_deg[a], lat.lon0_deg), cap.rlat_deg[a], elev[a],
                mesh::kNodeCap);
    }
    const auto n0 = static_cast<NodeId>(ring.size());
    auto id = [&](NodeId v) {
      return v < n0 ? new_id[static_cast<std::size_t>(ring[static_cast<std::size_t>(v)])] : first + (v - n0);
    };
    cap_node.resize(g.node_i.size(), 0);
    for (const NodeId n : ring) cap_node[static_cast<std::size_t>(new_id[static_cast<std::size_t>(n)])] = 1;
    for (std::size_t a = 0; a < added; ++a) cap_node[static_cast<std::size_t>(first) + a] = 1;

    // Checks and quality, on the sphere of the lattice system.
    auto lattice_vec = [&](NodeId o) {
      return unit_vector_deg(g.rlon_deg[static_cast<std::size_t>(o)], g.rlat_deg[static_cast<std::size_t>(o)]);
    };
    double cap_area = 0.0, min_angle = 180.0, max_angle = 0.0;
    for (const auto& t : cap.triangles) {
      const std::array<NodeId, 3> o{id(t[0]), id(t[1]), id(t[2])};
      const Vec3 a = lattice_vec(o[0]), b = lattice_vec(o[1]), cc = lattice_vec(o[2]);
      const double area = spherical_triangle_area(a, b, cc);
      if (!(area > 0.0)) {
        throw InternalError(fmt::format("pole cap: triangle ({}, {}, {}) is not anticlockwise on the sphere (area {})",
                                        o[0], o[1], o[2], area));
      }
      cap_area += area;
      for (const double ang : spherical_angles_deg(a, b, cc)) {
        min_angle = std::min(min_angle, ang);
        max_angle = std::max(max_angle, ang);
      }
      g.triangles.push_back(o);
      g.triangle_level.push_back(0);
      source_triangle_.push_back(-1);
    }
    double replaced = 0.0;
    for (std::size_t t = 0; t < lm.triangles.size(); ++t) {
      if (tri_cap[t] != static_cast<std::int8_t>(k)) continue;
      std::array<Vec3, 3> v{};
      for (std::size_t a = 0; a < 3; ++a) {
        const auto n = static_cast<std::size_t>(lm.triangles[t][a]);
        v[a] = unit_vector_deg(lm.rlon_deg[n], lm.rlat_deg[n]);
      }
      replaced += spherical_triangle_area(v[0], v[1], v[2]);
    }
    // The island: its nodes become boundary nodes, its ring a loop (wet area on the left).
    const Vec3 pole = unit_vector_deg(0.0, r.north ? 90.0 : -90.0);
    double island_area = 0.0;
    mesh::BoundaryLoop island;
    const std::size_t ni = cap.island.size();
    for (std::size_t a = 0; a < ni; ++a) {
      const NodeId u = id(cap.island[a]), v = id(cap.island[(a + 1) % ni]);
      island.nodes.push_back(u);
      island_edges.push_back({u, v});
      g.node_flags[static_cast<std::size_t>(u)] |= mesh::kNodeBoundary;
      island_area -= spherical_triangle_area(pole, lattice_vec(u), lattice_vec(v));
    }
    island_area = std::abs(island_area);
    island_loops.push_back(std::move(island));
    c.area_relative_change = std::abs(cap_area + island_area - replaced) / replaced;
    if (!(c.area_relative_change <= 1e-9)) {
      throw InternalError(
          fmt::format("pole cap: area {} sr + island {} sr differs from the area replaced {} sr by {:.2e}", cap_area,
                      island_area, replaced, c.area_relative_change));
    }
    c.island_nodes = static_cast<std::int64_t>(ni);
    c.island_radius_deg = cap.island_radius_deg;
    c.island_area_km2 = island_area * kAuthalicRadiusKm * kAuthalicRadiusKm;
    c.ring_lat_deg = lat.lat_of(r.ring_j);
    c.ring_nodes = static_cast<std::int64_t>(ring.size());
    c.added_nodes = static_cast<std::int64_t>(added);
    c.added_triangles = static_cast<std::int64_t>(cap.triangles.size());
    c.rings = cap.rings;
    c.min_angle_deg = min_angle;
    c.max_angle_deg = max_angle;
  }
  // Valences around the cap nodes (all triangles: ring-0 nodes also have kept ones).
  if (!caps.empty()) {
    std::vector<int> valence(g.node_i.size(), 0);
    for (const auto& t : g.triangles)
      for (const NodeId v : t) ++valence[static_cast<std::size_t>(v)];
    for (std::size_t n = 0; n < cap_node.size(); ++n) {
      if (cap_node[n] == 0) continue;
      const bool north = (g.node_j[n] < 0 ? g.rlat_deg[n] : lat.lat_of(g.node_j[n])) > 0.0;
      PoleChange& c = change_of(north);
      c.max_valence = std::max(c.max_valence, valence[n]);
    }
  }

  // Boundary: edges and loops through the new ids; edges that vanish (the polar loop of a cap,
  // a merged pole row) go, and so does a loop left with fewer than 3 nodes.
  std::vector<std::int32_t> loop_id(lm.loops.size(), -1);
  for (std::size_t l = 0; l < lm.loops.size(); ++l) {
    mesh::BoundaryLoop loop;
    loop.outer = lm.loops[l].outer;
    loop.pole = lm.loops[l].pole;
    for (const NodeId v : lm.loops[l].nodes) {
      const NodeId o = new_id[static_cast<std::size_t>(v)];
      if (o < 0 || (!loop.nodes.empty() && loop.nodes.back() == o)) continue;
      loop.nodes.push_back(o);
    }
    while (loop.nodes.size() > 1 && loop.nodes.back() == loop.nodes.front()) loop.nodes.pop_back();
    if (loop.nodes.size() < 3) continue;
    loop_id[l] = static_cast<std::int32_t>(g.loops.size());
    g.loops.push_back(std::move(loop));
  }
  for (std::size_t e = 0; e < lm.boundary_edges.size(); ++e) {
    const NodeId a = new_id[static_cast<std::size_t>(lm.boundary_edges[e][0])];
    const NodeId b = new_id[static_cast<std::size_t>(lm.boundary_edges[e][1])];
    const std::int32_t l = lm.boundary_edge_loop.empty() ? -1 : lm.boundary_edge_loop[e];
    if (a < 0 || b < 0 || a == b || (l >= 0 && loop_id[static_cast<std::size_t>(l)] < 0)) continue;
    g.boundary_edges.push_back({a, b});
    g.boundary_edge_loop.push_back(l >= 0 ? loop_id[static_cast<std::size_t>(l)] : -1);
  }
  for (auto& loop : island_loops) {
    const auto l = static_cast<std::int32_t>(g.loops.size());
    for (std::size_t a = 0; a < loop.nodes.size(); ++a) g.boundary_edge_loop.push_back(l);
    g.loops.push_back(std::move(loop));
  }
  g.boundary_edges.insert(g.boundary_edges.end(), island_edges.begin(), island_edges.end());
  for (const NodeId p : lm.pinch_nodes) {
    const NodeId o = new_id[static_cast<std::size_t>(p)];
    if (o >= 0) g.pinch_nodes.push_back(o);
  }
  // A regional mesh reaching a pole row keeps its types: an edge stays open where it was open
  // (the polar island of a cap is an island; a merged pole row has no edges left).
  if (lm.typed) mesh::type_like(g, lm);
  owned_.emplace(std::move(g));
}

std::vector<std::string> GeographicMesh::describe() const {
  std::vector<std::string> lines;
  for (const auto& c : poles_) {
    const char* pole = c.north ? "North" : "South";
    if (c.method == PoleMethod::kCap) {
      lines.push_back(fmt::format(
          "{} pole: cap from ring 0 at {:g}° ({} nodes): {} triangles / {} nodes replaced by {} / {} in {} rings "
          "round an island of radius {:.2f}° ({:.0f} km²); min angle {:.1f}°, max valence {}",
          pole, c.ring_lat_deg, c.ring_nodes, c.removed_triangles, c.removed_nodes, c.added_triangles, c.added_nodes,
          c.rings, c.island_radius_deg, c.island_area_km2, c.min_angle_deg, c.max_valence));
    } else {
      lines.push_back(
          fmt::format("{} pole: pole row merged into one node ({} nodes merged, {} degenerate triangles "
                      "dropped) because {}",
                      pole, c.removed_nodes, c.removed_triangles, c.reason));
    }
  }
  return lines;
}

Json GeographicMesh::json() const {
  const mesh::Mesh& m = mesh();
  Json poles = Json::array();
  for (const auto& c : poles_) {
    Json p{{"pole", c.north ? "north" : "south"},
           {"method", std::string(name_of(c.method))},
           {"removed_nodes", c.removed_nodes},
           {"removed_triangles", c.removed_triangles}};
    if (c.method == PoleMethod::kCap) {
      p["ring_lat_deg"] = c.ring_lat_deg;
      p["ring_nodes"] = c.ring_nodes;
      p["added_nodes"] = c.added_nodes;
      p["added_triangles"] = c.added_triangles;
      p["rings"] = c.rings;
      p["island_nodes"] = c.island_nodes;
      p["island_radius_deg"] = c.island_radius_deg;
      p["island_area_km2"] = c.island_area_km2;
      p["max_valence"] = c.max_valence;
      p["min_angle_deg"] = std::round(c.min_angle_deg * 1000.0) / 1000.0;
      p["max_angle_deg"] = std::round(c.max_angle_deg * 1000.0) / 1000.0;
      p["area_relative_change"] = c.area_relative_change;
    } else {
      p["reason"] = c.reason;
    }
    poles.push_back(p);
  }
  Json j{{"nodes", m.node_count()}, {"triangles", m.triangle_count()}};
  if (!m.squares.empty()) j["squares"] = m.square_count();
  j["boundary_loops"] = m.loops.size();
  j["poles"] = poles;
  return j;
}

}  // namespace aq::io

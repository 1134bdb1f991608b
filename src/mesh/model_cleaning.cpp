// SPDX-License-Identifier: GPL-3.0-or-later
// Cleaning a triangle mesh for the models (see model_cleaning.hpp).
#include "mesh/model_cleaning.hpp"

#include "mesh/boundaries.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.hpp"

namespace aq::mesh {

namespace {

using Tri = std::array<NodeId, 3>;

// Triangles round each node, ascending: node n has tri[start[n] .. start[n+1]).
struct NodeTriangles {
  std::vector<std::int64_t> start;
  std::vector<ElementId> tri;
};

NodeTriangles node_triangles(const std::vector<Tri>& t, std::int64_t nn) {
  NodeTriangles a;
  a.start.assign(static_cast<std::size_t>(nn) + 1, 0);
  for (const auto& tr : t)
    for (const NodeId v : tr) {
      if (v < 0 || v >= nn) throw InternalError(fmt::format("mesh cleaning: node {} out of range", v));
      ++a.start[static_cast<std::size_t>(v) + 1];
    }
  std::partial_sum(a.start.begin(), a.start.end(), a.start.begin());
  a.tri.resize(t.size() * 3);
  std::vector<std::int64_t> cursor(a.start.begin(), a.start.end() - 1);
  for (std::size_t k = 0; k < t.size(); ++k)
    for (const NodeId v : t[k])
      a.tri[static_cast<std::size_t>(cursor[static_cast<std::size_t>(v)]++)] = static_cast<ElementId>(k);
  return a;
}

// Area (km², authalic sphere) of the geodesic triangle of nodes a, b, c (Van Oosterom & Strackee).
double area_km2(const Mesh& m, const Tri& t) {
  constexpr double kRadiusKm = 6371.0072, kRad = 3.14159265358979323846 / 180.0;
  std::array<std::array<double, 3>, 3> p{};
  for (std::size_t k = 0; k < 3; ++k) {
    const auto v = static_cast<std::size_t>(t[k]);
    const double lo = m.lon_deg[v] * kRad, la = m.lat_deg[v] * kRad;
    p[k] = {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
  }
  auto dot = [](const auto& u, const auto& w) { return u[0] * w[0] + u[1] * w[1] + u[2] * w[2]; };
  const std::array<double, 3> bc{p[1][1] * p[2][2] - p[1][2] * p[2][1], p[1][2] * p[2][0] - p[1][0] * p[2][2],
                                 p[1][0] * p[2][1] - p[1][1] * p[2][0]};
  const double det = dot(p[0], bc), den = 1.0 + dot(p[0], p[1]) + dot(p[1], p[2]) + dot(p[2], p[0]);
  return std::abs(2.0 * std::atan2(det, den)) * kRadiusKm * kRadiusKm;
}

bool has_node(const Tri& t, NodeId v) { return t[0] == v || t[1] == v || t[2] == v; }

// Kept triangles other than `self` on edge (a, b).
template <class Alive>
int edge_neighbours(const std::vector<Tri>& t, const NodeTriangles& around, const Alive& alive, ElementId self,
                    NodeId a, NodeId b) {
  int count = 0;
  for (std::int64_t k = around.start[static_cast<std::size_t>(a)]; k < around.start[static_cast<std::size_t>(a) + 1];
       ++k) {
    const ElementId u = around.tri[static_cast<std::size_t>(k)];
    if (u != self && alive(u) && has_node(t[static_cast<std::size_t>(u)], b)) ++count;
  }
  return count;
}

// The fans of kept triangles round node v: a fan id per triangle of around.tri[start[v]..),
// -1 for removed ones; returns the number of fans. Two triangles are in one fan when a chain of
// kept triangles round v, each sharing an edge (v, w) with the next, joins them.
template <class Alive>
int fans_of(const std::vector<Tri>& t, const NodeTriangles& around, const Alive& alive, NodeId v,
            std::vector<int>& fan) {
  const std::int64_t b = around.start[static_cast<std::size_t>(v)], e = around.start[static_cast<std::size_t>(v) + 1];
  const auto n = static_cast<std::size_t>(e - b);
  fan.assign(n, -1);
  int fans = 0;
  std::vector<std::size_t> stack;
  for (std::size_t s = 0; s < n; ++s) {
    if (fan[s] >= 0 || !alive(around.tri[static_cast<std::size_t>(b) + s])) continue;
    fan[s] = fans;
    stack.assign(1, s);
    while (!stack.empty()) {
      const std::size_t x = stack.back();
      stack.pop_back();
      const Tri& tx = t[static_cast<std::size_t>(around.tri[static_cast<std::size_t>(b) + x])];
      for (std::size_t y = 0; y < n; ++y) {
        if (fan[y] >= 0 || !alive(around.tri[static_cast<std::size_t>(b) + y])) continue;
        const Tri& ty = t[static_cast<std::size_t>(around.tri[static_cast<std::size_t>(b) + y])];
        bool shares = false;  // an edge (v, w): a second common node
        for (const NodeId w : tx)
          if (w != v && has_node(ty, w)) shares = true;
        if (!shares) continue;
        fan[y] = fans;
        stack.push_back(y);
      }
    }
    ++fans;
  }
  return fans;
}

// One pass over the kept triangles: fewer than two neighbours, boundary edges per node, edges of
// more than two triangles.
template <class Alive>
void scan(const std::vector<Tri>& t, const NodeTriangles& around, const Alive& alive, std::vector<ElementId>& lonely,
          std::vector<int>& boundary_edges_at, std::int64_t& shared_edges) {
  lonely.clear();
  std::fill(boundary_edges_at.begin(), boundary_edges_at.end(), 0);
  shared_edges = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const auto id = static_cast<ElementId>(k);
    if (!alive(id)) continue;
    int neighbours = 0;
    for (int e = 0; e < 3; ++e) {
      const NodeId a = t[k][static_cast<std::size_t>(e)], b = t[k][static_cast<std::size_t>((e + 1) % 3)];
      const int c = edge_neighbours(t, around, alive, id, a, b);
      neighbours += std::min(c, 1);
      if (c == 0) {
        ++boundary_edges_at[static_cast<std::size_t>(a)];
        ++boundary_edges_at[static_cast<std::size_t>(b)];
      }
      if (c > 1 && a < b) ++shared_edges;  // counted once per triangle on it; see find_model_defects
    }
    if (neighbours < 2) lonely.push_back(id);
  }
}

}  // namespace

ModelDefects find_model_defects(const std::vector<Tri>& t, std::int64_t node_count) {
  const NodeTriangles around = node_triangles(t, node_count);
  auto alive = [](ElementId) { return true; };
  std::vector<ElementId> lonely;
  std::vector<int> boundary(static_cast<std::size_t>(node_count), 0);
  ModelDefects d;
  std::int64_t shared_marks = 0;
  scan(t, around, alive, lonely, boundary, shared_marks);
  d.one_neighbour_triangles = static_cast<std::int64_t>(lonely.size());
  // An edge of m > 2 triangles is marked by each of them once (for a < b in its own order, or for
  // b < a): count the edges themselves.
  if (shared_marks > 0) {
    std::vector<std::pair<NodeId, NodeId>> edges;
    for (const auto& tr : t)
      for (int e = 0; e < 3; ++e) {
        const NodeId a = tr[static_cast<std::size_t>(e)], b = tr[static_cast<std::size_t>((e + 1) % 3)];
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    std::sort(edges.begin(), edges.end());
    for (std::size_t k = 0; k < edges.size();) {
      std::size_t j = k;
      while (j < edges.size() && edges[j] == edges[k]) ++j;
      if (j - k > 2) ++d.shared_edges;
      k = j;
    }
  }
  std::vector<int> fan;
  for (NodeId v = 0; v < node_count; ++v)
    if (boundary[static_cast<std::size_t>(v)] > 2 && fans_of(t, around, alive, v, fan) > 1) ++d.pinch_nodes;
  return d;
}

ModelMesh::ModelMesh(const Mesh& m) : input_(m) {
  const std::vector<Tri>& t = m.triangles;
  const std::int64_t nn = m.node_count();
  const NodeTriangles around = node_triangles(t, nn);
  std::vector<char> keep(t.size(), 1);
  auto alive = [&keep](ElementId u) { return keep[static_cast<std::size_t>(u)] != 0; };

  std::vector<ElementId> lonely;
  std::vector<int> boundary(static_cast<std::size_t>(nn), 0);
  std::vector<int> fan;
  std::int64_t shared = 0;
  for (;;) {
    scan(t, around, alive, lonely, boundary, shared);
    if (shared > 0)
      throw InternalError("mesh cleaning: an edge belongs to more than two triangles (the mesh is not a surface)");
    if (!lonely.empty()) {
      for (const ElementId u : lonely) keep[static_cast<std::size_t>(u)] = 0;
      stats_.one_neighbour_triangles += static_cast<std::int64_t>(lonely.size());
      ++stats_.rounds;
      continue;
    }
    std::int64_t resolved = 0;
    for (NodeId v = 0; v < nn; ++v) {
      if (boundary[static_cast<std::size_t>(v)] <= 2) continue;
      const int fans = fans_of(t, around, alive, v, fan);
      if (fans < 2) continue;
      // The largest fan stays; a tie goes to the fan first met in triangle order.
      std::vector<std::int64_t> size(static_cast<std::size_t>(fans), 0);
      for (const int f : fan)
        if (f >= 0) ++size[static_cast<std::size_t>(f)];
      const auto best = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
      const std::int64_t b = around.start[static_cast<std::size_t>(v)];
      for (std::size_t s = 0; s < fan.size(); ++s) {
        if (fan[s] < 0 || fan[s] == best) continue;
        keep[static_cast<std::size_t>(around.tri[static_cast<std::size_t>(b) + s])] = 0;
        ++stats_.pinch_triangles;
      }
      ++resolved;
    }
    if (resolved == 0) break;
    stats_.pinches += resolved;
  }
  if (stats_.one_neighbour_triangles == 0 && stats_.pinch_triangles == 0) return;

  // The kept triangles and their nodes, in their order.
  std::vector<NodeId> new_id(static_cast<std::size_t>(nn), -1);
  for (std::size_t k = 0; k < t.size(); ++k)
    if (keep[k] != 0)
      for (const NodeId v : t[k]) new_id[static_cast<std::size_t>(v)] = 0;
  Mesh g;
  g.lattice = m.lattice;
  g.rotation = m.rotation;
  g.floodplain_top_m = m.floodplain_top_m;
  // Exactly the kept counts: growing by push_back alone would leave up to twice the capacity.
  const auto kept_nodes = static_cast<std::size_t>(std::count(new_id.begin(), new_id.end(), NodeId{0}));
  const auto kept_triangles = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));
  for (auto* v : {&g.node_i, &g.node_j}) v->reserve(kept_nodes);
  for (auto* v : {&g.lon_deg, &g.lat_deg, &g.rlon_deg, &g.rlat_deg, &g.depth_m}) v->reserve(kept_nodes);
  g.node_flags.reserve(kept_nodes);
  g.triangles.reserve(kept_triangles);
  g.triangle_level.reserve(kept_triangles);
  g.triangle_square.reserve(kept_triangles);
  source_triangle_.reserve(kept_triangles);
  for (std::size_t n = 0; n < static_cast<std::size_t>(nn); ++n) {
    if (new_id[n] < 0) {
      ++stats_.removed_nodes;
      continue;
    }
    new_id[n] = static_cast<NodeId>(g.node_i.size());
    g.node_i.push_back(m.node_i[n]);
    g.node_j.push_back(m.node_j[n]);
    g.lon_deg.push_back(m.lon_deg[n]);
    g.lat_deg.push_back(m.lat_deg[n]);
    g.rlon_deg.push_back(m.rlon_deg[n]);
    g.rlat_deg.push_back(m.rlat_deg[n]);
    g.depth_m.push_back(m.depth_m[n]);
    g.node_flags.push_back(static_cast<std::uint8_t>(m.node_flags[n] & ~kNodeBoundary));
  }
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (keep[k] == 0) {
      stats_.removed_area_km2 += area_km2(m, t[k]);
      continue;
    }
    g.triangles.push_back({new_id[static_cast<std::size_t>(t[k][0])], new_id[static_cast<std::size_t>(t[k][1])],
                           new_id[static_cast<std::size_t>(t[k][2])]});
    g.triangle_level.push_back(m.triangle_level.empty() ? 0 : m.triangle_level[k]);
    g.triangle_square.push_back(-1);
    source_triangle_.push_back(static_cast<ElementId>(k));
  }
  if (g.triangles.empty())
    throw NumericalError("mesh cleaning: no triangle has two neighbours; the mesh is too small for the models");

  // Boundary edges of the cleaned mesh (wet on the left: the kept triangle's own direction), one
  // leaving each boundary node (no pinch is left).
  const auto gn = static_cast<std::size_t>(g.node_i.size());
  std::vector<NodeId> next(gn, -1);
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (keep[k] == 0) continue;
    for (int e = 0; e < 3; ++e) {
      const NodeId a = t[k][static_cast<std::size_t>(e)], b = t[k][static_cast<std::size_t>((e + 1) % 3)];
      if (edge_neighbours(t, around, alive, static_cast<ElementId>(k), a, b) > 0) continue;
      NodeId& slot = next[static_cast<std::size_t>(new_id[static_cast<std::size_t>(a)])];
      if (slot >= 0) throw InternalError("mesh cleaning: a pinch vertex is left (two boundary edges leave one node)");
      slot = new_id[static_cast<std::size_t>(b)];
    }
  }
  // Where each edge of the input's loops was: (loop, position) by its first node (new ids).
  struct Place {
    NodeId a, b;
    std::int64_t loop, index;
  };
  std::vector<Place> places;
  for (std::size_t l = 0; l < m.loops.size(); ++l) {
    const auto& ln = m.loops[l].nodes;
    for (std::size_t k = 0; k < ln.size(); ++k) {
      const NodeId a = new_id[static_cast<std::size_t>(ln[k])],
                   b = new_id[static_cast<std::size_t>(ln[(k + 1) % ln.size()])];
      if (a >= 0 && b >= 0) places.push_back({a, b, static_cast<std::int64_t>(l), static_cast<std::int64_t>(k)});
    }
  }
  std::sort(places.begin(), places.end(),
            [](const Place& x, const Place& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  constexpr std::int64_t kNew = std::numeric_limits<std::int64_t>::max();
  auto place_of = [&](NodeId a, NodeId b) -> std::pair<std::int64_t, std::int64_t> {
    const auto it = std::lower_bound(places.begin(), places.end(), std::make_pair(a, b),
                                     [](const Place& p, const std::pair<NodeId, NodeId>& k) {
                                       return std::tie(p.a, p.b) < std::tie(k.first, k.second);
                                     });
    if (it != places.end() && it->a == a && it->b == b) return {it->loop, it->index};
    return {kNew, kNew};
  };
  // Trace every loop; its key is the earliest input-loop edge on it (a loop of new edges only:
  // after all others, by its smallest node), and it starts there.
  struct Traced {
    std::pair<std::int64_t, std::int64_t> key;
    std::vector<NodeId> nodes;
  };
  std::vector<Traced> loops;
  std::vector<char> seen(gn, 0);
  for (std::size_t s = 0; s < gn; ++s) {
    if (next[s] < 0 || seen[s] != 0) continue;
    std::vector<NodeId> nodes;
    for (auto v = static_cast<NodeId>(s); seen[static_cast<std::size_t>(v)] == 0;
         v = next[static_cast<std::size_t>(v)]) {
      if (next[static_cast<std::size_t>(v)] < 0) throw InternalError("mesh cleaning: a boundary loop does not close");
      seen[static_cast<std::size_t>(v)] = 1;
      nodes.push_back(v);
    }
    if (nodes.front() != next[static_cast<std::size_t>(nodes.back())])
      throw InternalError("mesh cleaning: a boundary loop does not close");
    std::size_t start = 0;
    std::pair<std::int64_t, std::int64_t> key{kNew, kNew};
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const auto p = place_of(nodes[k], nodes[(k + 1) % nodes.size()]);
      if (p < key) {
        key = p;
        start = k;
      }
    }
    if (key.first == kNew) key = {kNew, *std::min_element(nodes.begin(), nodes.end())};
    std::rotate(nodes.begin(), nodes.begin() + static_cast<std::ptrdiff_t>(start), nodes.end());
    loops.push_back({key, std::move(nodes)});
  }
  std::sort(loops.begin(), loops.end(), [](const Traced& x, const Traced& y) { return x.key < y.key; });
  bool outer_given = false;
  for (auto& tl : loops) {
    BoundaryLoop loop;
    if (tl.key.first != kNew) {
      const BoundaryLoop& src = m.loops[static_cast<std::size_t>(tl.key.first)];
      loop.outer = src.outer && !outer_given;
      loop.pole = src.pole;
      outer_given = outer_given || loop.outer;
    }
    const auto id = static_cast<std::int32_t>(g.loops.size());
    for (std::size_t k = 0; k < tl.nodes.size(); ++k) {
      g.boundary_edges.push_back({tl.nodes[k], tl.nodes[(k + 1) % tl.nodes.size()]});
      g.boundary_edge_loop.push_back(id);
      g.node_flags[static_cast<std::size_t>(tl.nodes[k])] |= kNodeBoundary;
    }
    loop.nodes = std::move(tl.nodes);
    g.loops.push_back(std::move(loop));
  }

  const ModelDefects d = find_model_defects(g.triangles, g.node_count());
  if (!d.none())
    throw InternalError(fmt::format("mesh cleaning: {} triangles with one neighbour and {} pinches left",
                                    d.one_neighbour_triangles, d.pinch_nodes));
  if (m.typed) type_like(g, m);  // a regional mesh: an edge stays open when it was open (by its lattice vertices)
  owned_.emplace(std::move(g));
}

std::string ModelMesh::describe() const {
  const Mesh& c = mesh();
  return fmt::format(
      "{} triangles with one neighbour removed in {} rounds, {} pinches removed ({} triangles there); {} nodes, {} "
      "triangles, {} boundary loops left",
      stats_.one_neighbour_triangles, stats_.rounds, stats_.pinches, stats_.pinch_triangles, c.node_count(),
      c.triangle_count(), c.loops.size());
}

Json ModelMesh::json() const {
  const Mesh& c = mesh();
  return Json{{"one_neighbour_triangles_removed", stats_.one_neighbour_triangles},
              {"rounds", stats_.rounds},
              {"pinches_removed", stats_.pinches},
              {"pinch_triangles_removed", stats_.pinch_triangles},
              {"nodes_removed", stats_.removed_nodes},
              {"area_removed_km2", std::round(stats_.removed_area_km2)},
              {"nodes", c.node_count()},
              {"triangles", c.triangle_count()},
              {"boundary_loops", c.loops.size()}};
}

}  // namespace aq::mesh

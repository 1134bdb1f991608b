// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary typing of regional meshes (see boundaries.hpp).
#include "mesh/boundaries.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <tuple>

#include "core/error.hpp"

namespace aq::mesh {

namespace {

// Edge classes of a loop.
constexpr char kLand = 0, kOpenEdge = 1, kRiverEdge = 2;

struct Run {
  std::size_t start = 0, length = 0;
  char cls = kLand;
  [[nodiscard]] bool open() const { return cls != kLand; }  ///< open or river: a segment of the open list
};

// Maximal runs of equal flags around the cycle, the first starting where a run starts.
std::vector<Run> runs_of(const std::vector<char>& o) {
  const std::size_t n = o.size();
  std::vector<Run> out;
  std::size_t s = 0;
  while (s < n && o[s] == o[(s + n - 1) % n]) ++s;
  if (s == n) return {Run{0, n, o[0]}};
  for (std::size_t k = 0; k < n;) {
    const std::size_t a = (s + k) % n;
    std::size_t len = 0;
    while (k < n && o[(s + k) % n] == o[a]) {
      ++k;
      ++len;
    }
    out.push_back(Run{a, len, o[a]});
  }
  return out;
}

// Whether a loop runs anticlockwise in the lattice plane (the water on its left inside it: the
// outer coast of a part of the mesh, not an island in it), by its signed area over the nodes'
// lattice vertices (I unwrapped across the seam); false when a node is off the lattice.
bool anticlockwise(const Mesh& m, const std::vector<NodeId>& nodes) {
  const std::int64_t nx = m.lattice.nx;
  double area2 = 0.0, x = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const auto p = static_cast<std::size_t>(nodes[k]), q = static_cast<std::size_t>(nodes[(k + 1) % nodes.size()]);
    if (m.node_i[p] < 0 || m.node_i[q] < 0) return false;
    std::int64_t di = m.node_i[q] - m.node_i[p];
    if (di > nx / 2) di -= nx;
    if (di < -nx / 2) di += nx;
    const double y0 = static_cast<double>(m.node_j[p]), y1 = static_cast<double>(m.node_j[q]);
    const double x1 = x + static_cast<double>(di);
    area2 += x * y1 - x1 * y0;
    x = x1;
  }
  return area2 > 0.0;
}

std::string where(const Mesh& m, NodeId n) {
  const auto p = static_cast<std::size_t>(n);
  return fmt::format("{:.4f}°E {:.4f}°N (node {})", m.lon_deg[p], m.lat_deg[p], n + 1);
}

}  // namespace

BoundaryCounts type_boundaries(Mesh& m, const std::function<bool(NodeId, NodeId)>& is_open, const Logger* log,
                               const std::function<bool(NodeId, NodeId)>& is_river) {
  BoundaryCounts c;
  m.segments.clear();
  std::vector<BoundarySegment> land;
  std::vector<std::tuple<NodeId, NodeId, BoundaryType>> typed;
  for (std::size_t l = 0; l < m.loops.size(); ++l) {
    const std::vector<NodeId>& nodes = m.loops[l].nodes;
    const std::size_t n = nodes.size();
    if (n == 0) continue;
    std::vector<char> o(n);
    for (std::size_t k = 0; k < n; ++k) {
      const NodeId a = nodes[k], b = nodes[(k + 1) % n];
      o[k] = !is_open(a, b) ? kLand : (is_river && is_river(a, b)) ? kRiverEdge : kOpenEdge;
    }
    // Short land gaps between open runs become open; then short open runs become land (or join a
    // river run beside them). River runs stay as they are.
    for (int pass = 0; pass < 2; ++pass) {
      const bool gap_pass = pass == 0;
      const std::vector<Run> runs = runs_of(o);
      if (runs.size() < 2) break;
      for (std::size_t q = 0; q < runs.size(); ++q) {
        const Run& r = runs[q];
        if (r.cls != (gap_pass ? kLand : kOpenEdge) || static_cast<std::int64_t>(r.length) >= kMinSegmentEdges)
          continue;
        const char before = runs[(q + runs.size() - 1) % runs.size()].cls, after = runs[(q + 1) % runs.size()].cls;
        char to = kLand;
        if (gap_pass) {
          if (before != kOpenEdge || after != kOpenEdge) continue;  // a gap beside a river stays land
          to = kOpenEdge;
        } else if (before == kRiverEdge || after == kRiverEdge) {
          to = kRiverEdge;
        }
        for (std::size_t k = 0; k < r.length; ++k) o[(r.start + k) % n] = to;
        ++c.merged;
        if (log != nullptr)
          log->info("boundaries: {} {} edge(s) from {} to {} (shorter than {} edges) made {}",
                    gap_pass ? "land gap of" : "open segment of", r.length, where(m, nodes[r.start]),
                    where(m, nodes[(r.start + r.length) % n]), kMinSegmentEdges,
                    gap_pass           ? "open: the open segments around it merge"
                    : to == kRiverEdge ? "part of the river inflow beside it"
                                       : "land");
      }
    }
    const std::vector<Run> runs = runs_of(o);
    // A closed land loop is mainland when it is the outer loop, or the outer coast of another
    // part of the mesh (a seed's separate sea): anticlockwise around its water.
    const bool mainland = runs.size() > 1 || m.loops[l].outer || (!m.loops[l].pole && anticlockwise(m, nodes));
    const auto type_of = [&](char cls) {
      return cls == kRiverEdge  ? BoundaryType::kRiver
             : cls == kOpenEdge ? BoundaryType::kOpen
             : mainland         ? BoundaryType::kMainland
                                : BoundaryType::kIsland;
    };
    for (std::size_t k = 0; k < n; ++k) typed.emplace_back(nodes[k], nodes[(k + 1) % n], type_of(o[k]));
    if (runs.size() == 1) {
      BoundarySegment s;
      s.loop = static_cast<std::int32_t>(l);
      s.type = type_of(runs[0].cls);
      if (runs[0].open()) {  // open all round: two open segments (a looped open segment is refused by SCHISM)
        if (log != nullptr)
          log->warn("boundaries: loop {} is open all round (the domain edge is water everywhere along it); written "
                    "as two open segments meeting at {} and {}",
                    l + 1, where(m, nodes[0]), where(m, nodes[n / 2]));
        BoundarySegment a = s, b = s;
        a.nodes.assign(nodes.begin(), nodes.begin() + static_cast<std::ptrdiff_t>(n / 2 + 1));
        b.nodes.assign(nodes.begin() + static_cast<std::ptrdiff_t>(n / 2), nodes.end());
        b.nodes.push_back(nodes[0]);
        m.segments.push_back(std::move(a));
        m.segments.push_back(std::move(b));
      } else {
        s.closed = true;
        s.nodes = nodes;
        land.push_back(std::move(s));
      }
      continue;
    }
    for (const Run& r : runs) {
      BoundarySegment s;
      s.loop = static_cast<std::int32_t>(l);
      s.type = type_of(r.cls);
      for (std::size_t k = 0; k <= r.length; ++k) s.nodes.push_back(nodes[(r.start + k) % n]);
      (r.open() ? m.segments : land).push_back(std::move(s));
    }
  }
  for (auto& s : land) m.segments.push_back(std::move(s));
  std::sort(typed.begin(), typed.end());
  m.boundary_edge_type.assign(m.boundary_edges.size(), BoundaryType::kMainland);
  for (std::size_t e = 0; e < m.boundary_edges.size(); ++e) {
    const auto [a, b] = std::pair{m.boundary_edges[e][0], m.boundary_edges[e][1]};
    const auto it = std::lower_bound(typed.begin(), typed.end(), std::make_tuple(a, b, BoundaryType::kMainland));
    if (it == typed.end() || std::get<0>(*it) != a || std::get<1>(*it) != b)
      throw InternalError(fmt::format("boundary typing: edge {} -> {} is on no loop", a + 1, b + 1));
    m.boundary_edge_type[e] = std::get<2>(*it);
  }
  m.typed = true;
  BoundaryCounts counts = boundary_counts(m);
  counts.merged = c.merged;
  return counts;
}

bool edge_right_pixel(const Mesh& m, NodeId a, NodeId b, mask::PixelIJ& px) {
  const Lattice& lat = m.lattice;
  const auto pa = static_cast<std::size_t>(a), pb = static_cast<std::size_t>(b);
  const std::int64_t ia = m.node_i[pa], ja = m.node_j[pa];
  std::int64_t di = m.node_i[pb] - ia;
  const std::int64_t dj = m.node_j[pb] - ja;
  if (di > lat.nx / 2) di -= lat.nx;
  if (di < -lat.nx / 2) di += lat.nx;
  if ((di != 0) == (dj != 0)) return false;  // a diagonal (after cleaning) or a degenerate edge
  std::int64_t pi = ia, pj = ja;             // the pixel on the right of the first unit step
  if (di > 0) pj = ja - 1;
  if (di < 0) pi = ia - 1;
  if (dj < 0) {
    pi = ia - 1;
    pj = ja - 1;
  }
  if (pj < 0 || pj >= lat.ny) return false;
  px = {((pi % lat.nx) + lat.nx) % lat.nx, pj};
  return true;
}

BoundaryCounts type_domain_boundaries(Mesh& m, const std::function<bool(const mask::PixelIJ&)>& open_water,
                                      const Logger* log, const std::function<bool(const mask::PixelIJ&)>& river) {
  const auto is_open = [&](NodeId a, NodeId b) {
    mask::PixelIJ px;
    return edge_right_pixel(m, a, b, px) && open_water(px);
  };
  std::function<bool(NodeId, NodeId)> is_river;
  if (river) {
    is_river = [&](NodeId a, NodeId b) {
      mask::PixelIJ px;
      return edge_right_pixel(m, a, b, px) && river(px);
    };
  }
  return type_boundaries(m, is_open, log, is_river);
}

BoundaryCounts boundary_counts(const Mesh& m) {
  BoundaryCounts c;
  for (const BoundarySegment& s : m.segments) {
    const auto edges = static_cast<std::int64_t>(s.nodes.size()) - (s.closed ? 0 : 1);
    switch (s.type) {
      case BoundaryType::kOpen:
        ++c.open_segments;
        c.open_nodes += static_cast<std::int64_t>(s.nodes.size());
        c.open_edges += edges;
        break;
      case BoundaryType::kMainland:
        ++c.mainland_segments;
        c.mainland_edges += edges;
        break;
      case BoundaryType::kIsland:
        ++c.islands;
        c.island_edges += edges;
        break;
      case BoundaryType::kRiver:
        ++c.river_segments;
        c.river_nodes += static_cast<std::int64_t>(s.nodes.size());
        c.river_edges += edges;
        break;
    }
  }
  return c;
}

std::string describe(const BoundaryCounts& c) {
  return fmt::format(
             "{} open segment(s) ({} nodes, {} edges), {} mainland piece(s) ({} edges), {} island(s) ({} edges)",
             c.open_segments, c.open_nodes, c.open_edges, c.mainland_segments, c.mainland_edges, c.islands,
             c.island_edges) +
         (c.river_segments > 0 ? fmt::format(", {} river inflow segment(s) ({} nodes, {} edges)", c.river_segments,
                                             c.river_nodes, c.river_edges)
                               : std::string()) +
         (c.merged > 0 ? fmt::format("; {} short piece(s) retyped", c.merged) : std::string());
}

Json boundaries_json(const Mesh& m, const BoundaryCounts& c) {
  Json open = Json::array();
  for (const BoundarySegment& s : m.segments) {
    if (s.type != BoundaryType::kOpen) continue;
    const auto a = static_cast<std::size_t>(s.nodes.front()), b = static_cast<std::size_t>(s.nodes.back());
    open.push_back(Json{{"nodes", s.nodes.size()},
                        {"from", {m.lon_deg[a], m.lat_deg[a]}},
                        {"to", {m.lon_deg[b], m.lat_deg[b]}}});
  }
  Json rivers = Json::array();
  for (const BoundarySegment& s : m.segments) {
    if (s.type != BoundaryType::kRiver) continue;
    const auto a = static_cast<std::size_t>(s.nodes.front()), b = static_cast<std::size_t>(s.nodes.back());
    rivers.push_back(
        Json{{"nodes", s.nodes.size()}, {"from", {m.lon_deg[a], m.lat_deg[a]}}, {"to", {m.lon_deg[b], m.lat_deg[b]}}});
  }
  return Json{
      {"open_segments", c.open_segments},         {"open_nodes", c.open_nodes},         {"open_edges", c.open_edges},
      {"river_segments", c.river_segments},       {"river_nodes", c.river_nodes},       {"rivers", rivers},
      {"mainland_segments", c.mainland_segments}, {"mainland_edges", c.mainland_edges}, {"islands", c.islands},
      {"island_edges", c.island_edges},           {"retyped_short_pieces", c.merged},   {"open", open}};
}

BoundaryCounts type_like(Mesh& derived, const Mesh& typed) {
  // The open and the river edges of `typed`, as pairs of lattice vertices, sorted.
  std::vector<std::array<std::int64_t, 4>> keys, river_keys;
  for (std::size_t e = 0; e < typed.boundary_edges.size() && e < typed.boundary_edge_type.size(); ++e) {
    const BoundaryType t = typed.boundary_edge_type[e];
    if (t != BoundaryType::kOpen && t != BoundaryType::kRiver) continue;
    const auto a = static_cast<std::size_t>(typed.boundary_edges[e][0]);
    const auto b = static_cast<std::size_t>(typed.boundary_edges[e][1]);
    keys.push_back({typed.node_i[a], typed.node_j[a], typed.node_i[b], typed.node_j[b]});
    if (t == BoundaryType::kRiver) river_keys.push_back(keys.back());
  }
  std::sort(keys.begin(), keys.end());
  std::sort(river_keys.begin(), river_keys.end());
  const auto in = [&](const std::vector<std::array<std::int64_t, 4>>& set, NodeId a, NodeId b) {
    const auto pa = static_cast<std::size_t>(a), pb = static_cast<std::size_t>(b);
    if (derived.node_i[pa] < 0 || derived.node_i[pb] < 0) return false;
    const std::array<std::int64_t, 4> k{derived.node_i[pa], derived.node_j[pa], derived.node_i[pb], derived.node_j[pb]};
    return std::binary_search(set.begin(), set.end(), k);
  };
  return type_boundaries(
      derived, [&](NodeId a, NodeId b) { return in(keys, a, b); }, nullptr,
      [&](NodeId a, NodeId b) { return in(river_keys, a, b); });
}

}  // namespace aq::mesh

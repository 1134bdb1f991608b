// SPDX-License-Identifier: GPL-3.0-or-later
// The open boundary of a polygon domain moved onto the polygon (see open_snap.hpp).
#include "mesh/open_snap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/types.hpp"
#include "mask/lattice_coords.hpp"
#include "mesh/sphere_geometry.hpp"

namespace aq::mesh {

namespace {

constexpr double kOnPolygonDeg = 1e-9;
constexpr double kEarthRadiusKm = 6371.0088;  // mean radius (IUGG), as the time step's distances

// The nearest point of the rings' edges (straight in lon/lat) to (lon, lat), in the local plane
// (λ·cos φ, φ) of the point; its longitude is the ring's (continuous) one.
mask::LonLat nearest_on_rings(const std::vector<mask::PolygonRing>& rings, double lon, double lat) {
  const double c = std::cos(lat * kDegToRad);
  double best = std::numeric_limits<double>::infinity();
  mask::LonLat out{lon, lat};
  for (const auto& r : rings) {
    const std::size_t n = r.lon.size();
    for (std::size_t k = 0; k < n; ++k) {
      const double ax = r.lon[k], ay = r.lat[k], bx = r.lon[(k + 1) % n], by = r.lat[(k + 1) % n];
      const double x = lon + 360.0 * std::round((0.5 * (ax + bx) - lon) / 360.0);
      const double ux = (bx - ax) * c, uy = by - ay, px = (x - ax) * c, py = lat - ay;
      const double len2 = ux * ux + uy * uy;
      const double t = len2 > 0.0 ? std::clamp((px * ux + py * uy) / len2, 0.0, 1.0) : 0.0;
      const double qx = ax + t * (bx - ax), qy = ay + t * (by - ay);
      const double dx = (qx - x) * c, dy = qy - lat, d2 = dx * dx + dy * dy;
      if (d2 < best) {
        best = d2;
        out = {qx - (x - lon), qy};
      }
    }
  }
  return out;
}

double orient(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

bool on_segment(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}

// Whether the closed segments pq and rs cross or touch.
bool segments_meet(const std::array<double, 2>& p, const std::array<double, 2>& q, const std::array<double, 2>& r,
                   const std::array<double, 2>& s) {
  const double d1 = orient(r, s, p), d2 = orient(r, s, q), d3 = orient(p, q, r), d4 = orient(p, q, s);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment(r, s, p)) || (d2 == 0 && on_segment(r, s, q)) || (d3 == 0 && on_segment(p, q, r)) ||
         (d4 == 0 && on_segment(p, q, s));
}

// Compressed lists: the items of key k are items[start[k] .. start[k+1]).
struct Csr {
  std::vector<std::int64_t> start, items;
  [[nodiscard]] auto of(std::size_t k) const {
    struct Range {
      const std::int64_t *b, *e;
      [[nodiscard]] const std::int64_t* begin() const { return b; }
      [[nodiscard]] const std::int64_t* end() const { return e; }
    };
    return Range{items.data() + start[k], items.data() + start[k + 1]};
  }
};

template <typename Keys>
Csr make_csr(std::size_t keys, std::size_t count, Keys&& keys_of) {
  Csr c;
  c.start.assign(keys + 1, 0);
  for (std::size_t x = 0; x < count; ++x)
    keys_of(x, [&](std::size_t k) { ++c.start[k + 1]; });
  for (std::size_t k = 0; k < keys; ++k) c.start[k + 1] += c.start[k];
  c.items.resize(static_cast<std::size_t>(c.start[keys]));
  std::vector<std::int64_t> fill(c.start.begin(), c.start.end() - 1);
  for (std::size_t x = 0; x < count; ++x)
    keys_of(x, [&](std::size_t k) { c.items[static_cast<std::size_t>(fill[k]++)] = static_cast<std::int64_t>(x); });
  return c;
}

}  // namespace

std::string OpenSnapResult::describe() const {
  return fmt::format(
      "{} open-boundary nodes: {} moved onto the polygon (largest move {:.3f} km at {:.4f}°E {:.4f}°N, mean {:.3f} "
      "km), {} already on it, {} kept on the lattice ({} would turn a triangle over, {} would take an angle out of "
      "[{:g}°, {:g}°], {} would make boundary edges cross or touch, {} would be dry)",
      open_nodes, moved, max_move_km, max_move_lon_deg, max_move_lat_deg, mean_move_km, on_polygon, kept(),
      kept_orientation, kept_angle, min_angle_deg, max_angle_deg, kept_crossing, kept_dry);
}

Json OpenSnapResult::json() const {
  return Json{{"open_nodes", open_nodes},
              {"moved", moved},
              {"on_polygon", on_polygon},
              {"kept", kept()},
              {"kept_orientation", kept_orientation},
              {"kept_angle", kept_angle},
              {"kept_crossing", kept_crossing},
              {"kept_dry", kept_dry},
              {"max_move_km", std::round(max_move_km * 1e4) / 1e4},
              {"max_move_at_deg", std::array<double, 2>{max_move_lon_deg, max_move_lat_deg}},
              {"mean_move_km", std::round(mean_move_km * 1e4) / 1e4},
              {"min_angle_deg", min_angle_deg},
              {"max_angle_deg", max_angle_deg}};
}

OpenSnapResult snap_open_boundary(Mesh& m, const std::vector<mask::PolygonRing>& rings, const PoleRotation& rot,
                                  const PointElevation& elevation, const OpenSnapOptions& o) {
  OpenSnapResult res;
  res.min_angle_deg = o.min_angle_deg;
  res.max_angle_deg = o.max_angle_deg;
  const auto nn = static_cast<std::size_t>(m.node_count());
  const Lattice& lat = m.lattice;

  // The open segments' nodes, in segment order, each once.
  std::vector<NodeId> nodes;
  std::vector<char> seen(nn, 0);
  for (const auto& s : m.segments) {
    if (s.type != BoundaryType::kOpen) continue;
    for (const NodeId v : s.nodes) {
      const auto p = static_cast<std::size_t>(v);
      if (seen[p] != 0 || m.node_i[p] < 0) continue;
      seen[p] = 1;
      nodes.push_back(v);
    }
  }
  res.open_nodes = static_cast<std::int64_t>(nodes.size());
  if (nodes.empty() || rings.empty()) return res;

  const Csr node_tris = make_csr(nn, m.triangles.size(), [&](std::size_t t, auto&& add) {
    for (const NodeId v : m.triangles[t]) add(static_cast<std::size_t>(v));
  });
  const Csr node_edges = make_csr(nn, m.boundary_edges.size(), [&](std::size_t e, auto&& add) {
    for (const NodeId v : m.boundary_edges[e]) add(static_cast<std::size_t>(v));
  });
  // Boundary edges by lattice vertex (key J·nx + I of each end), and how far an edge reaches.
  std::vector<std::pair<std::int64_t, std::int64_t>> by_vertex;
  std::int64_t reach = 1;
  auto wrap_di = [&](std::int64_t di) {
    if (di > lat.nx / 2) di -= lat.nx;
    if (di < -lat.nx / 2) di += lat.nx;
    return di;
  };
  for (std::size_t e = 0; e < m.boundary_edges.size(); ++e) {
    const auto a = static_cast<std::size_t>(m.boundary_edges[e][0]), b = static_cast<std::size_t>(m.boundary_edges[e][1]);
    if (m.node_i[a] < 0 || m.node_i[b] < 0) continue;
    reach = std::max({reach, std::abs(wrap_di(m.node_i[b] - m.node_i[a])), std::abs(m.node_j[b] - m.node_j[a])});
    for (const std::size_t v : {a, b}) by_vertex.emplace_back(m.node_j[v] * lat.nx + m.node_i[v], static_cast<std::int64_t>(e));
  }
  std::sort(by_vertex.begin(), by_vertex.end());
  const std::int64_t radius = reach + 2;  // a move is under one pixel: an edge it can meet has an end this near

  const double pix = lat.pixel_deg();
  // Position of node v in the lattice plane, relative to node c's column (seam-safe).
  auto plane = [&](std::size_t c, std::size_t v) -> std::array<double, 2> {
    const double x = static_cast<double>(wrap_di(m.node_i[v] - m.node_i[c])) * pix + m.plane_dx_deg(static_cast<NodeId>(v));
    return {x, m.plane_y_deg(static_cast<NodeId>(v))};
  };
  auto sphere = [&](std::size_t v) { return unit_vector_deg(m.lon_deg[v], m.lat_deg[v]); };
  struct Shape {
    bool positive = true;
    double min_angle = 180.0, max_angle = 0.0;
  };
  // The triangles around node c: anticlockwise (sphere and plane), extreme angles over all.
  auto shape = [&](std::size_t c) {
    Shape s;
    for (const std::int64_t t : node_tris.of(c)) {
      const auto& tr = m.triangles[static_cast<std::size_t>(t)];
      std::array<std::array<double, 3>, 3> u{};
      std::array<std::array<double, 2>, 3> q{};
      for (std::size_t a = 0; a < 3; ++a) {
        u[a] = sphere(static_cast<std::size_t>(tr[a]));
        q[a] = plane(c, static_cast<std::size_t>(tr[a]));
      }
      if (!(spherical_triangle_area(u[0], u[1], u[2]) > 0.0) || !(orient(q[0], q[1], q[2]) > 0.0)) s.positive = false;
      for (const double ang : spherical_angles_deg(u[0], u[1], u[2])) {
        if (!std::isfinite(ang)) s.positive = false;  // std::min/max would pass a NaN angle by
        s.min_angle = std::min(s.min_angle, ang);
        s.max_angle = std::max(s.max_angle, ang);
      }
    }
    return s;
  };
  // Whether a boundary edge at node c crosses or touches a boundary edge without a common node.
  auto edges_meet = [&](std::size_t c) {
    for (const std::int64_t e : node_edges.of(c)) {
      const auto& ee = m.boundary_edges[static_cast<std::size_t>(e)];
      const auto p0 = static_cast<std::size_t>(ee[0]), p1 = static_cast<std::size_t>(ee[1]);
      const auto P = plane(c, p0), Q = plane(c, p1);
      for (std::int64_t dj = -radius; dj <= radius; ++dj) {
        const std::int64_t j = m.node_j[c] + dj;
        if (j < 0 || j > lat.ny) continue;
        for (std::int64_t di = -radius; di <= radius; ++di) {
          const std::int64_t key = j * lat.nx + wrap_index(m.node_i[c] + di, lat.nx);
          auto it = std::lower_bound(by_vertex.begin(), by_vertex.end(), std::make_pair(key, std::int64_t{-1}));
          for (; it != by_vertex.end() && it->first == key; ++it) {
            const auto& f = m.boundary_edges[static_cast<std::size_t>(it->second)];
            if (f[0] == ee[0] || f[0] == ee[1] || f[1] == ee[0] || f[1] == ee[1]) continue;
            if (segments_meet(P, Q, plane(c, static_cast<std::size_t>(f[0])), plane(c, static_cast<std::size_t>(f[1]))))
              return true;
          }
        }
      }
    }
    return false;
  };

  std::vector<char> done(nn, 0);  // moved, or already on the polygon
  std::vector<std::int8_t> why(nn, 0);  // the last pass's reason to keep: 1 orientation, 2 angle, 3 crossing, 4 dry
  double sum_km = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    for (const NodeId v : nodes) {
      const auto p = static_cast<std::size_t>(v);
      if (done[p] != 0) continue;
      const mask::LonLat q = nearest_on_rings(rings, m.lon_deg[p], m.lat_deg[p]);
      const double new_lon = q.lon_deg + 360.0 * std::round((m.lon_deg[p] - q.lon_deg) / 360.0);
      const double move_deg = mask::angular_distance_deg({m.lon_deg[p], m.lat_deg[p]}, {new_lon, q.lat_deg});
      if (move_deg < kOnPolygonDeg) {
        done[p] = 1;
        ++res.on_polygon;
        continue;
      }
      const Shape before = shape(p);
      const double old_lon = m.lon_deg[p], old_lat = m.lat_deg[p], old_rlon = m.rlon_deg[p], old_rlat = m.rlat_deg[p];
      const std::uint8_t old_flags = m.node_flags[p];
      double rlon = new_lon, rlat = q.lat_deg;
      if (!rot.identity()) {
        rot.to_rotated(new_lon, q.lat_deg, rlon, rlat);
        rlon += 360.0 * std::round((old_rlon - rlon) / 360.0);
      }
      m.lon_deg[p] = new_lon;
      m.lat_deg[p] = q.lat_deg;
      m.rlon_deg[p] = rlon;
      m.rlat_deg[p] = rlat;
      m.node_flags[p] = static_cast<std::uint8_t>(old_flags | kNodeMoved);
      const Shape after = shape(p);
      std::int8_t reason = 0;
      double z = 0.0;
      if (!after.positive) {
        reason = 1;
      } else if (after.min_angle < std::min(o.min_angle_deg, before.min_angle) ||
                 after.max_angle > std::max(o.max_angle_deg, before.max_angle)) {
        reason = 2;
      } else if (edges_meet(p)) {
        reason = 3;
      } else {
        z = elevation(new_lon, q.lat_deg);
        const bool was_wet = m.depth_m[p] <= o.wet_max_elevation_m;
        if (!std::isfinite(z) || (was_wet && !(z <= o.wet_max_elevation_m))) reason = 4;
      }
      if (reason != 0) {
        m.lon_deg[p] = old_lon;
        m.lat_deg[p] = old_lat;
        m.rlon_deg[p] = old_rlon;
        m.rlat_deg[p] = old_rlat;
        m.node_flags[p] = old_flags;
        why[p] = reason;
        continue;
      }
      m.depth_m[p] = z;
      done[p] = 1;
      why[p] = 0;
      ++res.moved;
      const double km = move_deg * kDegToRad * kEarthRadiusKm;
      sum_km += km;
      if (km > res.max_move_km) {
        res.max_move_km = km;
        res.max_move_lon_deg = old_lon;
        res.max_move_lat_deg = old_lat;
      }
    }
  }
  for (const NodeId v : nodes) {
    switch (why[static_cast<std::size_t>(v)]) {
      case 1: ++res.kept_orientation; break;
      case 2: ++res.kept_angle; break;
      case 3: ++res.kept_crossing; break;
      case 4: ++res.kept_dry; break;
      default: break;
    }
  }
  if (res.moved > 0) res.mean_move_km = sum_km / static_cast<double>(res.moved);
  return res;
}

}  // namespace aq::mesh

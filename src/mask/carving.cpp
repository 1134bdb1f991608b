// SPDX-License-Identifier: GPL-3.0-or-later
// Carving passages, channels and blockages into the bathymetry (see carving.hpp).
#include "mask/carving.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

#include "core/edit_distance.hpp"
#include "core/error.hpp"
#include "core/sphere_vectors.hpp"
#include "core/types.hpp"
#include "mask/passages.hpp"

namespace aq::mask {

namespace {

using V3 = sphere::Vec3;

constexpr double kKmPerDeg = 111.19508;  // great-circle km per degree on the 6371.0088 km sphere
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A table passage's carved path continues this many times (K + 1) pixels past each side's centre.
constexpr double kExtendPixels = 3.0;

using sphere::cross;
using sphere::dot;
V3 unit(double lon_deg, double lat_deg) { return sphere::unit_deg(lon_deg, lat_deg); }
V3 normalized(const V3& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}
LonLat to_lonlat(const V3& v) {
  return {std::atan2(v[1], v[0]) * kRadToDeg, std::asin(std::clamp(v[2], -1.0, 1.0)) * kRadToDeg};
}
double arc_deg(const V3& a, const V3& b) {
  return std::atan2(std::sqrt(dot(cross(a, b), cross(a, b))), dot(a, b)) * kRadToDeg;
}

// Douglas–Peucker on lon/lat points in a local plane (x scaled by cos of the mean latitude):
// the indices of the kept points, first and last always.
std::vector<std::size_t> simplify(const std::vector<LonLat>& pts, double tol_deg) {
  const std::size_t n = pts.size();
  if (n <= 2) {
    std::vector<std::size_t> all(n);
    for (std::size_t k = 0; k < n; ++k) all[k] = k;
    return all;
  }
  double mean = 0.0;
  for (const LonLat& p : pts) mean += p.lat_deg;
  const double cx = std::cos(mean / static_cast<double>(n) * kDegToRad);
  std::vector<unsigned char> keep(n, 0);
  keep[0] = keep[n - 1] = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const double ax = pts[a].lon_deg * cx, ay = pts[a].lat_deg, bx = pts[b].lon_deg * cx, by = pts[b].lat_deg;
    const double len = std::hypot(bx - ax, by - ay);
    double worst = -1.0;
    std::size_t at = a;
    for (std::size_t k = a + 1; k < b; ++k) {
      const double px = pts[k].lon_deg * cx, py = pts[k].lat_deg;
      const double d =
          len > 0.0 ? std::abs((bx - ax) * (ay - py) - (ax - px) * (by - ay)) / len : std::hypot(px - ax, py - ay);
      if (d > worst) {
        worst = d;
        at = k;
      }
    }
    if (worst > tol_deg) {
      keep[at] = 1;
      stack.push_back({a, at});
      stack.push_back({at, b});
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k] != 0) out.push_back(k);
  return out;
}

// The sampling step (degrees) of a search grid: the raster's cell, coarser when the grid would
// hold more than `max_cells` samples over `area_deg2`.
double search_step(const raster::Bathymetry& bathy, double area_deg2, double max_cells) {
  const auto& info = bathy.info();
  double s = std::min(info.dlon, info.dlat);
  if (!(s > 0.0) || !std::isfinite(s)) s = 1.0 / 12.0;
  return std::max(s, std::sqrt(area_deg2 / max_cells));
}

struct Planner {
  Planner(const config::MaskOptions& options, const Lattice& l, const PoleRotation& r, const raster::Bathymetry& b)
      : o(options), lattice(l), rot(r), bathy(b) {}
  const config::MaskOptions& o;
  const Lattice& lattice;
  const PoleRotation& rot;
  const raster::Bathymetry& bathy;
  double h = 0.0, floor_depth = 0.0, rpx_channel = 0.0, rpx_block = 0.0;
  std::vector<raster::Corridor> corridors;
  Carving out;

  // Half-widths of the arcs of a polyline: rpx pixels (the larger end's pixel), at least
  // min_half_deg.
  std::vector<double> half_widths(const std::vector<double>& lon, const std::vector<double>& lat, double rpx,
                                  double min_half_deg) const {
    std::vector<double> r;
    for (std::size_t k = 0; k + 1 < lon.size(); ++k) {
      const double p =
          std::max(pixel_arc_deg(lattice, rot, lon[k], lat[k]), pixel_arc_deg(lattice, rot, lon[k + 1], lat[k + 1]));
      r.push_back(std::max(rpx * p, min_half_deg));
    }
    return r;
  }

  void add(CarvedLine line, raster::EditKind kind, double elevation, std::vector<double> r) {
    raster::Corridor c;
    c.name = line.name;
    c.kind = kind;
    c.elevation_m = elevation;
    if (kind == raster::EditKind::kChannel) c.keep_at_or_below_m = -h;
    c.lon_deg = line.lon_deg;
    c.lat_deg = line.lat_deg;
    line.half_width_km_min = *std::min_element(r.begin(), r.end()) * kKmPerDeg;
    line.half_width_km_max = *std::max_element(r.begin(), r.end()) * kKmPerDeg;
    line.length_km = 0.0;
    for (std::size_t k = 0; k + 1 < line.lon_deg.size(); ++k)
      line.length_km +=
          arc_deg(unit(line.lon_deg[k], line.lat_deg[k]), unit(line.lon_deg[k + 1], line.lat_deg[k + 1])) * kKmPerDeg;
    c.half_width_deg = std::move(r);
    corridors.push_back(std::move(c));
    out.lines.push_back(std::move(line));
  }

  // A passage of the built-in table: the deepest path between its sides' centres inside its box,
  // continued at both ends through the sea beyond the strait to the deepest water within
  // kExtendPixels·(K + 1) pixels of each side's centre (where a coarse lattice's K-windows have
  // room to join the carved channel to the open sea).
  void table_passage(const Passage& p) {
    const GeoBox& b = p.box;
    const auto centre = [](const GeoBox& q) {
      return LonLat{0.5 * (q.lon_min_deg + q.lon_max_deg), 0.5 * (q.lat_min_deg + q.lat_max_deg)};
    };
    const LonLat ca = centre(p.side_a), cb = centre(p.side_b);
    const double reach = kExtendPixels * (static_cast<double>(o.cursor) + 1.0) *
                         std::max(pixel_arc_deg(lattice, rot, ca.lon_deg, ca.lat_deg),
                                  pixel_arc_deg(lattice, rot, cb.lon_deg, cb.lat_deg));
    // The search region: the box and `reach` around it (in latitude; in longitude at its cosine).
    const double lat0 = std::max(-89.9, b.lat_min_deg - reach), lat1 = std::min(89.9, b.lat_max_deg + reach);
    const double cmin = std::cos(std::max(std::abs(lat0), std::abs(lat1)) * kDegToRad);
    const double ext_lon = std::min(60.0, reach / std::max(cmin, 0.05));
    const double lon0 = b.lon_min_deg - ext_lon, lon1 = b.lon_max_deg + ext_lon;
    const double w = lon1 - lon0, hh = lat1 - lat0;
    const double s = search_step(bathy, w * hh, 2e6);
    const auto nx = std::max<std::int64_t>(3, static_cast<std::int64_t>(std::ceil(w / s)));
    const auto ny = std::max<std::int64_t>(3, static_cast<std::int64_t>(std::ceil(hh / s)));
    const double sx = w / static_cast<double>(nx), sy = hh / static_cast<double>(ny);
    const auto n = static_cast<std::size_t>(nx * ny);
    std::vector<double> lon(n), lat(n), z(n);
    std::vector<double> dx(static_cast<std::size_t>(ny));
    for (std::int64_t j = 0; j < ny; ++j) {
      const double la = lat0 + (static_cast<double>(j) + 0.5) * sy;
      dx[static_cast<std::size_t>(j)] = sx * std::cos(la * kDegToRad) * kKmPerDeg;
      for (std::int64_t i = 0; i < nx; ++i) {
        lon[static_cast<std::size_t>(j * nx + i)] = lon0 + (static_cast<double>(i) + 0.5) * sx;
        lat[static_cast<std::size_t>(j * nx + i)] = la;
      }
    }
    bathy.sample_points(lon.data(), lat.data(), nx * ny, z.data());
    std::vector<double> z_box(n, kNaN);     // the core search stays inside the box
    std::vector<unsigned char> side(n, 0);  // 1: in the box; 2: in side A; 4: in side B
    bool any = false;
    for (std::size_t c = 0; c < n; ++c) {
      if (b.contains(lon[c], lat[c])) {
        side[c] = 1;
        z_box[c] = z[c];
        any = any || !std::isnan(z[c]);
      }
      if (p.side_a.contains(lon[c], lat[c])) side[c] |= 2;
      if (p.side_b.contains(lon[c], lat[c])) side[c] |= 4;
    }
    if (!any) {
      out.skipped.push_back(
          fmt::format("{} (mask.passages_open): its box is outside the raster's coverage; not carved", p.name));
      return;
    }
    const auto cell_of = [&](LonLat q) {
      const auto i =
          std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((q.lon_deg - lon0) / sx)), 0, nx - 1);
      const auto j =
          std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((q.lat_deg - lat0) / sy)), 0, ny - 1);
      return j * nx + i;
    };
    const std::int64_t a = cell_of(ca), t = cell_of(cb);
    std::vector<unsigned char> target(n, 0);
    target[static_cast<std::size_t>(t)] = 1;
    std::vector<std::int64_t> path;
    const double m = minimax_path(z_box, nx, ny, {a}, target, dx, sy * kKmPerDeg, &path);
    CarvedLine line;
    line.name = p.name;
    line.source = "mask.passages_open";
    line.kind = LineKind::kPassage;
    if (std::isfinite(m)) {
      line.raster_sill_m = m;
      std::size_t top = 0;
      for (std::size_t k = 0; k < path.size(); ++k)
        if (z[static_cast<std::size_t>(path[k])] > z[static_cast<std::size_t>(path[top])]) top = k;
      line.sill = {lon[static_cast<std::size_t>(path[top])], lat[static_cast<std::size_t>(path[top])]};
      if (m <= -h) {
        line.depth_m = std::max(-m, floor_depth);
        line.depth_from =
            fmt::format("the raster's sill {:.0f} m at {:.3f}°E {:.3f}°N on the deepest path between the sides", -m,
                        line.sill.lon_deg, line.sill.lat_deg);
      } else {
        line.depth_m = std::max(p.sill_depth_m, floor_depth);
        line.depth_from = fmt::format(
            "the table's nominal sill depth: the raster's deepest path between the sides "
            "crosses {} at {:.3f}°E {:.3f}°N",
            m > 0.0 ? fmt::format("land of {:+.0f} m", m) : fmt::format("{:.0f} m, not below -h", m), line.sill.lon_deg,
            line.sill.lat_deg);
      }
    } else {
      path = {a, t};  // a straight line between the centres
      line.depth_m = std::max(p.sill_depth_m, floor_depth);
      line.depth_from = "the table's nominal sill depth: no-data cuts every path between the sides (a straight line)";
    }
    // Both ends continued into the open sea: outside the box, or inside that end's side.
    std::vector<unsigned char> allow_a(n, 0), allow_b(n, 0);
    for (std::size_t c = 0; c < n; ++c) {
      allow_a[c] = (side[c] & 1) == 0 || (side[c] & 2) != 0 ? 1 : 0;
      allow_b[c] = (side[c] & 1) == 0 || (side[c] & 4) != 0 ? 1 : 0;
    }
    const std::vector<std::int64_t> ext_a =
        extend_to_deepest(z, allow_a, nx, ny, a, ca, reach, lon, lat, dx, sy * kKmPerDeg);
    const std::vector<std::int64_t> ext_b =
        extend_to_deepest(z, allow_b, nx, ny, t, cb, reach, lon, lat, dx, sy * kKmPerDeg);
    std::vector<std::int64_t> cells(ext_a.rbegin(), ext_a.rend());
    if (!cells.empty()) cells.pop_back();  // the centre of side A starts `path`
    cells.insert(cells.end(), path.begin(), path.end());
    if (!ext_b.empty()) cells.insert(cells.end(), ext_b.begin() + 1, ext_b.end());
    std::vector<LonLat> pts;
    for (const std::int64_t c : cells)
      pts.push_back({lon[static_cast<std::size_t>(c)], lat[static_cast<std::size_t>(c)]});
    for (const std::size_t k : simplify(pts, 0.5 * std::max(sx, sy))) {
      line.lon_deg.push_back(pts[k].lon_deg);
      line.lat_deg.push_back(pts[k].lat_deg);
    }
    if (line.lon_deg.size() == 1) {  // everything in one cell
      line.lon_deg.push_back(line.lon_deg[0]);
      line.lat_deg.push_back(line.lat_deg[0]);
    }
    auto r = half_widths(line.lon_deg, line.lat_deg, rpx_channel, 0.0);
    const double e = -line.depth_m;
    add(std::move(line), raster::EditKind::kChannel, e, std::move(r));
  }

  // From cell `start` (at `from`), the cheapest path (deep water cheaper) through allowed wet
  // cells (z <= max(-h, z[start])) within `radius_deg` of `from` to the deepest of them (ties: the
  // cheaper, then the smaller index); [start] alone when none is deeper.
  std::vector<std::int64_t> extend_to_deepest(const std::vector<double>& z, const std::vector<unsigned char>& allow,
                                              std::int64_t nx, std::int64_t ny, std::int64_t start, LonLat from,
                                              double radius_deg, const std::vector<double>& lon,
                                              const std::vector<double>& lat, const std::vector<double>& dx,
                                              double dy) const {
    const auto n = static_cast<std::size_t>(nx * ny);
    const double zs = z[static_cast<std::size_t>(start)];
    const double zmax = std::isnan(zs) ? -h : std::max(-h, zs);
    const V3 f = unit(from.lon_deg, from.lat_deg);
    const double cos_r = std::cos(radius_deg * kDegToRad);
    const double D = std::max(h, 0.0) + 10.0;
    using Item = std::pair<double, std::int64_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
    std::vector<double> cost(n, kInf);
    std::vector<std::int64_t> prev(n, -1);
    cost[static_cast<std::size_t>(start)] = 0.0;
    q.push({0.0, start});
    std::int64_t best = start;
    while (!q.empty()) {
      const auto [v, c] = q.top();
      q.pop();
      if (v > cost[static_cast<std::size_t>(c)]) continue;
      const double zc = z[static_cast<std::size_t>(c)], zb = z[static_cast<std::size_t>(best)];
      if (!std::isnan(zc) && (std::isnan(zb) || zc < zb)) best = c;
      const std::int64_t i = c % nx, j = c / nx;
      const std::array<std::int64_t, 4> nb{i > 0 ? c - 1 : -1, i + 1 < nx ? c + 1 : -1, j > 0 ? c - nx : -1,
                                           j + 1 < ny ? c + nx : -1};
      for (std::size_t e = 0; e < 4; ++e) {
        const std::int64_t d = nb[e];
        if (d < 0) continue;
        const auto u = static_cast<std::size_t>(d);
        if (allow[u] == 0 || std::isnan(z[u]) || z[u] > zmax) continue;
        if (dot(unit(lon[u], lat[u]), f) < cos_r) continue;
        const double g = D / (std::max(-z[u], 0.0) + D);
        const double nv = v + (e < 2 ? dx[static_cast<std::size_t>(j)] : dy) * g * g;
        if (nv < cost[u]) {
          cost[u] = nv;
          prev[u] = c;
          q.push({nv, d});
        }
      }
    }
    std::vector<std::int64_t> ext;
    for (std::int64_t c = best; c >= 0; c = prev[static_cast<std::size_t>(c)]) ext.push_back(c);
    std::reverse(ext.begin(), ext.end());
    return ext;
  }

  // The sill (m) of the deepest path inside the corridor of a drawn line from its first vertex's
  // end to its last's, and where it is; +inf when no-data cuts it.
  double corridor_sill(const EditLine& l, LonLat& where) const {
    std::vector<V3> v;
    for (std::size_t k = 0; k < l.lon_deg.size(); ++k) v.push_back(unit(l.lon_deg[k], l.lat_deg[k]));
    double total = 0.0;
    for (std::size_t k = 0; k + 1 < v.size(); ++k) total += arc_deg(v[k], v[k + 1]);
    const double s0 = search_step(bathy, 1.0, 1e6);
    const double ds = std::max(s0, total / 4000.0);
    // Points along the line (the vertices and slerp points between) and their unit normals.
    std::vector<V3> along;
    for (std::size_t k = 0; k + 1 < v.size(); ++k) {
      const double ang = arc_deg(v[k], v[k + 1]);
      const int parts = std::max(1, static_cast<int>(std::ceil(ang / ds)));
      for (int q = 0; q < parts; ++q) {
        const double t = static_cast<double>(q) / parts, w = ang * kDegToRad, sw = std::sin(w);
        if (sw < 1e-15) {
          along.push_back(v[k]);
          continue;
        }
        const double fa = std::sin((1.0 - t) * w) / sw, fb = std::sin(t * w) / sw;
        along.push_back(normalized(
            {fa * v[k][0] + fb * v[k + 1][0], fa * v[k][1] + fb * v[k + 1][1], fa * v[k][2] + fb * v[k + 1][2]}));
      }
    }
    along.push_back(v.back());
    const auto ny = static_cast<std::int64_t>(along.size());
    double r_max = 0.0;
    for (std::size_t k = 0; k < along.size(); ++k) {
      const LonLat g = to_lonlat(along[k]);
      r_max = std::max(r_max, rpx_channel * pixel_arc_deg(lattice, rot, g.lon_deg, g.lat_deg));
    }
    const auto nt = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::ceil(r_max / s0)), 1, 100);
    const std::int64_t nx = 2 * nt + 1;
    const double dt = r_max / static_cast<double>(nt);
    std::vector<double> lon(static_cast<std::size_t>(nx * ny)), lat(lon.size()), z(lon.size());
    for (std::int64_t j = 0; j < ny; ++j) {
      const V3& p = along[static_cast<std::size_t>(j)];
      const V3& prev = along[static_cast<std::size_t>(std::max<std::int64_t>(0, j - 1))];
      const V3& next = along[static_cast<std::size_t>(std::min(ny - 1, j + 1))];
      V3 n = cross(p, {next[0] - prev[0], next[1] - prev[1], next[2] - prev[2]});
      const double ln = std::sqrt(dot(n, n));
      n = ln > 0.0 ? V3{n[0] / ln, n[1] / ln, n[2] / ln} : V3{0.0, 0.0, 0.0};
      for (std::int64_t i = 0; i < nx; ++i) {
        const double d = static_cast<double>(i - nt) * dt * kDegToRad;
        const V3 q = normalized({std::cos(d) * p[0] + std::sin(d) * n[0], std::cos(d) * p[1] + std::sin(d) * n[1],
                                 std::cos(d) * p[2] + std::sin(d) * n[2]});
        const LonLat g = to_lonlat(q);
        lon[static_cast<std::size_t>(j * nx + i)] = g.lon_deg;
        lat[static_cast<std::size_t>(j * nx + i)] = g.lat_deg;
      }
    }
    bathy.sample_points(lon.data(), lat.data(), nx * ny, z.data());
    std::vector<std::int64_t> sources;
    std::vector<unsigned char> target(z.size(), 0);
    for (std::int64_t i = 0; i < nx; ++i) {
      sources.push_back(i);
      target[static_cast<std::size_t>((ny - 1) * nx + i)] = 1;
    }
    std::vector<double> dxs(static_cast<std::size_t>(ny), dt * kKmPerDeg);
    std::vector<std::int64_t> path;
    const double m =
        minimax_path(z, nx, ny, sources, target, dxs, total / static_cast<double>(ny - 1) * kKmPerDeg, &path);
    if (std::isfinite(m)) {
      std::size_t top = 0;
      for (std::size_t k = 0; k < path.size(); ++k)
        if (z[static_cast<std::size_t>(path[k])] > z[static_cast<std::size_t>(path[top])]) top = k;
      const auto c = static_cast<std::size_t>(path[top]);
      where = {lon[c], lat[c]};
    }
    return m;
  }

  void drawn_line(const EditLine& l) {
    CarvedLine line;
    line.name = l.name;
    line.source = l.where;
    line.kind = l.kind;
    line.lon_deg = l.lon_deg;
    line.lat_deg = l.lat_deg;
    if (l.kind == LineKind::kBlockage) {
      const double top = std::isnan(l.height_m) ? kBlockageHeightM : l.height_m;
      line.height_m = std::max(top, -h + kCarveBelowThresholdM);
      line.depth_from =
          std::isnan(l.height_m) ? fmt::format("the default height {} m", kBlockageHeightM) : "stated (height_m)";
      if (line.height_m != top) line.depth_from += fmt::format(", raised above -mask.min_depth_m");
      auto r = half_widths(line.lon_deg, line.lat_deg, rpx_block, 0.0);
      const double e = line.height_m;
      add(std::move(line), raster::EditKind::kBlockage, e, std::move(r));
      return;
    }
    double min_half = 0.0;
    if (l.kind == LineKind::kChannel) {
      const double width = std::isnan(l.width_m) ? o.channel_width_m : l.width_m;
      min_half = 0.5 * width / 1000.0 / kKmPerDeg;
      line.depth_m = std::max(std::isnan(l.depth_m) ? o.channel_depth_m : l.depth_m, floor_depth);
      line.depth_from = std::isnan(l.depth_m) ? "mask.channel_depth_m" : "stated (depth_m)";
    } else if (!std::isnan(l.depth_m)) {
      line.depth_m = std::max(l.depth_m, floor_depth);
      line.depth_from = "stated (depth_m)";
    } else {
      LonLat where{kNaN, kNaN};
      const double m = corridor_sill(l, where);
      line.raster_sill_m = std::isfinite(m) ? m : kNaN;
      line.sill = where;
      if (std::isfinite(m) && m <= -h) {
        line.depth_m = std::max(-m, floor_depth);
        line.depth_from =
            fmt::format("the raster's sill {:.0f} m at {:.3f}°E {:.3f}°N on the deepest path along the line", -m,
                        where.lon_deg, where.lat_deg);
      } else {
        line.depth_m = std::max(o.channel_depth_m, floor_depth);
        line.depth_from =
            std::isfinite(m)
                ? fmt::format("mask.channel_depth_m (the raster closes the line: {:+.0f} m at {:.3f}°E {:.3f}°N)", m,
                              where.lon_deg, where.lat_deg)
                : std::string("mask.channel_depth_m (no-data cuts the line)");
      }
    }
    if (!std::isnan(l.depth_m) && line.depth_m > l.depth_m)
      line.depth_from += fmt::format(", deepened to {} m below -mask.min_depth_m", kCarveBelowThresholdM);
    auto r = half_widths(line.lon_deg, line.lat_deg, rpx_channel, min_half);
    const double e = -line.depth_m;
    add(std::move(line), raster::EditKind::kChannel, e, std::move(r));
  }
};

}  // namespace

double pixel_arc_deg(const Lattice& lattice, const PoleRotation& rot, double lon_deg, double lat_deg) {
  const double p = lattice.pixel_deg();
  if (!lattice.mercator()) return p;
  const LonLat r = geographic_to_lattice(rot, {lon_deg, lat_deg});
  return p * std::cos(r.lat_deg * kDegToRad);
}

void check_passage_names(const config::MaskOptions& options) {
  std::vector<std::string> bad;
  for (const std::string& name : options.passages_open) {
    if (find_passage(name) != nullptr) continue;
    std::string best;
    std::size_t bd = 4;
    for (const Passage& p : critical_passages())
      if (const std::size_t d = edit_distance(p.name, name, /*ignore_case=*/true); d < bd) {
        bd = d;
        best = p.name;
      }
    bad.push_back(fmt::format("\"{}\"{}", name, best.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", best)));
  }
  if (bad.empty()) return;
  std::string names;
  for (const Passage& p : critical_passages()) names += fmt::format("{}{}", names.empty() ? "" : ", ", p.name);
  std::string list;
  for (const std::string& b : bad) list += (list.empty() ? "" : ", ") + b;
  throw ConfigError(
      fmt::format("mask.passages_open: {} {} not in the table of passages; the names are: {} (a passage "
                  "elsewhere: draw it in a line file, mask.transects)",
                  list, bad.size() == 1 ? "is" : "are", names));
}

Carving plan_carving(const config::MaskOptions& options, const Lattice& lattice, const PoleRotation& rot,
                     const raster::Bathymetry& bathy) {
  check_passage_names(options);
  Planner pl(options, lattice, rot, bathy);
  pl.h = options.min_depth_m;
  pl.floor_depth = std::max(pl.h, 0.0) + kCarveBelowThresholdM;
  const double k = static_cast<double>(std::max(1, options.cursor));
  pl.rpx_channel = (k + 1.0) / std::sqrt(2.0) + 0.25;
  pl.rpx_block = std::sqrt(0.5) + 0.25;
  std::vector<const Passage*> done;
  for (const std::string& name : options.passages_open) {
    const Passage* p = find_passage(name);
    if (std::find(done.begin(), done.end(), p) != done.end()) continue;  // two names of one passage
    done.push_back(p);
    pl.table_passage(*p);
  }
  if (!options.transects.empty())
    for (const EditLine& l : read_edit_lines(options.transects, options.transects_layer, "mask.transects", false))
      pl.drawn_line(l);
  if (!options.channels.empty())
    for (const EditLine& l : read_edit_lines(options.channels, options.channels_layer, "mask.channels", true))
      pl.drawn_line(l);
  if (!pl.corridors.empty()) pl.out.edits = std::make_shared<const raster::ElevationEdits>(std::move(pl.corridors));
  return std::move(pl.out);
}

double minimax_path(const std::vector<double>& z, std::int64_t nx, std::int64_t ny,
                    const std::vector<std::int64_t>& sources, const std::vector<unsigned char>& is_target,
                    const std::vector<double>& dx, double dy, std::vector<std::int64_t>* path) {
  const auto n = static_cast<std::size_t>(nx * ny);
  using Item = std::pair<double, std::int64_t>;  // ties by cell index: deterministic
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  const auto neighbours = [nx, ny](std::int64_t c, std::array<std::int64_t, 4>& nb) {
    const std::int64_t i = c % nx, j = c / nx;
    nb = {i > 0 ? c - 1 : -1, i + 1 < nx ? c + 1 : -1, j > 0 ? c - nx : -1, j + 1 < ny ? c + nx : -1};
  };
  std::vector<double> best(n, kInf);
  for (const std::int64_t s : sources) {
    const auto u = static_cast<std::size_t>(s);
    if (std::isnan(z[u]) || z[u] >= best[u]) continue;
    best[u] = z[u];
    q.push({z[u], s});
  }
  double sill = kInf;
  std::int64_t reached = -1;
  std::array<std::int64_t, 4> nb{};
  while (!q.empty()) {
    const auto [v, c] = q.top();
    q.pop();
    if (v > best[static_cast<std::size_t>(c)]) continue;
    if (is_target[static_cast<std::size_t>(c)] != 0) {
      sill = v;
      reached = c;
      break;
    }
    neighbours(c, nb);
    for (const std::int64_t d : nb) {
      if (d < 0 || std::isnan(z[static_cast<std::size_t>(d)])) continue;
      const double nv = std::max(v, z[static_cast<std::size_t>(d)]);
      if (nv < best[static_cast<std::size_t>(d)]) {
        best[static_cast<std::size_t>(d)] = nv;
        q.push({nv, d});
      }
    }
  }
  if (path == nullptr || reached < 0) return sill;
  // The cheapest path through cells <= sill, deep water cheaper (the middle of the channel).
  const double D = std::max(-sill, 0.0) + 10.0;
  const auto weight = [D](double zz) {
    const double f = D / (std::max(-zz, 0.0) + D);
    return f * f;
  };
  std::vector<double> cost(n, kInf);
  std::vector<std::int64_t> prev(n, -1);
  q = {};
  for (const std::int64_t s : sources) {
    const auto u = static_cast<std::size_t>(s);
    if (std::isnan(z[u]) || z[u] > sill || cost[u] == 0.0) continue;
    cost[u] = 0.0;
    q.push({0.0, s});
  }
  std::int64_t end = -1;
  while (!q.empty()) {
    const auto [v, c] = q.top();
    q.pop();
    if (v > cost[static_cast<std::size_t>(c)]) continue;
    if (is_target[static_cast<std::size_t>(c)] != 0) {
      end = c;
      break;
    }
    neighbours(c, nb);
    for (std::size_t e = 0; e < 4; ++e) {
      const std::int64_t d = nb[e];
      if (d < 0) continue;
      const double zd = z[static_cast<std::size_t>(d)];
      if (std::isnan(zd) || zd > sill) continue;
      const double len = e < 2 ? dx[static_cast<std::size_t>(c / nx)] : dy;
      const double nv = v + len * weight(zd);
      if (nv < cost[static_cast<std::size_t>(d)]) {
        cost[static_cast<std::size_t>(d)] = nv;
        prev[static_cast<std::size_t>(d)] = c;
        q.push({nv, d});
      }
    }
  }
  path->clear();
  for (std::int64_t c = end; c >= 0; c = prev[static_cast<std::size_t>(c)]) path->push_back(c);
  std::reverse(path->begin(), path->end());
  return sill;
}

Json carving_json(const Carving& c) {
  Json arr = Json::array();
  for (const CarvedLine& l : c.lines) {
    Json line = Json::array();
    for (std::size_t k = 0; k < l.lon_deg.size(); ++k) line.push_back(Json::array({l.lon_deg[k], l.lat_deg[k]}));
    Json j{{"name", l.name},
           {"source", l.source},
           {"kind", std::string(name_of(l.kind))},
           {"depth_from", l.depth_from},
           {"half_width_km", {l.half_width_km_min, l.half_width_km_max}},
           {"length_km", l.length_km},
           {"line", line}};
    if (l.kind == LineKind::kBlockage)
      j["height_m"] = l.height_m;
    else
      j["depth_m"] = l.depth_m;
    if (!std::isnan(l.raster_sill_m)) {
      j["raster_sill_elevation_m"] = l.raster_sill_m;
      j["sill"] = Json::array({l.sill.lon_deg, l.sill.lat_deg});
    }
    arr.push_back(j);
  }
  return arr;
}

std::vector<std::string> describe_carving(const Carving& c) {
  std::vector<std::string> out;
  for (const CarvedLine& l : c.lines) {
    const std::string what = l.kind == LineKind::kBlockage
                                 ? fmt::format("blockage, land at {:+.0f} m ({})", l.height_m, l.depth_from)
                                 : fmt::format("{} {:.0f} m deep, from {}", l.kind, l.depth_m, l.depth_from);
    const std::string width =
        std::abs(l.half_width_km_max - l.half_width_km_min) < 0.05 * l.half_width_km_max
            ? fmt::format("{:.3g} km", 2.0 * l.half_width_km_max)
            : fmt::format("{:.3g}-{:.3g} km", 2.0 * l.half_width_km_min, 2.0 * l.half_width_km_max);
    out.push_back(
        fmt::format("{} [{}]: {}; corridor {} wide along {:.0f} km", l.name, l.source, what, width, l.length_km));
  }
  for (const std::string& s : c.skipped) out.push_back(s);
  return out;
}

}  // namespace aq::mask

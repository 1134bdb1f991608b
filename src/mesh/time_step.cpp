// SPDX-License-Identifier: GPL-3.0-or-later
// The explicit barotropic time step of a mesh (see time_step.hpp).
#include "mesh/time_step.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/types.hpp"
#include "quadtree/parallel.hpp"

namespace aq::mesh {

namespace {

constexpr double kEarthRadiusM = 6371008.8;
constexpr double kGravity = 9.81;
// Edges shorter than this are the lattice's pole row (its nodes are one point; the geographic
// writers replace that row by a pole cap): not an edge a model sees.
constexpr double kMinEdgeM = 1e-3;

// The haversine distance, given cos φ of both ends (computed once per node by the callers that
// measure every edge: two of the six sines and cosines of each edge).
double great_circle_m(double lon1, double lat1, double cos_lat1, double lon2, double lat2, double cos_lat2) {
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad;
  const double dp = p2 - p1, dl = (lon2 - lon1) * kDegToRad;
  const double sp = std::sin(dp / 2), sl = std::sin(dl / 2);
  const double a = sp * sp + cos_lat1 * cos_lat2 * sl * sl;
  return 2.0 * kEarthRadiusM * std::asin(std::min(1.0, std::sqrt(a)));
}

double great_circle_m(double lon1, double lat1, double lon2, double lat2) {
  return great_circle_m(lon1, lat1, std::cos(lat1 * kDegToRad), lon2, lat2, std::cos(lat2 * kDegToRad));
}

// A lower bound (m) of great_circle_m for the same ends, without a trigonometric call: from the
// same half-angle arguments x, sin x ≥ x − x³/6 (x ≥ 0; sin² is bounded by the square of the
// bound's positive part) and asin y ≥ y, less a relative 1e-12 for the rounding of either side
// (both take the same rounded arguments; their other operations differ by a few ulp).
double great_circle_lower_bound_m(double lon1, double lat1, double cos_lat1, double lon2, double lat2,
                                  double cos_lat2) {
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad;
  const double hp = std::abs((p2 - p1) / 2), hl = std::abs((lon2 - lon1) * kDegToRad / 2);
  const double sp = std::max(0.0, hp - hp * hp * hp / 6.0), sl = std::max(0.0, hl - hl * hl * hl / 6.0);
  const double cc = cos_lat1 * cos_lat2;
  // cc < 0 only for latitudes beyond ±90°: then cc·sin² ≥ cc·x², as |sin x| ≤ |x|.
  const double a = sp * sp + (cc >= 0.0 ? cc * sl * sl : cc * hl * hl);
  return 2.0 * kEarthRadiusM * std::min(1.0, std::sqrt(std::max(0.0, a))) * (1.0 - 1e-12);
}

// H of triangle `tri`: the deepest of its nodes, at least min_depth_m.
double triangle_depth(const std::array<NodeId, 3>& tri, const double* depth_m, double min_depth_m) {
  double h = min_depth_m;
  for (const NodeId v : tri)
    if (depth_m[v] > h) h = depth_m[v];
  return h;
}

// dt (s) of triangle `tri`: its shortest edge over 1 mm / √(g·h) (+inf without such an edge).
double triangle_dt(const std::array<NodeId, 3>& tri, const double* lon_deg, const double* lat_deg,
                   const double* cos_lat, double h) {
  double edge = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const auto a = static_cast<std::size_t>(tri[static_cast<std::size_t>(k)]);
    const auto b = static_cast<std::size_t>(tri[static_cast<std::size_t>((k + 1) % 3)]);
    const double len = great_circle_m(lon_deg[a], lat_deg[a], cos_lat[a], lon_deg[b], lat_deg[b], cos_lat[b]);
    if (len > kMinEdgeM) edge = std::min(edge, len);
  }
  return edge / std::sqrt(kGravity * h);
}

// cos φ of every node (radians from degrees as great_circle_m converts them), once per run of
// nodes of one latitude (the same bits): the lattice's nodes are numbered by row (mesh.hpp).
std::vector<double> node_cos_lat(const std::vector<double>& lat_deg) {
  const auto nodes = static_cast<std::int64_t>(lat_deg.size());
  std::vector<double> cos_lat(lat_deg.size());
  const double* lat = lat_deg.data();
  double* out = cos_lat.data();
  quadtree::for_each_block(nodes, quadtree::block_count(nodes, 16), [&](int, std::int64_t begin, std::int64_t end) {
    std::uint64_t row_bits = 0;
    double row_cos = 0.0;
    for (std::int64_t k = begin; k < end; ++k) {
      const auto bits = std::bit_cast<std::uint64_t>(lat[k]);
      if (k == begin || bits != row_bits) {
        row_bits = bits;
        row_cos = std::cos(lat[k] * kDegToRad);
      }
      out[k] = row_cos;
    }
  });
  return cos_lat;
}

double round6(double x) { return std::round(x * 1e6) / 1e6; }

}  // namespace

std::vector<double> triangle_time_steps(const std::vector<double>& lon_deg, const std::vector<double>& lat_deg,
                                        const std::vector<double>& depth_m,
                                        const std::vector<std::array<NodeId, 3>>& triangles, double min_depth_m) {
  const auto n = static_cast<std::int64_t>(triangles.size());
  const std::vector<double> cos_lat = node_cos_lat(lat_deg);
  std::vector<double> dt(static_cast<std::size_t>(n));
  const double *lon = lon_deg.data(), *lat = lat_deg.data(), *cl = cos_lat.data(), *depth = depth_m.data();
  const std::array<NodeId, 3>* tri = triangles.data();
  double* out = dt.data();
#pragma omp parallel for schedule(static) default(none) shared(lon, lat, cl, depth, tri, out, n, min_depth_m)
  for (std::int64_t t = 0; t < n; ++t)
    out[t] = triangle_dt(tri[t], lon, lat, cl, triangle_depth(tri[t], depth, min_depth_m));
  return dt;
}

SmallestTimeStep smallest_time_step(const std::vector<double>& lon_deg, const std::vector<double>& lat_deg,
                                    const std::vector<double>& depth_m,
                                    const std::vector<std::array<NodeId, 3>>& triangles, double min_depth_m) {
  const auto n = static_cast<std::int64_t>(triangles.size());
  const std::vector<double> cos_lat = node_cos_lat(lat_deg);
  const double *lon = lon_deg.data(), *lat = lat_deg.data(), *cl = cos_lat.data(), *depth = depth_m.data();
  const std::array<NodeId, 3>* tri = triangles.data();
  // Each block keeps its own smallest (dt, first triangle) and measures a triangle's edges only
  // when their lower bounds allow a dt at most that small. A block's smallest is never below the
  // overall one, so every triangle whose dt equals the overall smallest is measured in its block:
  // the result is that of a full scan, for any number of blocks.
  const int blocks = quadtree::block_count(n, 16);
  std::vector<SmallestTimeStep> best(static_cast<std::size_t>(blocks));
  quadtree::for_each_block(n, blocks, [&](int b, std::int64_t begin, std::int64_t end) {
    SmallestTimeStep mine;
    for (std::int64_t t = begin; t < end; ++t) {
      const std::array<NodeId, 3>& v = tri[t];
      const double h = triangle_depth(v, depth, min_depth_m);
      if (mine.triangle >= 0) {
        double bound = std::numeric_limits<double>::infinity();  // ≤ the shortest edge over 1 mm
        for (int k = 0; k < 3; ++k) {
          const auto a = static_cast<std::size_t>(v[static_cast<std::size_t>(k)]);
          const auto c = static_cast<std::size_t>(v[static_cast<std::size_t>((k + 1) % 3)]);
          bound = std::min(bound, great_circle_lower_bound_m(lon[a], lat[a], cl[a], lon[c], lat[c], cl[c]));
        }
        if (bound / std::sqrt(kGravity * h) > mine.dt_s) continue;
      }
      const double dt = triangle_dt(v, lon, lat, cl, h);
      if (std::isnan(dt) && t != 0) continue;  // as std::min_element: NaN only as the first entry
      if (mine.triangle < 0 || dt < mine.dt_s) mine = {dt, t};
    }
    best[static_cast<std::size_t>(b)] = mine;
  });
  SmallestTimeStep r;
  for (const SmallestTimeStep& b : best)  // blocks in triangle order: the first smallest wins ties
    if (b.triangle >= 0 && (r.triangle < 0 || b.dt_s < r.dt_s)) r = b;
  return r;
}

namespace {

// The smallest of `dt` (the first: deterministic) and its triangle's shortest edge, H (from
// `depth`, at least min_depth_m) and first node.
struct Limiting {
  double dt_s = 0.0;
  std::int64_t triangle = -1;
  double edge_m = 0.0, depth_m = 0.0, lon_deg = 0.0, lat_deg = 0.0, max_elevation_m = 0.0;
};

Limiting limiting(const Mesh& mesh, const std::vector<double>& depth, const SmallestTimeStep& smallest,
                  double min_depth_m) {
  Limiting r;
  r.dt_s = smallest.dt_s;
  r.triangle = smallest.triangle;
  const auto& tri = mesh.triangles[static_cast<std::size_t>(r.triangle)];
  double edge = std::numeric_limits<double>::infinity(), h = min_depth_m;
  r.max_elevation_m = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const auto a = static_cast<std::size_t>(tri[static_cast<std::size_t>(k)]);
    const auto b = static_cast<std::size_t>(tri[static_cast<std::size_t>((k + 1) % 3)]);
    const double len = great_circle_m(mesh.lon_deg[a], mesh.lat_deg[a], mesh.lon_deg[b], mesh.lat_deg[b]);
    if (len > kMinEdgeM) edge = std::min(edge, len);
    h = std::max(h, depth[a]);
    r.max_elevation_m = std::max(r.max_elevation_m, mesh.depth_m[a]);
  }
  r.edge_m = edge;
  r.depth_m = h;
  r.lon_deg = mesh.lon_deg[static_cast<std::size_t>(tri[0])];
  r.lat_deg = mesh.lat_deg[static_cast<std::size_t>(tri[0])];
  return r;
}

}  // namespace

TimeStep time_step(const Mesh& mesh, double min_depth_m, double dt_s, double courant_max, double flood_level_m) {
  TimeStep r;
  r.min_depth_m = min_depth_m;
  r.dt_s = dt_s;
  r.courant_max = courant_max;
  std::vector<double> depth(mesh.depth_m.size());
  for (std::size_t k = 0; k < depth.size(); ++k) depth[k] = -mesh.depth_m[k];
  r.triangles = static_cast<std::int64_t>(mesh.triangles.size());
  if (mesh.triangles.empty()) return r;
  // Every triangle's dt only for the Courant numbers; the smallest alone measures few edges.
  const std::vector<double> dt =
      dt_s > 0.0 ? triangle_time_steps(mesh.lon_deg, mesh.lat_deg, depth, mesh.triangles, min_depth_m)
                 : std::vector<double>();
  const Limiting at_rest = limiting(
      mesh, depth, smallest_time_step(mesh.lon_deg, mesh.lat_deg, depth, mesh.triangles, min_depth_m), min_depth_m);
  r.max_stable_dt_s = at_rest.dt_s;
  r.limiting_triangle = at_rest.triangle;
  r.limiting_edge_m = at_rest.edge_m;
  r.limiting_depth_m = at_rest.depth_m;
  r.limiting_lon_deg = at_rest.lon_deg;
  r.limiting_lat_deg = at_rest.lat_deg;
  if (flood_level_m > 0.0) {  // the highest water the floodplain is built for over every node
    std::vector<double> flooded(depth.size());
    for (std::size_t k = 0; k < depth.size(); ++k) flooded[k] = depth[k] + flood_level_m;
    const Limiting wd =
        limiting(mesh, flooded, smallest_time_step(mesh.lon_deg, mesh.lat_deg, flooded, mesh.triangles, min_depth_m),
                 min_depth_m);
    TimeStep::WettingDrying& w = r.wetting_drying;
    w.flood_level_m = flood_level_m;
    w.max_stable_dt_s = wd.dt_s;
    w.limiting_triangle = wd.triangle;
    w.limiting_edge_m = wd.edge_m;
    w.limiting_depth_m = wd.depth_m;
    w.limiting_lon_deg = wd.lon_deg;
    w.limiting_lat_deg = wd.lat_deg;
    w.limiting_elevation_m = wd.max_elevation_m;
  }
  if (dt_s > 0.0) {
    std::vector<double> cr(dt.size());
    for (std::size_t k = 0; k < dt.size(); ++k) cr[k] = dt_s / dt[k];
    r.above_courant_max = std::count_if(cr.begin(), cr.end(), [&](double c) { return c > courant_max; });
    for (std::size_t k = 0; k < cr.size(); ++k) {
      if (!(cr[k] > courant_max)) continue;
      if (k < mesh.triangle_level.size()) {
        const std::size_t l = mesh.triangle_level[k];
        if (r.above_by_level.size() <= l) r.above_by_level.resize(l + 1, 0);
        ++r.above_by_level[l];
      }
      bool coast = false;
      for (const NodeId v : mesh.triangles[k])
        coast = coast || (static_cast<std::size_t>(v) < mesh.node_flags.size() &&
                          (mesh.node_flags[static_cast<std::size_t>(v)] & kNodeBoundary) != 0);
      if (coast) ++r.above_touching_coast;
    }
    std::sort(cr.begin(), cr.end());
    for (const double p : {0.0, 0.5, 0.9, 0.99, 1.0})
      r.courant_percentiles.push_back(
          cr[static_cast<std::size_t>(std::llround(p * static_cast<double>(cr.size() - 1)))]);
  }
  return r;
}

Json time_step_json(const TimeStep& t) {
  Json j{{"max_stable_dt_s", round6(t.max_stable_dt_s)},
         {"dt_at_courant_max_s", round6(t.max_stable_dt_s * t.courant_max)},
         {"formula", "min over triangles of shortest edge / sqrt(g * H), H = deepest node, at least min_depth_m"},
         {"gravity_m_s2", kGravity},
         {"min_depth_m", t.min_depth_m},
         {"triangles", t.triangles},
         {"limiting_triangle", t.limiting_triangle},
         {"limiting_edge_m", round6(t.limiting_edge_m)},
         {"limiting_depth_m", round6(t.limiting_depth_m)},
         {"limiting_lon_deg", round6(t.limiting_lon_deg)},
         {"limiting_lat_deg", round6(t.limiting_lat_deg)}};
  if (t.wetting_drying.flood_level_m > 0.0) {
    const TimeStep::WettingDrying& w = t.wetting_drying;
    j["wetting_drying"] =
        Json{{"flood_level_m", w.flood_level_m},
             {"max_stable_dt_s", round6(w.max_stable_dt_s)},
             {"dt_at_courant_max_s", round6(w.max_stable_dt_s * t.courant_max)},
             {"formula",
              "min over triangles of shortest edge / sqrt(g * H), H = flood_level_m - elevation at the deepest "
              "node (the water the floodplain is built for over every node), at least min_depth_m"},
             {"limiting_triangle", w.limiting_triangle},
             {"limiting_edge_m", round6(w.limiting_edge_m)},
             {"limiting_depth_m", round6(w.limiting_depth_m)},
             {"limiting_highest_node_elevation_m", round6(w.limiting_elevation_m)},
             {"limiting_lon_deg", round6(w.limiting_lon_deg)},
             {"limiting_lat_deg", round6(w.limiting_lat_deg)}};
  }
  if (t.dt_s > 0.0) {
    Json c{{"dt_s", t.dt_s},
           {"courant_max", t.courant_max},
           {"above_courant_max", t.above_courant_max},
           {"above_by_level", t.above_by_level},
           {"above_touching_coast", t.above_touching_coast}};
    const char* names[] = {"min", "median", "p90", "p99", "max"};
    for (std::size_t k = 0; k < t.courant_percentiles.size(); ++k) c[names[k]] = round6(t.courant_percentiles[k]);
    j["courant"] = c;
  }
  return j;
}

}  // namespace aq::mesh

// SPDX-License-Identifier: GPL-3.0-or-later
// The pole cap triangulation (see pole_cap.hpp).
#include "mesh/pole_cap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace aq::mesh {

namespace {

// A node of the cap in the pole's own frame: colatitude r (rad) and unwrapped angle θ (deg).
struct CapPoint {
  double r = 0.0, theta_deg = 0.0;
};

std::array<double, 3> unit_vector(const CapPoint& p) {
  const double t = p.theta_deg * kDegToRad;
  return {std::sin(p.r) * std::cos(t), std::sin(p.r) * std::sin(t), std::cos(p.r)};
}

double chord2(const CapPoint& a, const CapPoint& b) {
  const auto u = unit_vector(a), v = unit_vector(b);
  return (u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) + (u[2] - v[2]) * (u[2] - v[2]);
}

// One closed ring of cap ids with their points, ordered by angle from the first.
struct Ring {
  std::vector<NodeId> ids;
  std::vector<CapPoint> points;
};

// Zipper between the outer ring `a` and the inner ring `b`: |a| + |b| triangles, anticlockwise
// in the (λ, φ) plane of the North-pole frame. Starts at the edge (a[0], the last node of b)
// and, at each step, adds the shorter of the two possible new edges.
void zip(const Ring& a, const Ring& b, std::vector<std::array<NodeId, 3>>& out) {
  const auto na = static_cast<std::int64_t>(a.ids.size()), nb = static_cast<std::int64_t>(b.ids.size());
  // Unrolled sequences: a[0..na] (a[na] = a[0] one turn later), b[-1..nb-1] as bb[0..nb].
  auto ap = [&](std::int64_t i) {
    CapPoint p = a.points[static_cast<std::size_t>(i % na)];
    if (i >= na) p.theta_deg += 360.0;
    return p;
  };
  auto bp = [&](std::int64_t j) {
    if (j == 0) {
      CapPoint p = b.points[static_cast<std::size_t>(nb - 1)];
      p.theta_deg -= 360.0;
      return p;
    }
    return b.points[static_cast<std::size_t>(j - 1)];
  };
  auto aid = [&](std::int64_t i) { return a.ids[static_cast<std::size_t>(i % na)]; };
  auto bid = [&](std::int64_t j) { return b.ids[static_cast<std::size_t>(j == 0 ? nb - 1 : j - 1)]; };
  std::int64_t i = 0, j = 0;
  while (i < na || j < nb) {
    const bool outer = j == nb || (i < na && chord2(ap(i + 1), bp(j)) <= chord2(ap(i), bp(j + 1)));
    if (outer) {
      out.push_back({aid(i), aid(i + 1), bid(j)});
      ++i;
    } else {
      out.push_back({aid(i), bid(j + 1), bid(j)});
      ++j;
    }
  }
}

}  // namespace

PoleCap make_pole_cap(const std::vector<double>& ring_rlon_deg, double ring_rlat_deg, bool north) {
  const auto n0 = static_cast<std::int64_t>(ring_rlon_deg.size());
  const double r0 = (90.0 - (north ? ring_rlat_deg : -ring_rlat_deg)) * kDegToRad;
  if (n0 < 3 || !(r0 > 0.0) || !(r0 < kPi / 2.0)) {
    throw InternalError(fmt::format("pole cap: ring of {} nodes at latitude {}° for the {} pole", n0, ring_rlat_deg,
                                    north ? "North" : "South"));
  }
  for (std::int64_t k = 1; k < n0; ++k) {
    if (!(ring_rlon_deg[static_cast<std::size_t>(k)] > ring_rlon_deg[static_cast<std::size_t>(k - 1)])) {
      throw InternalError("pole cap: ring longitudes are not strictly ascending");
    }
  }
  if (!(ring_rlon_deg.back() - ring_rlon_deg.front() < 360.0)) {
    throw InternalError("pole cap: ring longitudes span 360° or more");
  }

  // Ring 0, then the inner rings. The size s grows from h (the mean spacing of ring 0) by
  // kGrowth per unit of distance towards the pole; rings are s·√3/2 apart (equilateral
  // triangles), all distances stretched so that the last ring is one step from the pole; ring k holds
  // 2π sin(r_k) / s(r_k) nodes, never more than the ring outside it.
  constexpr double kGrowth = 0.25;
  const double theta0 = ring_rlon_deg.front();
  const double h = 2.0 * kPi * std::sin(r0) / static_cast<double>(n0);
  auto size = [&](double r) { return h + kGrowth * (r0 - r); };
  std::vector<double> radii;  // colatitudes of the inner rings before the stretch
  double r = r0;
  double last_step = 0.0;
  while (true) {
    last_step = size(r) * std::sqrt(3.0) / 2.0;
    if (r - last_step <= 0.5 * last_step) break;  // the pole is closer than half a step: stop
    r -= last_step;
    radii.push_back(r);
  }
  // Stretch the ring distances so that the gap from the last ring to the pole is one step.
  const double stretch = r0 / (r0 - r + last_step);
  PoleCap cap;
  std::vector<CapPoint> points;  // new nodes, in the frame of the pole
  Ring outer;
  for (std::int64_t k = 0; k < n0; ++k) {
    outer.ids.push_back(static_cast<NodeId>(k));
    outer.points.push_back({r0, ring_rlon_deg[static_cast<std::size_t>(k)]});
  }
  // Ring k's nodes are equally spaced in G = w·F0 + (1 − w)·(θ − θ0)/360, F0 the fraction of
  // ring-0 nodes west of θ and w = 2^-k: ring 1 follows half of ring 0's uneven spacing (finer
  // squares below it), the inner rings ever less, so no triangle between rings spans a 4:1 step.
  auto ring0 = [&](std::int64_t i) {
    return i < n0 ? ring_rlon_deg[static_cast<std::size_t>(i)] : ring_rlon_deg.front() + 360.0;
  };
  auto blend = [&](double w, std::int64_t i) {
    return w * static_cast<double>(i) / static_cast<double>(n0) + (1.0 - w) * (ring0(i) - theta0) / 360.0;
  };
  std::int64_t prev_n = n0;
  for (const double raw : radii) {
    const double rk = r0 - (r0 - raw) * stretch;
    const std::int64_t n =
        std::clamp<std::int64_t>(std::llround(2.0 * kPi * std::sin(rk) / size(raw)), std::int64_t{3}, prev_n);
    Ring inner;
    const double w = std::pow(0.5, cap.rings + 1);
    std::int64_t seg = 0;  // segment [a_seg, a_seg+1] of ring 0 holding the current target
    for (std::int64_t m = 0; m < n; ++m) {
      const double target = (static_cast<double>(m) + 0.5) / static_cast<double>(n);
      while (seg + 1 < n0 && blend(w, seg + 1) <= target) ++seg;
      const double g0 = blend(w, seg), g1 = blend(w, seg + 1);
      const double theta = ring0(seg) + (ring0(seg + 1) - ring0(seg)) * (target - g0) / (g1 - g0);
      inner.ids.push_back(static_cast<NodeId>(n0 + static_cast<std::int64_t>(points.size())));
      const CapPoint p{rk, theta};
      inner.points.push_back(p);
      points.push_back(p);
    }
    zip(outer, inner, cap.triangles);
    outer = std::move(inner);
    prev_n = n;
    ++cap.rings;
  }
  // The last ring bounds the polar island, wet area on the left: westward round the North pole,
  // eastward round the South pole (mirrored below).
  cap.island.assign(outer.ids.rbegin(), outer.ids.rend());
  cap.island_radius_deg = outer.points.front().r / kDegToRad;

  // Into lattice coordinates; the South cap is the mirror image (its triangles and island turn
  // round).
  for (const CapPoint& p : points) {
    const double lat = 90.0 - p.r / kDegToRad;
    cap.rlon_deg.push_back(p.theta_deg);
    cap.rlat_deg.push_back(north ? lat : -lat);
  }
  if (!north) {
    for (auto& t : cap.triangles) std::swap(t[1], t[2]);
    std::reverse(cap.island.begin(), cap.island.end());
  }
  return cap;
}

}  // namespace aq::mesh

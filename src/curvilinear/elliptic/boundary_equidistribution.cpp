// SPDX-License-Identifier: GPL-3.0-or-later
// 1-D equidistribution of boundary nodes (seed 004 Sec. 1; digest B.2); see boundary_equidistribution.hpp.
#include "curvilinear/elliptic/boundary_equidistribution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace aq::curvilinear {

ArcPolyline::ArcPolyline(std::vector<PlanePoint> pts) : points(std::move(pts)) {
  if (points.size() < 2) throw InternalError("ArcPolyline: fewer than 2 points");
  arc.resize(points.size());
  arc[0] = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k)
    arc[k] = arc[k - 1] + std::hypot(points[k].x - points[k - 1].x, points[k].y - points[k - 1].y);
}

void ArcPolyline::locate(double a, int& k, double& t) const {
  const int last = static_cast<int>(points.size()) - 2;
  const auto it = std::upper_bound(arc.begin(), arc.end(), a);
  k = std::clamp(static_cast<int>(it - arc.begin()) - 1, 0, last);
  const double len = arc[static_cast<std::size_t>(k) + 1] - arc[static_cast<std::size_t>(k)];
  t = len > 0.0 ? std::clamp((a - arc[static_cast<std::size_t>(k)]) / len, 0.0, 1.0) : 0.0;
}

PlanePoint ArcPolyline::at(double a) const {
  int k = 0;
  double t = 0.0;
  locate(a, k, t);
  const PlanePoint& p = points[static_cast<std::size_t>(k)];
  const PlanePoint& q = points[static_cast<std::size_t>(k) + 1];
  return {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
}

std::vector<double> equidistribute(const ArcPolyline& line, int n, const ControlFunction& w) {
  if (n < 2) throw InternalError("equidistribute: fewer than 2 nodes");
  const double len = line.length();
  std::vector<double> s(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) s[static_cast<std::size_t>(k)] = len * k / (n - 1);
  if (w.is_unity() || len <= 0.0) return s;
  constexpr int kMaxSweeps = 100;
  constexpr double kOmega = 0.5;
  std::vector<double> rho(static_cast<std::size_t>(n - 1)), cum(static_cast<std::size_t>(n)), next(s.size());
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    cum[0] = 0.0;
    for (std::size_t k = 0; k + 1 < s.size(); ++k) {
      const PlanePoint m = line.at(0.5 * (s[k] + s[k + 1]));
      rho[k] = w(m.x, m.y);
      if (!(rho[k] > 0.0) || !std::isfinite(rho[k]))
        throw ConfigError(fmt::format(
            "regional.weight: the control function w = {} at ({:.6g}, {:.6g}) on the contour: must be finite and > 0",
            rho[k], m.x, m.y));
      cum[k + 1] = cum[k] + rho[k] * (s[k + 1] - s[k]);
    }
    // New node k at W = k/(n−1)·W_total, inverting the piecewise linear W(s).
    double change = 0.0;
    std::size_t piece = 0;
    next[0] = 0.0;
    next.back() = len;
    for (int k = 1; k < n - 1; ++k) {
      const double target = cum.back() * k / (n - 1);
      while (piece + 2 < cum.size() && cum[piece + 1] < target) ++piece;
      const double sk = s[piece] + (target - cum[piece]) / rho[piece];
      next[static_cast<std::size_t>(k)] = (1.0 - kOmega) * s[static_cast<std::size_t>(k)] + kOmega * sk;
      change = std::max(change, std::fabs(next[static_cast<std::size_t>(k)] - s[static_cast<std::size_t>(k)]));
    }
    s.swap(next);
    if (change < 1e-10 * len) break;
  }
  return s;
}

std::vector<PlanePoint> equidistributed_points(const ArcPolyline& line, int n, const ControlFunction& w) {
  const std::vector<double> s = equidistribute(line, n, w);
  std::vector<PlanePoint> out(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) out[k] = line.at(s[k]);
  return out;
}

BoundaryNodes equidistributed_boundary_nodes(const SplineContour& contour, int nx_pts, int ny_pts,
                                             const ControlFunction& w, int samples_per_segment) {
  if (nx_pts < 2 || ny_pts < 2)  // regional.nx, ny are validated at load
    throw InternalError(fmt::format("boundary nodes: {} x {} points; need at least 2 x 2", nx_pts, ny_pts));
  BoundaryNodes nodes;
  nodes.nx_pts = nx_pts;
  nodes.ny_pts = ny_pts;
  nodes.s.assign(static_cast<std::size_t>(nodes.count()), 0.0);
  for (int side = 0; side < 4; ++side) {
    const auto sd = static_cast<Side>(side);
    const double s0 = contour.side_begin(sd), s1 = contour.side_end(sd);
    // Samples in contour order: the side's knots refined uniformly inside each segment.
    std::vector<double> param;
    for (int k = 0; k < contour.num_points(); ++k) {
      const double a = contour.knot(k), b = contour.knot(k + 1);
      if (b <= s0 || a >= s1) continue;
      for (int m = 0; m < samples_per_segment; ++m) param.push_back(a + (b - a) * m / samples_per_segment);
    }
    param.push_back(s1);
    std::vector<PlanePoint> pts(param.size());
    for (std::size_t k = 0; k < param.size(); ++k) pts[k] = contour.point(param[k]);
    const ArcPolyline line(std::move(pts));
    const int n = nodes.side_count(sd);
    std::vector<double> a = equidistribute(line, n, w);
    std::vector<double> s(a.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      int piece = 0;
      double t = 0.0;
      line.locate(a[k], piece, t);
      s[k] = param[static_cast<std::size_t>(piece)] +
             t * (param[static_cast<std::size_t>(piece) + 1] - param[static_cast<std::size_t>(piece)]);
    }
    s.front() = s0;
    s.back() = s1;
    set_side_parameters(nodes, sd, s);
  }
  return nodes;
}

}  // namespace aq::curvilinear

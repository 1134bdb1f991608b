// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary nodes and mode-2 uniform filling (seed 000 Sec. 2.4; digest izogrid.md §7.1).
#include "curvilinear/common/boundary_nodes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::curvilinear {

int polygon_index(const BoundaryNodes& nodes, Side side, int k) {
  const auto c = nodes.corner_indices();
  const int idx = c[static_cast<std::size_t>(side)] + k;
  return idx == nodes.count() ? 0 : idx;
}

std::vector<double> side_parameters(const SplineContour& contour, const BoundaryNodes& nodes, Side side) {
  const int n = nodes.side_count(side);
  std::vector<double> out(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    out[static_cast<std::size_t>(k)] = nodes.s[static_cast<std::size_t>(polygon_index(nodes, side, k))];
  if (side == Side::kWest) out.back() = contour.period();
  return out;
}

void set_side_parameters(BoundaryNodes& nodes, Side side, const std::vector<double>& params) {
  const int n = nodes.side_count(side);
  if (static_cast<int>(params.size()) != n || static_cast<int>(nodes.s.size()) != nodes.count())
    throw InternalError("set_side_parameters: size mismatch");
  for (int k = 0; k < n; ++k) {
    const int idx = polygon_index(nodes, side, k);
    if (side == Side::kWest && k == n - 1) continue;  // SW corner is s = 0
    nodes.s[static_cast<std::size_t>(idx)] = params[static_cast<std::size_t>(k)];
  }
}

void node_positions(const SplineContour& contour, const BoundaryNodes& nodes, std::vector<double>& x,
                    std::vector<double>& y) {
  const auto nb = nodes.s.size();
  x.resize(nb);
  y.resize(nb);
  // Corners are evaluated at their knots; every node belongs to one segment of its side.
  for (std::size_t i = 0; i < nb; ++i) {
    const PlanePoint p = contour.point(nodes.s[i]);
    x[i] = p.x;
    y[i] = p.y;
  }
}

void set_grid_boundary(const SplineContour& contour, const BoundaryNodes& nodes, Grid2D& grid) {
  const int L = nodes.nx_pts, M = nodes.ny_pts;
  if (grid.nx_pts != L || grid.ny_pts != M ||
      grid.x.size() != static_cast<std::size_t>(L) * static_cast<std::size_t>(M))
    throw InternalError("set_grid_boundary: grid size differs from the boundary nodes");
  std::vector<double> x, y;
  node_positions(contour, nodes, x, y);
  auto put = [&](int i, int j, int idx) {
    grid.x[grid.at(i, j)] = x[static_cast<std::size_t>(idx)];
    grid.y[grid.at(i, j)] = y[static_cast<std::size_t>(idx)];
  };
  for (int k = 0; k < L; ++k) put(k, 0, polygon_index(nodes, Side::kSouth, k));
  for (int k = 0; k < M; ++k) put(L - 1, k, polygon_index(nodes, Side::kEast, k));
  for (int k = 0; k < L; ++k) put(L - 1 - k, M - 1, polygon_index(nodes, Side::kNorth, k));
  for (int k = 0; k < M; ++k) put(0, M - 1 - k, polygon_index(nodes, Side::kWest, k));
}

namespace {

// The next node after s_prev at chord distance h along the contour (the first crossing).
double next_node(const SplineContour& c, double s_prev, double h, double ds_guess) {
  const PlanePoint p0 = c.point(s_prev);
  auto g = [&](double s) {
    const PlanePoint p = c.point(s);
    return std::hypot(p.x - p0.x, p.y - p0.y) - h;
  };
  // Bracket the first sign change, stepping at most half a guessed node step at a time.
  const double step = 0.5 * ds_guess;
  double lo = s_prev, hi = s_prev + step;
  double ghi = g(hi);
  int guard = 0;
  while (ghi < 0.0) {
    lo = hi;
    hi += step;
    ghi = g(hi);
    if (++guard > 100000) throw NumericalError("uniform boundary nodes: cannot place a node (step too large?)");
  }
  // Safeguarded Newton in [lo, hi].
  double s = 0.5 * (lo + hi);
  constexpr double kUlp = std::numeric_limits<double>::epsilon();
  for (int it = 0; it < 200; ++it) {
    const PlanePoint p = c.point(s);
    const PlanePoint d = c.derivative(s, 1);
    const double dx = p.x - p0.x, dy = p.y - p0.y;
    const double r = std::hypot(dx, dy);
    const double gv = r - h;
    if (gv < 0.0)
      lo = s;
    else
      hi = s;
    const double gd = r > 0.0 ? (dx * d.x + dy * d.y) / r : 0.0;
    const double small = 4.0 * kUlp * std::fabs(s);
    double sn = gd > 0.0 ? s - gv / gd : 0.5 * (lo + hi);
    if (gv == 0.0 || std::fabs(sn - s) <= small || hi - lo <= small) break;  // converged at s
    if (!(sn > lo && sn < hi)) sn = 0.5 * (lo + hi);
    s = sn;
  }
  return s;
}

}  // namespace

BoundaryNodes uniform_boundary_nodes(const SplineContour& contour, int nx_pts, int ny_pts,
                                     const UniformOptions& options, UniformStats* stats) {
  if (nx_pts < 2 || ny_pts < 2)  // regional.nx, ny are validated at load
    throw InternalError(
        fmt::format("uniform boundary nodes: a grid needs at least 2 x 2 points, got {} x {}", nx_pts, ny_pts));
  BoundaryNodes nodes;
  nodes.nx_pts = nx_pts;
  nodes.ny_pts = ny_pts;
  nodes.s.assign(static_cast<std::size_t>(nodes.count()), 0.0);
  const auto& corners = contour.corners();
  const int np = contour.num_points();
  for (int si = 0; si < 4; ++si) {
    const Side side = static_cast<Side>(si);
    const int n = nodes.side_count(side);
    const double a = contour.side_begin(side), b = contour.side_end(side);
    // Rough length: the control polygon of the side (§7.1 step 1).
    double poly = 0.0;
    const int k0 = corners[static_cast<std::size_t>(si)];
    const int k1 = si == 3 ? np : corners[static_cast<std::size_t>(si) + 1];
    for (int k = k0; k < k1; ++k) {
      const auto ku = static_cast<std::size_t>(k), kn = static_cast<std::size_t>((k + 1) % np);
      poly += std::hypot(contour.control_x()[kn] - contour.control_x()[ku],
                         contour.control_y()[kn] - contour.control_y()[ku]);
    }
    const double ds_guess0 = (b - a) / (n - 1);
    std::vector<double> s(static_cast<std::size_t>(n));
    s[0] = a;
    s.back() = b;
    const PlanePoint pe = contour.point(b);
    // Places nodes 1..n−2 at chord step h and returns the miss F(h) = (remaining chord from node
    // n−2 to the end corner) − h, negative when node n−2 passed the corner. F is smooth in h
    // (the corner itself never enters), so the secant converges fast.
    auto march = [&](double h) {
      double ds = ds_guess0;
      for (int j = 1; j < n - 1; ++j) {
        s[static_cast<std::size_t>(j)] = next_node(contour, s[static_cast<std::size_t>(j) - 1], h, ds);
        ds = std::max(s[static_cast<std::size_t>(j)] - s[static_cast<std::size_t>(j) - 1], 1e-6 * ds_guess0);
      }
      const double sl = s[static_cast<std::size_t>(n) - 2];
      const PlanePoint pl = contour.point(sl);
      const double rem = std::hypot(pe.x - pl.x, pe.y - pl.y);
      return (sl < b ? rem : -rem) - h;
    };
    int it = 0;
    double h1 = poly / (n - 1);
    if (n > 2) {
      // h from the control polygon (§7.1 step 1), then the miss spread over the n−1 steps
      // (§7.1 step 3), then secant steps to round-off.
      double h0 = h1;
      double f0 = march(h0);
      h1 = h0 + f0 / (n - 1);
      double f1 = march(h1);
      it = 2;
      // The miss is only computable to ~ulp(s)·|C'|·√n (each node carries its own round-off),
      // so besides the tolerance the correction also stops when it no longer improves.
      double best_h = std::fabs(f1) < std::fabs(f0) ? h1 : h0;
      double best_f = std::min(std::fabs(f0), std::fabs(f1));
      int stalled = 0;
      while (best_f > options.tolerance * best_h) {
        if (stalled >= 3 && best_f <= 1e-9 * best_h) break;  // round-off floor
        if (it >= options.max_iterations)
          throw NumericalError(fmt::format(
              "uniform boundary nodes: the {} side did not close in {} step corrections (the last step misses "
              "by {:.3g} plane units)",
              side_name(side), options.max_iterations, best_f));
        double h2 = (f1 != f0) ? h1 - f1 * (h1 - h0) / (f1 - f0) : h1;
        if (!(h2 > 0.0) || !std::isfinite(h2)) h2 = 0.5 * h1;
        if (h2 == h1) break;
        h0 = h1;
        f0 = f1;
        h1 = h2;
        f1 = march(h1);
        ++it;
        if (std::fabs(f1) < best_f) {
          best_f = std::fabs(f1);
          best_h = h1;
          stalled = 0;
        } else {
          ++stalled;
        }
      }
      if (h1 != best_h) {
        h1 = best_h;
        march(h1);
      }
      if (!(s[static_cast<std::size_t>(n) - 2] < b))
        throw NumericalError(
            fmt::format("uniform boundary nodes: the {} side could not be filled with {} nodes", side_name(side), n));
    } else {
      const PlanePoint pa = contour.point(a);
      h1 = std::hypot(pe.x - pa.x, pe.y - pa.y);
    }
    set_side_parameters(nodes, side, s);
    if (stats != nullptr) {
      stats->iterations[static_cast<std::size_t>(si)] = it;
      stats->step[static_cast<std::size_t>(si)] = h1;
    }
  }
  return nodes;
}

}  // namespace aq::curvilinear

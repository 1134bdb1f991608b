// SPDX-License-Identifier: GPL-3.0-or-later
// Level-line tracing and intersection; see level_intersections.hpp.
#include "curvilinear/bvp/level_intersections.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "curvilinear/bvp/natural_spline.hpp"

namespace aq::curvilinear {

namespace {

// The reference grid seen with (i, j) swapped or not, so that one tracer follows f = L from the
// row j = 0 to the row j = ny−1 and carries the other function h along.
struct View {
  const SurfaceGrid& g;
  const std::vector<double>& f;
  const std::vector<double>& h;
  bool transposed;
  [[nodiscard]] int nx() const { return transposed ? g.ny_pts : g.nx_pts; }
  [[nodiscard]] int ny() const { return transposed ? g.nx_pts : g.ny_pts; }
  [[nodiscard]] std::size_t at(int i, int j) const { return transposed ? g.at(j, i) : g.at(i, j); }
};

struct IsoPoint {
  Vec3 x;
  double h = 0.0;  // the other function at x
};

bool above(double v, double level) { return v >= level; }

//   c3 ---e2--- c2        cell (i, j) of the view; edges e0 bottom, e1 right, e2 top, e3 left
//   |           |
//   e3          e1
//   |           |
//   c0 ---e0--- c1
constexpr int kEdgeA[4] = {0, 1, 3, 0};
constexpr int kEdgeB[4] = {1, 2, 2, 3};
constexpr int kCornerDi[4] = {0, 1, 1, 0};
constexpr int kCornerDj[4] = {0, 0, 1, 1};

std::vector<IsoPoint> trace(const View& v, double level, const char* name) {
  const int nx = v.nx(), ny = v.ny();
  auto crossing = [&](int ia, int ja, int ib, int jb) {
    const std::size_t a = v.at(ia, ja), b = v.at(ib, jb);
    const double t = (level - v.f[a]) / (v.f[b] - v.f[a]);
    return IsoPoint{lerp(v.g.p[a], v.g.p[b], t), v.h[a] + t * (v.h[b] - v.h[a])};
  };
  std::vector<IsoPoint> line;
  int i = 0;
  while (i + 1 < nx && above(v.f[v.at(i, 0)], level) == above(v.f[v.at(i + 1, 0)], level)) ++i;
  if (i + 1 >= nx) throw NumericalError(fmt::format("level line {} = {} does not cross its start side", name, level));
  line.push_back(crossing(i, 0, i + 1, 0));
  int j = 0, entry = 0;
  const long max_steps = 4L * nx * ny;
  for (long step = 0; step < max_steps; ++step) {
    bool up[4];
    double fc[4];
    for (int c = 0; c < 4; ++c) {
      fc[c] = v.f[v.at(i + kCornerDi[c], j + kCornerDj[c])];
      up[c] = above(fc[c], level);
    }
    int exits[4], n_exit = 0;
    for (int e = 0; e < 4; ++e)
      if (e != entry && up[kEdgeA[e]] != up[kEdgeB[e]]) exits[n_exit++] = e;
    int exit = -1;
    if (n_exit == 1) {
      exit = exits[0];
    } else if (n_exit == 3) {
      // Saddle: the bilinear centre value decides whether c0, c2 are connected.
      const double fs = (fc[0] * fc[2] - fc[1] * fc[3]) / (fc[0] + fc[2] - fc[1] - fc[3]);
      static constexpr int kPairCut13[4] = {1, 0, 3, 2};  // c0–c2 connected: {e0,e1}, {e2,e3}
      static constexpr int kPairCut02[4] = {3, 2, 1, 0};  // otherwise: {e0,e3}, {e1,e2}
      exit = above(fs, level) == up[0] ? kPairCut13[entry] : kPairCut02[entry];
    } else {
      throw NumericalError(fmt::format("level line {} = {}: broken in reference cell ({}, {})", name, level, i, j));
    }
    const int a = kEdgeA[exit], b = kEdgeB[exit];
    line.push_back(crossing(i + kCornerDi[a], j + kCornerDj[a], i + kCornerDi[b], j + kCornerDj[b]));
    switch (exit) {
      case 0:
        if (j == 0)
          throw NumericalError(
              fmt::format("level line {} = {} returns to its start side (the solution is not monotone there; refine "
                          "the reference grid)",
                          name, level));
        --j;
        entry = 2;
        break;
      case 1:
        if (i + 2 >= nx)
          throw NumericalError(fmt::format("level line {} = {} leaves through a Dirichlet side", name, level));
        ++i;
        entry = 3;
        break;
      case 2:
        if (j + 2 >= ny) return line;
        ++j;
        entry = 0;
        break;
      default:
        if (i == 0)
          throw NumericalError(fmt::format("level line {} = {} leaves through a Dirichlet side", name, level));
        --i;
        entry = 1;
        break;
    }
  }
  throw NumericalError(fmt::format("level line {} = {} does not reach its end side", name, level));
}

// The boundary polyline j' = const... as a level line: column i of the view for f = 0 or 1.
std::vector<IsoPoint> boundary_line(const View& v, int i) {
  std::vector<IsoPoint> line;
  for (int j = 0; j < v.ny(); ++j) line.push_back({v.g.p[v.at(i, j)], v.h[v.at(i, j)]});
  return line;
}

// Points of `line` where h = levels[q], q = 0..Q (the ends for q = 0 and Q).
void cut(const std::vector<IsoPoint>& line, const std::vector<double>& levels, LevelInterpolation interp,
         std::vector<Vec3>& out, const char* name, double level_f) {
  const std::size_t m = line.size(), nq = levels.size();
  out.assign(nq, Vec3{});
  out.front() = line.front().x;
  out.back() = line.back().x;
  std::optional<NaturalSpline> sx, sy, sz, sh;
  if (interp == LevelInterpolation::kCubic && m >= 3) {
    std::vector<double> x(m), y(m), z(m), h(m);
    for (std::size_t k = 0; k < m; ++k) {
      x[k] = line[k].x.x;
      y[k] = line[k].x.y;
      z[k] = line[k].x.z;
      h[k] = line[k].h;
    }
    sx.emplace(std::move(x));
    sy.emplace(std::move(y));
    sz.emplace(std::move(z));
    sh.emplace(std::move(h));
  }
  std::size_t k = 0;
  for (std::size_t q = 1; q + 1 < nq; ++q) {
    const double hl = levels[q];
    while (k + 1 < m && above(line[k].h, hl) == above(line[k + 1].h, hl)) ++k;
    if (k + 1 >= m)
      throw NumericalError(fmt::format("level line {} = {} does not reach the other level {}", name, level_f, hl));
    const double t = (hl - line[k].h) / (line[k + 1].h - line[k].h);
    if (!sh) {
      out[q] = lerp(line[k].x, line[k + 1].x, t);
      continue;
    }
    // Root of the spline h(t) = hl inside [k, k+1] (it brackets: the spline interpolates the ends).
    double lo = static_cast<double>(k), hi = lo + 1.0;
    const bool lo_up = above((*sh)(lo), hl);
    for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (above((*sh)(mid), hl) == lo_up) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    const double tt = 0.5 * (lo + hi);
    out[q] = Vec3{(*sx)(tt), (*sy)(tt), (*sz)(tt)};
  }
}

// X^f_pq for every f-level p (rows of the result: index p, then q).
std::vector<Vec3> intersections(const View& v, const std::vector<double>& f_levels, const std::vector<double>& h_levels,
                                LevelInterpolation interp, const char* name) {
  const std::size_t np = f_levels.size(), nq = h_levels.size();
  std::vector<Vec3> out(np * nq);
  std::vector<Vec3> row;
  for (std::size_t p = 0; p < np; ++p) {
    const std::vector<IsoPoint> line = p == 0        ? boundary_line(v, 0)
                                       : p + 1 == np ? boundary_line(v, v.nx() - 1)
                                                     : trace(v, f_levels[p], name);
    cut(line, h_levels, interp, row, name, f_levels[p]);
    for (std::size_t q = 0; q < nq; ++q) out[p * nq + q] = row[q];
  }
  return out;
}

void check_levels(const std::vector<double>& l, const char* name) {
  bool ok = l.size() >= 2 && l.front() == 0.0 && l.back() == 1.0;
  for (std::size_t k = 1; ok && k < l.size(); ++k) ok = l[k] > l[k - 1];
  if (!ok) throw InternalError(fmt::format("{} levels must increase strictly from 0 to 1 ({} given)", name, l.size()));
}

}  // namespace

SurfaceGrid level_intersections(const SurfaceGrid& reference, const std::vector<double>& theta,
                                const std::vector<double>& eta, const std::vector<double>& theta_levels,
                                const std::vector<double>& eta_levels, LevelInterpolation interpolation) {
  check_levels(theta_levels, "theta");
  check_levels(eta_levels, "eta");
  if (theta.size() != reference.p.size() || eta.size() != reference.p.size())
    throw InternalError("level_intersections: theta/eta do not match the reference grid");
  const int np = static_cast<int>(theta_levels.size()), nq = static_cast<int>(eta_levels.size());
  // θ increases along i and its level lines run along j: the untransposed view; η the transposed one.
  const std::vector<Vec3> xt =
      intersections(View{reference, theta, eta, false}, theta_levels, eta_levels, interpolation, "theta");
  const std::vector<Vec3> xe =
      intersections(View{reference, eta, theta, true}, eta_levels, theta_levels, interpolation, "eta");
  SurfaceGrid out(np, nq);
  for (int q = 0; q < nq; ++q) {
    for (int p = 0; p < np; ++p) {
      const Vec3 a = xt[static_cast<std::size_t>(p) * static_cast<std::size_t>(nq) + static_cast<std::size_t>(q)];
      const Vec3 b = xe[static_cast<std::size_t>(q) * static_cast<std::size_t>(np) + static_cast<std::size_t>(p)];
      const bool boundary = p == 0 || q == 0 || p + 1 == np || q + 1 == nq;
      // On the boundary one of the two is the boundary polyline itself: keep it.
      if (!boundary) {
        out(p, q) = 0.5 * (a + b);
      } else if (p == 0 || p + 1 == np) {
        out(p, q) = a;
      } else {
        out(p, q) = b;
      }
    }
  }
  return out;
}

std::vector<double> graded_levels(int n, double ratio) {
  if (n < 1 || !(ratio > 0.0) || !std::isfinite(ratio))
    throw InternalError(fmt::format("graded levels: n = {}, ratio = {} (need n >= 1, ratio > 0)", n, ratio));
  std::vector<double> l(static_cast<std::size_t>(n) + 1, 0.0);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += n > 1 ? std::pow(ratio, static_cast<double>(k) / (n - 1)) : 1.0;
  double acc = 0.0;
  for (int k = 0; k < n; ++k) {
    acc += (n > 1 ? std::pow(ratio, static_cast<double>(k) / (n - 1)) : 1.0) / sum;
    l[static_cast<std::size_t>(k) + 1] = acc;
  }
  if (ratio == 1.0)
    for (int k = 0; k <= n; ++k) l[static_cast<std::size_t>(k)] = static_cast<double>(k) / n;
  l.back() = 1.0;
  return l;
}

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Mode 3: outer inverse-problem loop around IZ89; see inverse_problem.hpp (seed 000 Sec. 2.4,
// eqs. (22)–(26); digest izogrid.md §7.2).
#include "curvilinear/conformal/inverse_problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/finite.hpp"
#include "core/timer.hpp"
#include "curvilinear/conformal/iz89.hpp"

namespace aq::curvilinear {

int inner_pass_count(InnerSchedule schedule, int m) {
  const double md = static_cast<double>(std::max(m, 1));
  const double v =
      schedule == InnerSchedule::kExponential ? std::pow(2.0, 0.5 * (md + 5.0)) : std::sqrt(2.0 * md + 5.0);
  // Guard against pow(2, k) landing an ulp above an integer (exact for integer exponents anyway).
  return static_cast<int>(std::ceil(v - 1e-9));
}

namespace {

// Cumulative chord distances along one side of the polygon, contour order.
std::vector<double> side_distances(const std::vector<double>& x, const std::vector<double>& y,
                                   const BoundaryNodes& nodes, Side side) {
  const int n = nodes.side_count(side);
  std::vector<double> c(static_cast<std::size_t>(n), 0.0);
  for (int k = 1; k < n; ++k) {
    const auto a = static_cast<std::size_t>(polygon_index(nodes, side, k - 1));
    const auto b = static_cast<std::size_t>(polygon_index(nodes, side, k));
    c[static_cast<std::size_t>(k)] = c[static_cast<std::size_t>(k) - 1] + std::hypot(x[b] - x[a], y[b] - y[a]);
  }
  return c;
}

// Lagrange interpolation of f(t) at t* from `p` points around the interval containing t*.
double lagrange(const std::vector<double>& t, const std::vector<double>& f, double ts, int p) {
  const int n = static_cast<int>(t.size());
  const int i = static_cast<int>(std::upper_bound(t.begin(), t.end(), ts) - t.begin()) - 1;  // t_i <= ts < t_{i+1}
  int first = i - (p / 2 - 1);
  first = std::clamp(first, 0, std::max(0, n - p));
  const int last = std::min(n, first + p);
  double sum = 0.0;
  for (int a = first; a < last; ++a) {
    double w = 1.0;
    for (int b = first; b < last; ++b)
      if (b != a)
        w *= (ts - t[static_cast<std::size_t>(b)]) / (t[static_cast<std::size_t>(a)] - t[static_cast<std::size_t>(b)]);
    sum += w * f[static_cast<std::size_t>(a)];
  }
  return sum;
}

bool increasing(const std::vector<double>& v) {
  for (std::size_t k = 1; k < v.size(); ++k)
    if (!(v[k] > v[k - 1])) return false;
  return true;
}

// Anderson acceleration (type II, Walker & Ni 2011) of the fixed-point map s -> G(s) of the
// outer loop: s_new = G(s_m) − ΔG γ with γ = argmin |f_m − ΔF γ|, f = G(s) − s, over the last
// `depth` differences. The accelerated iterate is used only if every side stays increasing.
class Anderson {
 public:
  explicit Anderson(int depth) : depth_(depth) {}
  void reset() {
    df_.clear();
    dg_.clear();
    has_prev_ = false;
  }
  void step(const std::vector<double>& s, std::vector<double>& g, const BoundaryNodes& shape) {
    if (depth_ <= 0) return;
    const std::size_t n = s.size();
    std::vector<double> f(n);
    for (std::size_t i = 0; i < n; ++i) f[i] = g[i] - s[i];
    if (has_prev_) {
      std::vector<double> a(n), b(n);
      for (std::size_t i = 0; i < n; ++i) {
        a[i] = f[i] - f_prev_[i];
        b[i] = g[i] - g_prev_[i];
      }
      df_.push_back(std::move(a));
      dg_.push_back(std::move(b));
      if (static_cast<int>(df_.size()) > depth_) {
        df_.erase(df_.begin());
        dg_.erase(dg_.begin());
      }
    }
    f_prev_ = f;
    g_prev_ = g;
    has_prev_ = true;
    const std::size_t q = df_.size();
    if (q == 0) return;
    // Least squares by modified Gram–Schmidt QR of ΔF (q ≤ 8 columns).
    std::vector<std::vector<double>> qm = df_;
    std::vector<double> r(q * q, 0.0);
    for (std::size_t j = 0; j < q; ++j) {
      for (std::size_t i = 0; i < j; ++i) {
        double d = 0.0;
        for (std::size_t k = 0; k < n; ++k) d += qm[i][k] * qm[j][k];
        r[i * q + j] = d;
        for (std::size_t k = 0; k < n; ++k) qm[j][k] -= d * qm[i][k];
      }
      double nrm = 0.0;
      for (std::size_t k = 0; k < n; ++k) nrm += qm[j][k] * qm[j][k];
      nrm = std::sqrt(nrm);
      if (!(nrm > 1e-14 * (1.0 + std::sqrt(r[j * q + j] * r[j * q + j])))) {  // dependent column
        reset();
        return;
      }
      r[j * q + j] = nrm;
      for (std::size_t k = 0; k < n; ++k) qm[j][k] /= nrm;
    }
    std::vector<double> gamma(q, 0.0), rhs(q, 0.0);
    for (std::size_t i = 0; i < q; ++i)
      for (std::size_t k = 0; k < n; ++k) rhs[i] += qm[i][k] * f[k];
    for (std::size_t i = q; i-- > 0;) {
      double v = rhs[i];
      for (std::size_t j = i + 1; j < q; ++j) v -= r[i * q + j] * gamma[j];
      gamma[i] = v / r[i * q + i];
    }
    std::vector<double> out = g;
    for (std::size_t j = 0; j < q; ++j)
      for (std::size_t k = 0; k < n; ++k) out[k] -= gamma[j] * dg_[j][k];
    out[0] = g[0];  // the SW corner stays at s = 0
    BoundaryNodes trial = shape;
    trial.s = out;
    for (const auto& c : trial.corner_indices()) trial.s[static_cast<std::size_t>(c)] = g[static_cast<std::size_t>(c)];
    std::vector<double> all = trial.s;
    all.push_back(1e300);
    if (!increasing(all)) return;
    g = trial.s;
  }

 private:
  int depth_;
  bool has_prev_ = false;
  std::vector<double> f_prev_, g_prev_;
  std::vector<std::vector<double>> df_, dg_;
};

}  // namespace

RectangleMeasure measure_rectangle(const std::vector<double>& x, const std::vector<double>& y,
                                   const BoundaryNodes& nodes) {
  RectangleMeasure m;
  for (int si = 0; si < 4; ++si) {
    const Side side = static_cast<Side>(si);
    const std::vector<double> c = side_distances(x, y, nodes, side);
    const int n = static_cast<int>(c.size());
    const double len = c.back();
    m.side_length[static_cast<std::size_t>(si)] = len;
    for (int k = 1; k < n - 1; ++k)
      m.residual =
          nan_max(m.residual, std::fabs(c[static_cast<std::size_t>(k)] / len - static_cast<double>(k) / (n - 1)));
  }
  m.aspect_ratio = (m.side_length[0] + m.side_length[2]) / (m.side_length[1] + m.side_length[3]);
  return m;
}

InverseResult solve_inverse_problem(const SplineContour& contour, const BoundaryNodes& initial,
                                    const InverseOptions& options, const Logger& log) {
  // regional.tolerance, interp_points and max_outer are validated at load: these are preconditions.
  if (!(options.tolerance > 0.0) || options.interpolation_points < 2 || options.interpolation_points > 8 ||
      options.max_outer_iterations < 1)
    throw InternalError(fmt::format("inverse problem: tolerance {}, {} interpolation points, {} outer iterations",
                                    options.tolerance, options.interpolation_points, options.max_outer_iterations));
  if (options.cell_multiple < 1 || (initial.ny_pts - 1) % options.cell_multiple != 0 ||
      (initial.nx_pts - 1) % options.cell_multiple != 0)
    throw InternalError(fmt::format("inverse problem: grid {} x {} points does not fit cell multiple {}",
                                    initial.nx_pts, initial.ny_pts, options.cell_multiple));
  const Timer timer;
  const ProgressFn progress = log.progress("regional inverse problem");
  InverseResult res;
  BoundaryNodes nodes = initial;
  std::vector<double> x, y;
  bool nx_frozen = !options.auto_nx;
  const int cm = options.cell_multiple;
  Anderson anderson(options.acceleration_depth);
  double prev_residual = 1.0;
  double tol = options.tolerance;
  std::vector<double> full_residuals;  // residuals of the iterates with IZ89 converged to round-off
  for (int m = 1;; ++m) {
    // The distribution's round-off floor grows like Nb² (as IZ89's, see iz89.hpp): measured
    // 2e-13..6e-13 at Nb = 460 and 1e-11..4e-11 at Nb = 5060.
    tol = std::max(options.tolerance, 4e-18 * static_cast<double>(nodes.count()) * nodes.count());
    node_positions(contour, nodes, x, y);
    Iz89Options io;
    io.max_passes = std::min(inner_pass_count(options.schedule, m), options.max_inner_passes);
    // Inexact inner solves: IZ89 only as accurate as this iteration can use (the final iterate
    // is always checked with IZ89 converged to round-off, below).
    io.angle_tolerance = std::max(options.iz89_angle_tolerance, options.inner_relative_tolerance * prev_residual);
    io.floor_threshold = options.iz89_floor_threshold;
    io.threads = options.threads;
    Iz89Result iz = iz89_straighten(x, y, nodes.corner_indices(), io);
    int passes = iz.passes;
    RectangleMeasure meas = measure_rectangle(x, y, nodes);
    bool full = iz.converged && io.angle_tolerance <= options.iz89_angle_tolerance;
    if (meas.residual <= tol && !full) {
      // A candidate: resume IZ89 on the same polygon to round-off and measure again. Also when the
      // inexact solve ran out of passes: with the "sqrt" schedule (9 passes at m = 40) the residual
      // can be below the tolerance while IZ89 never converges within one outer iteration, and the
      // loop used to run out of outer iterations (LC Black Sea; found by the configuration sweep).
      io.angle_tolerance = options.iz89_angle_tolerance;
      io.max_passes = std::max(1, options.max_inner_passes - passes);
      iz = iz89_straighten(x, y, nodes.corner_indices(), io);
      passes += iz.passes;
      meas = measure_rectangle(x, y, nodes);
      full = iz.converged;
    }
    if (!std::isfinite(meas.residual)) {
      std::int64_t k = first_non_finite(x);
      if (k < 0) k = first_non_finite(y);
      const auto at = static_cast<std::size_t>(std::max<std::int64_t>(k, 0));
      throw NumericalError(
          fmt::format("inverse problem: the rectangle residual is {} in outer iteration {}{}", meas.residual, m,
                      k < 0 ? std::string(" (the node positions are finite: a side of zero length)")
                            : fmt::format(" (first non-finite straightened vertex {} = ({}, {}))", k, x[at], y[at])));
    }
    prev_residual = meas.residual;
    res.residual_history.push_back(meas.residual);
    res.aspect_history.push_back(meas.aspect_ratio);
    res.nx_pts_history.push_back(nodes.nx_pts);
    res.inner_passes.push_back(passes);
    res.iz89_angle.push_back(iz.max_angle.empty() ? 0.0 : iz.max_angle.back());
    res.outer_iterations = m;
    log.debug(
        "inverse problem: iteration {}: residual {:.3e}, W/H {:.9f}, {} x {} nodes, {} IZ89 passes (max angle "
        "{:.2e}{})",
        m, meas.residual, meas.aspect_ratio, nodes.nx_pts, nodes.ny_pts, passes, res.iz89_angle.back(),
        iz.converged ? "" : ", not converged");
    if (progress && m >= 1) {  // a fraction of the way from the first residual down to the tolerance, in log
      const double r0 = std::max(res.residual_history.front(), tol * 1.0001);
      const double f = std::log(r0 / std::max(meas.residual, tol)) / std::log(r0 / tol);
      progress(std::clamp(f, 0.0, 0.99), fmt::format("iteration {}: residual {:.2e} (tolerance {:.1e}), {} x {} nodes", m,
                                                     meas.residual, tol, nodes.nx_pts, nodes.ny_pts));
    }
    // The round-off floor: three fully converged iterates that no longer halve the residual.
    bool floor = false;
    if (full) {
      full_residuals.push_back(meas.residual);
      const std::size_t n = full_residuals.size();
      floor = n >= 3 && options.floor_residual > 0.0 && meas.residual <= options.floor_residual &&
              meas.residual > 0.5 * std::min(full_residuals[n - 2], full_residuals[n - 3]);
    }
    const bool done = (meas.residual <= tol || floor) && full;
    if (done || m >= options.max_outer_iterations) {
      res.nodes = nodes;
      res.aspect_ratio = meas.aspect_ratio;
      res.residual = meas.residual;
      res.tolerance = tol;
      res.converged = done;
      res.at_floor = done && meas.residual > tol;
      if (res.at_floor)
        log.info(
            "inverse problem: the residual stalled at {:.2e} (tolerance {:.1e}): the round-off floor of this "
            "contour's node distribution, accepted",
            meas.residual, tol);
      res.rect_x = x;
      res.rect_y = y;
      if (!done && options.fail_on_limit)
        throw NumericalError(fmt::format(
            "inverse problem (mode 3) did not converge in {} outer iterations: residual {:.3e} reached, tolerance "
            "{:.1e} (inner schedule '{}', IZ89 {}converged in the last iteration, max angle {:.2e}); raise the "
            "iteration limit or smooth the contour",
            m, meas.residual, tol, std::string(name_of(options.schedule)), iz.converged ? "" : "not ",
            res.iz89_angle.back()));
      break;
    }

    // New node count along ξ from the aspect ratio (isotropic cells), ny fixed.
    int new_l = nodes.nx_pts;
    if (!nx_frozen) {
      const int cells = static_cast<int>(std::lround((nodes.ny_pts - 1) / cm * meas.aspect_ratio));
      new_l = std::max(1, cells) * cm + 1;
      const auto& h = res.nx_pts_history;
      if (h.size() >= 2 && new_l != nodes.nx_pts && new_l == h[h.size() - 2]) {
        log.warn("inverse problem: nx oscillates between {} and {}; keeping {}", (new_l - 1) / cm,
                 (nodes.nx_pts - 1) / cm, (nodes.nx_pts - 1) / cm);
        new_l = nodes.nx_pts;
        nx_frozen = true;
      }
      if (meas.residual < options.nx_freeze_residual) nx_frozen = true;
    }

    // Update each side separately (23)–(26).
    BoundaryNodes next;
    next.nx_pts = new_l;
    next.ny_pts = nodes.ny_pts;
    next.s.assign(static_cast<std::size_t>(next.count()), 0.0);
    for (int si = 0; si < 4; ++si) {
      const Side side = static_cast<Side>(si);
      const std::vector<double> c = side_distances(x, y, nodes, side);
      const std::vector<double> s_old = side_parameters(contour, nodes, side);
      const int n = static_cast<int>(c.size());
      std::vector<double> t(static_cast<std::size_t>(n));
      for (int k = 0; k < n; ++k) t[static_cast<std::size_t>(k)] = c[static_cast<std::size_t>(k)] / c.back();
      for (int k = 1; k < n; ++k)
        if (!(t[static_cast<std::size_t>(k)] > t[static_cast<std::size_t>(k) - 1]))
          throw NumericalError(fmt::format(
              "inverse problem: the IZ89 image of the {} side is not monotone at node {} (outer iteration {}); the "
              "contour is too irregular for this number of nodes",
              side_name(side), k, m));
      const int nn = next.side_count(side);
      std::vector<double> s_new(static_cast<std::size_t>(nn));
      s_new.front() = s_old.front();
      s_new.back() = s_old.back();
      for (int k = 1; k < nn - 1; ++k)
        s_new[static_cast<std::size_t>(k)] =
            lagrange(t, s_old, static_cast<double>(k) / (nn - 1), options.interpolation_points);
      if (!increasing(s_new))
        throw NumericalError(fmt::format(
            "inverse problem: updated nodes on the {} side are out of order (outer iteration {})", side_name(side), m));
      set_side_parameters(next, side, s_new);
    }
    if (next.nx_pts == nodes.nx_pts) {
      anderson.step(nodes.s, next.s, next);  // may replace next.s by the accelerated iterate
    } else {
      anderson.reset();
    }
    nodes = std::move(next);
  }
  res.seconds = timer.wall_s();
  return res;
}

}  // namespace aq::curvilinear

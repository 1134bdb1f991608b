// SPDX-License-Identifier: GPL-3.0-or-later
// ED2 and Ryskin–Leal grids by Picard iteration with IC(0)-preconditioned CG (seed 004 Sec. 3;
// digest B.4); see elliptic_grids.hpp.
#include "curvilinear/elliptic/elliptic_grids.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "curvilinear/common/grid_checks.hpp"

namespace aq::curvilinear {

namespace {

// Grids with fewer nodes compute their coefficients on one thread (a parallel region costs more).
constexpr std::size_t kParallelNodes = 40000;

// The interior operator K (boundary values zero), its IC(0) factor and PCG for K δ = r. The factor
// stores its entries divided by the pivots, so the two triangular sweeps of the preconditioner
// multiply (a division on their serial dependency chain cost more than the rest of CG), and the
// neighbour along the row comes last, so the chain is one multiply-add per node; the dot
// products ride along with the loops that produce their operands. Sums run in one fixed order.
class FaceOperator {
 public:
  FaceOperator(int nx, int ny)
      : L_(nx),
        M_(ny),
        a_(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)),
        b_(a_.size()),
        d_(a_.size()),
        inv_(a_.size()),
        lo_a_(a_.size()),
        lo_b_(a_.size()),
        up_a_(a_.size()),
        up_b_(a_.size()),
        res_(a_.size()),
        z_(a_.size()),
        p_(a_.size()),
        q_(a_.size()) {}
  std::vector<double>& a() { return a_; }
  std::vector<double>& b() { return b_; }

  // IC(0) of K: pivots d; forward sweep z_p = r_p/d_p + (a₋ z_{p−1} + b₋ z_{p−s})/d_p, backward
  // sweep z_p += (a₊ z_{p+1} + b₊ z_{p+s})/d_p.
  void factor() {
    for (int j = 1; j < M_ - 1; ++j)
      for (int i = 1; i < L_ - 1; ++i) {
        const std::size_t p = idx(i, j);
        double d = a_[p] + a_[p - 1] + b_[p] + b_[p - s()];
        if (i > 1) d -= a_[p - 1] * a_[p - 1] / d_[p - 1];
        if (j > 1) d -= b_[p - s()] * b_[p - s()] / d_[p - s()];
        d_[p] = d;
        inv_[p] = 1.0 / d;
        lo_a_[p] = a_[p - 1] * inv_[p];
        lo_b_[p] = b_[p - s()] * inv_[p];
        up_a_[p] = a_[p] * inv_[p];
        up_b_[p] = b_[p] * inv_[p];
      }
  }

  // Residual of the nodal equations at the current coordinates u (boundary included): Σ coef (u_nb − u_p).
  void residual(const std::vector<double>& u, std::vector<double>& r) const {
    std::fill(r.begin(), r.end(), 0.0);
    for (int j = 1; j < M_ - 1; ++j)
      for (int i = 1; i < L_ - 1; ++i) {
        const std::size_t p = idx(i, j);
        r[p] = a_[p] * (u[p + 1] - u[p]) - a_[p - 1] * (u[p] - u[p - 1]) + b_[p] * (u[p + s()] - u[p]) -
               b_[p - s()] * (u[p] - u[p - s()]);
      }
  }

  // δ ≈ K⁻¹ r by PCG from δ = 0; returns the iterations used.
  int solve(const std::vector<double>& r, std::vector<double>& delta, double rel_tol, int max_iterations) {
    const std::size_t n = a_.size();
    delta.assign(n, 0.0);
    std::copy(r.begin(), r.end(), res_.begin());
    const double rr0 = dot(res_, res_);
    if (!(rr0 > 0.0)) return 0;
    double rz = precondition(res_, z_);
    std::copy(z_.begin(), z_.end(), p_.begin());
    int it = 0;
    for (; it < max_iterations; ++it) {
      const double pq = apply(p_, q_);
      if (!(pq > 0.0)) break;
      const double alpha = rz / pq;
      double rr = 0.0;
      for (int j = 1; j < M_ - 1; ++j)
        for (int i = 1; i < L_ - 1; ++i) {
          const std::size_t k = idx(i, j);
          delta[k] += alpha * p_[k];
          res_[k] -= alpha * q_[k];
          rr += res_[k] * res_[k];
        }
      if (rr < rel_tol * rel_tol * rr0) {
        ++it;
        break;
      }
      const double rz_new = precondition(res_, z_);
      const double beta = rz_new / rz;
      rz = rz_new;
      for (int j = 1; j < M_ - 1; ++j)
        for (int i = 1; i < L_ - 1; ++i) {
          const std::size_t k = idx(i, j);
          p_[k] = z_[k] + beta * p_[k];
        }
    }
    return it;
  }

 private:
  int L_, M_;
  std::vector<double> a_, b_, d_, inv_, lo_a_, lo_b_, up_a_, up_b_, res_, z_, p_, q_;
  [[nodiscard]] std::size_t s() const { return static_cast<std::size_t>(L_); }
  [[nodiscard]] std::size_t idx(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(L_) + static_cast<std::size_t>(i);
  }
  [[nodiscard]] double dot(const std::vector<double>& u, const std::vector<double>& v) const {
    double sum = 0.0;
    for (int j = 1; j < M_ - 1; ++j)
      for (int i = 1; i < L_ - 1; ++i) sum += u[idx(i, j)] * v[idx(i, j)];
    return sum;
  }
  // out = K u on the interior; returns u·out.
  double apply(const std::vector<double>& u, std::vector<double>& out) const {
    double sum = 0.0;
    for (int j = 1; j < M_ - 1; ++j)
      for (int i = 1; i < L_ - 1; ++i) {
        const std::size_t p = idx(i, j);
        const double d = a_[p] + a_[p - 1] + b_[p] + b_[p - s()];
        out[p] = d * u[p] - a_[p] * u[p + 1] - a_[p - 1] * u[p - 1] - b_[p] * u[p + s()] - b_[p - s()] * u[p - s()];
        sum += u[p] * out[p];
      }
    return sum;
  }
  // z = (D + Lo)⁻ᵀ D (D + Lo)⁻¹ r; boundary entries of z stay 0 (never written). Returns r·z,
  // summed in the backward sweep's order.
  double precondition(const std::vector<double>& r, std::vector<double>& z) const {
    for (int j = 1; j < M_ - 1; ++j)
      for (int i = 1; i < L_ - 1; ++i) {
        const std::size_t p = idx(i, j);
        z[p] = r[p] * inv_[p] + lo_b_[p] * z[p - s()] + lo_a_[p] * z[p - 1];
      }
    double sum = 0.0;
    for (int j = M_ - 2; j >= 1; --j)
      for (int i = L_ - 2; i >= 1; --i) {
        const std::size_t p = idx(i, j);
        z[p] = z[p] + up_b_[p] * z[p + s()] + up_a_[p] * z[p + 1];
        sum += r[p] * z[p];
      }
    return sum;
  }
};

double weight_at(const ControlFunction& w, double x, double y) {
  const double v = w(x, y);
  if (!(v > 0.0) || !std::isfinite(v))
    throw InputError(fmt::format("control function w = {} at ({:.6g}, {:.6g}): must be positive and finite", v, x, y));
  return v;
}

// Face coefficients of ED2 or RL from the current grid (see the header's formulas).
void face_coefficients(const Grid2D& g, const ControlFunction& w, EllipticMethod method, double floor,
                       std::vector<double>& A, std::vector<double>& B) {
  const int L = g.nx_pts, M = g.ny_pts;
  const auto s = static_cast<std::size_t>(L);
  const double* x = g.x.data();
  const double* y = g.y.data();
  const bool ed2 = method == EllipticMethod::kEd2;
  double* pa = A.data();
  double* pb = B.data();
  const ControlFunction* pw = &w;
  [[maybe_unused]] const bool parallel = static_cast<std::size_t>(L) * static_cast<std::size_t>(M) >= kParallelNodes;
#pragma omp parallel for default(none) shared(x, y, pa, pb, pw) firstprivate(L, M, s, ed2, floor) \
    schedule(static) if (parallel)
  for (int j = 0; j < M; ++j) {
    for (int i = 0; i < L; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * s + static_cast<std::size_t>(i);
      if (i + 1 < L && j >= 1 && j + 1 < M) {  // a at (i+½, j)
        const double tx = 0.25 * (x[p + s] + x[p + s + 1] - x[p - s] - x[p - s + 1]);
        const double ty = 0.25 * (y[p + s] + y[p + s + 1] - y[p - s] - y[p - s + 1]);
        const double g22 = tx * tx + ty * ty;
        if (ed2) {
          pa[p] = std::max(weight_at(*pw, 0.5 * (x[p] + x[p + 1]), 0.5 * (y[p] + y[p + 1])) * g22, floor);
        } else {
          const double ex = x[p + 1] - x[p], ey = y[p + 1] - y[p];
          pa[p] = std::clamp(std::sqrt(g22 / std::max(ex * ex + ey * ey, floor)), 1e-3, 1e3);
        }
      }
      if (j + 1 < M && i >= 1 && i + 1 < L) {  // b at (i, j+½)
        const double tx = 0.25 * (x[p + 1] + x[p + s + 1] - x[p - 1] - x[p + s - 1]);
        const double ty = 0.25 * (y[p + 1] + y[p + s + 1] - y[p - 1] - y[p + s - 1]);
        const double g11 = tx * tx + ty * ty;
        if (ed2) {
          pb[p] = std::max(weight_at(*pw, 0.5 * (x[p] + x[p + s]), 0.5 * (y[p] + y[p + s])) * g11, floor);
        } else {
          const double ex = x[p + s] - x[p], ey = y[p + s] - y[p];
          pb[p] = std::clamp(std::sqrt(g11 / std::max(ex * ex + ey * ey, floor)), 1e-3, 1e3);
        }
      }
    }
  }
}

}  // namespace

const char* elliptic_method_name(EllipticMethod m) { return m == EllipticMethod::kEd2 ? "ed2" : "rl"; }

const char* elliptic_stop_name(EllipticStop s) {
  switch (s) {
    case EllipticStop::kNodesSettled:
      return "nodes and criteria settled";
    case EllipticStop::kAveragesSettled:
      return "averages settled";
    case EllipticStop::kIterationCap:
      break;
  }
  return "iteration cap";
}

Criteria grid_criteria(const Grid2D& grid, const ControlFunction& w) {
  CheckOptions co;
  co.cells_only = true;
  co.dxi_over_deta = 1.0;
  if (!w.is_unity()) co.weight = [&w](double x, double y) { return w(x, y); };
  const GridQuality q = check_grid(grid, co);
  Criteria c;
  const QualityField* f[4] = {&q.f1, &q.f2, &q.f3, &q.f4};
  for (std::size_t k = 0; k < 4; ++k) {
    c.worst[k] = f[k]->worst;
    c.average[k] = f[k]->average;
  }
  return c;
}

EllipticResult elliptic_smooth(Grid2D& g, const ControlFunction& w, const EllipticOptions& o) {
  if (!(o.relaxation > 0.0 && o.relaxation <= 1.0) || !(o.tolerance > 0.0) || !(o.criteria_tolerance > 0.0) ||
      o.max_iterations < 1 || o.check_every < 1 || !(o.inner_tolerance > 0.0 && o.inner_tolerance < 1.0) ||
      o.inner_iterations < 1)  // regional.relaxation, elliptic_* are validated at load
    throw InternalError(
        fmt::format("elliptic grid: relaxation {} must be in (0, 1], tolerances > 0, iterations >= 1", o.relaxation));
  const int L = g.nx_pts, M = g.ny_pts;
  if (L < 3 || M < 3) throw InternalError("elliptic_smooth: need at least 3 x 3 points");
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    x0 = std::min(x0, g.x[k]), x1 = std::max(x1, g.x[k]), y0 = std::min(y0, g.y[k]), y1 = std::max(y1, g.y[k]);
  }
  const double diam = std::hypot(x1 - x0, y1 - y0);
  const double floor = o.method == EllipticMethod::kEd2 ? 1e-24 * diam * diam * diam * diam : 1e-30 * diam * diam;

  EllipticResult res;
  res.history.push_back(grid_criteria(g, w));
  FaceOperator op(L, M);
  std::vector<double> r(g.x.size()), dx, dy;
  // Between two checks: did any f(k)_o (and, for `all`, any f(k)) change by criteria_tolerance or
  // more, or turn finite / infinite?
  const auto changed = [&](const Criteria& a, const Criteria& b, bool all) {
    for (std::size_t k = 0; k < 4; ++k) {
      const double dw = std::fabs(a.worst[k] - b.worst[k]), da = std::fabs(a.average[k] - b.average[k]);
      if (all && !(dw < o.criteria_tolerance) && std::isfinite(a.worst[k])) return true;
      if (!(da < o.criteria_tolerance) && std::isfinite(a.average[k])) return true;
      if (all && std::isfinite(a.worst[k]) != std::isfinite(b.worst[k])) return true;
      if (std::isfinite(a.average[k]) != std::isfinite(b.average[k])) return true;
    }
    return false;
  };
  int quiet_checks = 0;  // consecutive checks at which no average changed
  for (int it = 1; it <= o.max_iterations; ++it) {
    face_coefficients(g, w, o.method, floor, op.a(), op.b());
    op.factor();
    op.residual(g.x, r);
    res.cg_iterations += op.solve(r, dx, o.inner_tolerance, o.inner_iterations);
    op.residual(g.y, r);
    res.cg_iterations += op.solve(r, dy, o.inner_tolerance, o.inner_iterations);
    double move2 = 0.0;
    for (int j = 1; j < M - 1; ++j)
      for (int i = 1; i < L - 1; ++i) {
        const std::size_t p = g.at(i, j);
        g.x[p] += o.relaxation * dx[p];
        g.y[p] += o.relaxation * dy[p];
        move2 = std::max(move2, dx[p] * dx[p] + dy[p] * dy[p]);
      }
    res.iterations = it;
    res.last_move = o.relaxation * std::sqrt(move2) / diam;
    if (o.progress)
      o.progress(static_cast<double>(it) / o.max_iterations,
                 fmt::format("iteration {} of at most {}, last move {:.2e} (stops below {:.1e})", it, o.max_iterations,
                             res.last_move, o.tolerance));
    if (it % o.check_every == 0 || it == o.max_iterations) {
      const Criteria c = grid_criteria(g, w);
      const bool settled = !changed(c, res.history.back(), true);
      quiet_checks = changed(c, res.history.back(), false) ? 0 : quiet_checks + 1;
      res.history.push_back(c);
      if (settled && res.last_move < o.tolerance) {
        res.stop = EllipticStop::kNodesSettled;
      } else if (o.stop_when_averages_settle && quiet_checks >= 2) {
        res.stop = EllipticStop::kAveragesSettled;
      } else {
        continue;
      }
      res.converged = true;
      break;
    }
  }
  return res;
}

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Mehrstellen Dirichlet fill: 4-colour Chebyshev SOR (seed 000 eqs. (42)–(43)) and a direct
// 2-D DST-I solver (FFTW RODFT00). Stencil and eigenvalues: see laplace_fill.hpp.
//
// Both solvers work on coordinates shifted by the centre of the boundary's bounding box, so that
// round-off is relative to the grid's size, not to a false easting; only interior nodes are
// written back.
#include "curvilinear/conformal/laplace_fill.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>

#include "core/error.hpp"
#include "core/finite.hpp"
#include "core/timer.hpp"
#include "core/types.hpp"

namespace aq::curvilinear {

namespace {

/// Half-open bounding box of the boundary nodes.
struct Box {
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  [[nodiscard]] double extent() const { return std::max(x1 - x0, y1 - y0); }
};

Box boundary_box(const Grid2D& g) {
  Box b{g.x[0], g.x[0], g.y[0], g.y[0]};
  auto take = [&](int i, int j) {
    const std::size_t p = g.at(i, j);
    const double x = g.x[p];
    const double y = g.y[p];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      throw NumericalError(fmt::format("laplace_fill: boundary node ({}, {}) is not finite: ({}, {})", i, j, x, y));
    }
    b.x0 = std::min(b.x0, x);
    b.x1 = std::max(b.x1, x);
    b.y0 = std::min(b.y0, y);
    b.y1 = std::max(b.y1, y);
  };
  for (int i = 0; i < g.nx_pts; ++i) {
    take(i, 0);
    take(i, g.ny_pts - 1);
  }
  for (int j = 1; j < g.ny_pts - 1; ++j) {
    take(0, j);
    take(g.nx_pts - 1, j);
  }
  return b;
}

/// Transfinite (Coons) interpolation of the boundary into the interior, index-parametrised:
/// the SOR initial guess (digest §8.2 [S]).
void coons_fill(std::vector<double>& q, int nx, int ny) {
  auto at = [nx](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + i; };
  const double q00 = q[at(0, 0)];
  const double q10 = q[at(nx - 1, 0)];
  const double q01 = q[at(0, ny - 1)];
  const double q11 = q[at(nx - 1, ny - 1)];
  for (int j = 1; j < ny - 1; ++j) {
    const double t = static_cast<double>(j) / (ny - 1);
    for (int i = 1; i < nx - 1; ++i) {
      const double s = static_cast<double>(i) / (nx - 1);
      const double sides = (1 - s) * q[at(0, j)] + s * q[at(nx - 1, j)] + (1 - t) * q[at(i, 0)] + t * q[at(i, ny - 1)];
      const double corners = (1 - s) * (1 - t) * q00 + s * (1 - t) * q10 + (1 - s) * t * q01 + s * t * q11;
      q[at(i, j)] = sides - corners;
    }
  }
}

/// Half sweeps over fewer nodes than this run on one thread.
constexpr long kMinParallelNodes = 1L << 16;

/// Updates the nodes i0, i0+2, ... of one interior row of both fields; returns the largest
/// |update|.
inline double sor_row_colour(double* u, double* v, std::size_t row, int i0, int nx, std::size_t stride,
                             const StencilWeights& w, double scale) {
  double max_dq = 0.0;
  for (int i = i0; i <= nx - 2; i += 2) {
    const std::size_t p = row + static_cast<std::size_t>(i);
    const double du = scale * apply_stencil(u, p, stride, w);
    const double dv = scale * apply_stencil(v, p, stride, w);
    u[p] += du;
    v[p] += dv;
    max_dq = nan_max(max_dq, nan_max(std::fabs(du), std::fabs(dv)));
  }
  return max_dq;
}

/// Two of the four colours, c = (i mod 2) + 2 (j mod 2): the rows with j % 2 == cj, first their
/// even-i nodes (colour 2cj), then their odd-i nodes (colour 2cj+1). The 9-point stencil of a
/// node on row j reaches only rows j±1 (the other parity) and its own row's other colour, so
/// doing both colours row by row gives exactly the 4-colour sweep order (and the same bits) with
/// half the memory traffic. Rows are independent: bit-identical for any thread count.
double sor_half_sweep(double* u, double* v, int nx, int ny, int cj, StencilWeights w, double omega) {
  const int j0 = cj == 0 ? 2 : 1;  // first interior row of this parity
  const int nrows = j0 <= ny - 2 ? (ny - 2 - j0) / 2 + 1 : 0;
  const std::size_t stride = static_cast<std::size_t>(nx);
  const double scale = -omega / w.delta;
  // Small grids run serially: there a fork/join per half sweep costs more than the sweep (and a
  // lot more on a loaded machine). The result is the same either way. Rows are handed out in
  // small chunks, so when one thread is descheduled the other does its rows instead of waiting
  // for it at the join (rows are independent and max is exact: same bits for any split).
  [[maybe_unused]] const bool parallel = static_cast<long>(nrows) * nx >= kMinParallelNodes;  // OpenMP off: unused
  double max_dq = 0.0;
  // clang-format off
#pragma omp parallel for default(none) shared(u, v) firstprivate(nx, j0, nrows, stride, w, scale) \
    reduction(max : max_dq) schedule(dynamic, 8) if (parallel)
  // clang-format on
  for (int k = 0; k < nrows; ++k) {
    const std::size_t row = static_cast<std::size_t>(j0 + 2 * k) * stride;
    const double even = sor_row_colour(u, v, row, 2, nx, stride, w, scale);
    const double odd = sor_row_colour(u, v, row, 1, nx, stride, w, scale);
    max_dq = nan_max(max_dq, nan_max(even, odd));
  }
  return max_dq;
}

/// 4-colour Gauss–Seidel SOR with the monotone Chebyshev ω of (42)–(43). Decision (digest §13.11):
/// ω is updated once per full 4-colour iteration; r_Jacobi is the 5-point value, as in the paper.
void solve_sor(std::vector<double>& u, std::vector<double>& v, int nx, int ny, const StencilWeights& w,
               const LaplaceOptions& opt, double extent, LaplaceResult& result) {
  coons_fill(u, nx, ny);
  coons_fill(v, nx, ny);
  const double r_jacobi = 0.5 * (std::cos(kPi / nx) + std::cos(kPi / ny));
  const double r2 = r_jacobi * r_jacobi;
  const double stop = opt.tolerance * extent;
  double omega = 1.0;
  double max_dq = 0.0;
  for (int m = 1; m <= opt.max_iterations; ++m) {
    if (m >= 2) omega = 1.0 / (1.0 - 0.25 * omega * r2);
    max_dq = 0.0;
    max_dq = sor_half_sweep(u.data(), v.data(), nx, ny, 0, w, omega);                   // colours 0, 1
    max_dq = nan_max(max_dq, sor_half_sweep(u.data(), v.data(), nx, ny, 1, w, omega));  // colours 2, 3
    result.residual_history.push_back(max_dq / extent);
    result.iterations = m;
    if (!std::isfinite(max_dq)) break;
    if (max_dq <= stop) return;
  }
  throw NumericalError(
      fmt::format("laplace_fill: SOR did not converge on the {}x{} grid: max |dq|/extent = {:.3e} after {} iterations "
                  "(tolerance {:.1e})",
                  nx, ny, max_dq / extent, result.iterations, opt.tolerance));
}

struct FftwFree {
  void operator()(double* p) const { fftw_free(p); }
};
using FftwBuffer = std::unique_ptr<double, FftwFree>;

/// The FFTW planner is not thread-safe; every plan creation and destruction goes through this.
std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

/// Direct solve by 2-D DST-I. The interior (n1 × n2 nodes) system A q = b, b = −(operator applied
/// to the boundary values), is diagonal in the basis sin(π(p+1)(i)/(n1+1)) sin(π(q+1)(j)/(n2+1)).
/// FFTW's RODFT00 is unnormalised: applying it twice multiplies by 2(n1+1)·2(n2+1).
void solve_dst(std::vector<double>& u, std::vector<double>& v, int nx, int ny, const StencilWeights& w) {
  const int n1 = nx - 2;
  const int n2 = ny - 2;
  const std::size_t n = static_cast<std::size_t>(n1) * static_cast<std::size_t>(n2);
  const std::size_t stride = static_cast<std::size_t>(nx);

  // 1 − cos θ = 2 sin²(θ/2) keeps the small eigenvalues accurate.
  std::vector<double> a(static_cast<std::size_t>(n1));
  std::vector<double> b(static_cast<std::size_t>(n2));
  for (int p = 0; p < n1; ++p) {
    const double s = std::sin(0.5 * kPi * (p + 1) / (n1 + 1));
    a[static_cast<std::size_t>(p)] = -2.0 * s * s;  // cos a_p − 1
  }
  for (int q = 0; q < n2; ++q) {
    const double s = std::sin(0.5 * kPi * (q + 1) / (n2 + 1));
    b[static_cast<std::size_t>(q)] = -2.0 * s * s;  // cos b_q − 1
  }
  const double norm = 1.0 / (4.0 * (n1 + 1.0) * (n2 + 1.0));

  FftwBuffer buf[2] = {FftwBuffer(fftw_alloc_real(n)), FftwBuffer(fftw_alloc_real(n))};
  if (!buf[0] || !buf[1]) throw NumericalError(fmt::format("laplace_fill: cannot allocate {} doubles for FFTW", 2 * n));
  fftw_plan plan = nullptr;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan = fftw_plan_r2r_2d(n2, n1, buf[0].get(), buf[0].get(), FFTW_RODFT00, FFTW_RODFT00, FFTW_ESTIMATE);
  }
  if (plan == nullptr) throw NumericalError(fmt::format("laplace_fill: FFTW could not plan a {}x{} DST-I", n1, n2));

  double* fields[2] = {u.data(), v.data()};
  double* bufs[2] = {buf[0].get(), buf[1].get()};
  // One field per thread; fftw_execute_r2r is thread-safe. The result does not depend on the
  // thread count: each field is transformed by one thread with the same plan.
#pragma omp parallel for default(none) shared(fields, bufs, plan, a, b) firstprivate(n1, n2, stride, w, norm) \
    schedule(static) num_threads(2)
  for (int f = 0; f < 2; ++f) {
    double* q = fields[f];
    double* work = bufs[f];
    for (int j = 1; j <= n2; ++j) {
      for (int i = 1; i <= n1; ++i) q[static_cast<std::size_t>(j) * stride + i] = 0.0;
    }
    for (int j = 1; j <= n2; ++j) {
      for (int i = 1; i <= n1; ++i) {
        const std::size_t p = static_cast<std::size_t>(j) * stride + static_cast<std::size_t>(i);
        work[static_cast<std::size_t>(j - 1) * n1 + (i - 1)] = -apply_stencil(q, p, stride, w);
      }
    }
    fftw_execute_r2r(plan, work, work);
    for (int qq = 0; qq < n2; ++qq) {
      const double bq = b[static_cast<std::size_t>(qq)];
      for (int p = 0; p < n1; ++p) {
        const double ap = a[static_cast<std::size_t>(p)];
        const double lambda = 2.0 * w.alpha * ap + 2.0 * w.beta * bq + 4.0 * w.gamma * (ap * bq + ap + bq);
        work[static_cast<std::size_t>(qq) * n1 + p] *= norm / lambda;
      }
    }
    fftw_execute_r2r(plan, work, work);
    for (int j = 1; j <= n2; ++j) {
      for (int i = 1; i <= n1; ++i) {
        q[static_cast<std::size_t>(j) * stride + i] = work[static_cast<std::size_t>(j - 1) * n1 + (i - 1)];
      }
    }
  }
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_destroy_plan(plan);
}

/// Largest |operator|/|δ| over interior nodes of x and y; +inf if any value is not finite.
double max_residual(const Grid2D& g, const StencilWeights& w) {
  const int nx = g.nx_pts;
  const int ny = g.ny_pts;
  const std::size_t stride = static_cast<std::size_t>(nx);
  const double* x = g.x.data();
  const double* y = g.y.data();
  const double inv = 1.0 / std::fabs(w.delta);
  double r = 0.0;
  int bad = 0;
#pragma omp parallel for default(none) shared(x, y) firstprivate(nx, ny, stride, w, inv) reduction(max : r) \
    reduction(+ : bad) schedule(static)
  for (int j = 1; j < ny - 1; ++j) {
    for (int i = 1; i < nx - 1; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * stride + static_cast<std::size_t>(i);
      const double rx = std::fabs(apply_stencil(x, p, stride, w)) * inv;
      const double ry = std::fabs(apply_stencil(y, p, stride, w)) * inv;
      if (!std::isfinite(rx) || !std::isfinite(ry)) ++bad;
      r = nan_max(r, nan_max(rx, ry));
    }
  }
  return bad > 0 ? HUGE_VAL : r;
}

}  // namespace

LaplaceResult laplace_fill(Grid2D& grid, double dxi, double deta, const LaplaceOptions& options) {
  const Timer timer;
  check_laplace_shape(grid, "laplace_fill");
  if (!(dxi > 0.0) || !(deta > 0.0) || !std::isfinite(dxi) || !std::isfinite(deta)) {
    throw NumericalError(fmt::format("laplace_fill: steps dxi = {}, deta = {} must be positive and finite", dxi, deta));
  }
  const StencilWeights w = laplace_weights(dxi / deta, options.five_point);
  LaplaceResult result;
  const int nx = grid.nx_pts;
  const int ny = grid.ny_pts;
  if (nx < 3 || ny < 3) {
    result.seconds = timer.wall_s();
    return result;
  }

  const Box box = boundary_box(grid);
  const double extent = box.extent() > 0.0 ? box.extent() : 1.0;
  const double cx = 0.5 * (box.x0 + box.x1);
  const double cy = 0.5 * (box.y0 + box.y1);
  std::vector<double> u(grid.x.size());
  std::vector<double> v(grid.y.size());
  for (std::size_t p = 0; p < u.size(); ++p) {
    u[p] = grid.x[p] - cx;
    v[p] = grid.y[p] - cy;
  }

  if (options.solver == LaplaceOptions::Solver::kSor) {
    if (!(options.tolerance > 0.0) || options.max_iterations < 1) {
      throw NumericalError(fmt::format("laplace_fill: SOR tolerance {} and max_iterations {} must be positive",
                                       options.tolerance, options.max_iterations));
    }
    solve_sor(u, v, nx, ny, w, options, extent, result);
  } else {
    solve_dst(u, v, nx, ny, w);
    result.iterations = 1;
  }

  for (int j = 1; j < ny - 1; ++j) {
    for (int i = 1; i < nx - 1; ++i) {
      const std::size_t p = grid.at(i, j);
      grid.x[p] = u[p] + cx;
      grid.y[p] = v[p] + cy;
    }
  }
  result.residual = max_residual(grid, w) / extent;
  if (!std::isfinite(result.residual)) {
    std::int64_t k = first_non_finite(grid.x);
    if (k < 0) k = first_non_finite(grid.y);
    const auto at = static_cast<std::size_t>(std::max<std::int64_t>(k, 0));
    throw NumericalError(fmt::format(
        "laplace_fill: the {}x{} solution is not finite: the Laplace residual is {}{}", nx, ny, result.residual,
        k < 0 ? std::string()
              : fmt::format("; first non-finite node ({}, {}) = ({}, {})", at % static_cast<std::size_t>(nx),
                            at / static_cast<std::size_t>(nx), grid.x[at], grid.y[at])));
  }
  if (options.solver == LaplaceOptions::Solver::kDst) result.residual_history.push_back(result.residual);
  result.seconds = timer.wall_s();
  return result;
}

}  // namespace aq::curvilinear

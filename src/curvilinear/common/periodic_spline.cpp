// SPDX-License-Identifier: GPL-3.0-or-later
// Periodic spline systems and sweeps; see periodic_spline.hpp for the equations.
#include "curvilinear/common/periodic_spline.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

Block2 mul(const Block2& a, const Block2& b) {
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3]};
}
Vec2d mul(const Block2& a, const Vec2d& v) { return {a[0] * v[0] + a[1] * v[1], a[2] * v[0] + a[3] * v[1]}; }
Block2 add(const Block2& a, const Block2& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]}; }
Block2 neg(const Block2& a) { return {-a[0], -a[1], -a[2], -a[3]}; }
Vec2d add(const Vec2d& a, const Vec2d& b) { return {a[0] + b[0], a[1] + b[1]}; }
Vec2d sub(const Vec2d& a, const Vec2d& b) { return {a[0] - b[0], a[1] - b[1]}; }

Block2 inverse(const Block2& a) {
  const double det = a[0] * a[3] - a[1] * a[2];
  const double scale = std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]) + std::fabs(a[3]);
  if (!(std::fabs(det) > 1e-300) || !(std::fabs(det) > 1e-14 * scale * scale))
    throw NumericalError(fmt::format("periodic spline: singular 2x2 pivot block (determinant {:.3g})", det));
  return {a[3] / det, -a[1] / det, -a[2] / det, a[0] / det};
}

void check_pivot(double den) {
  if (!(std::fabs(den) > 1e-300) || !std::isfinite(den))
    throw NumericalError(fmt::format("periodic spline: zero pivot ({:.3g}) in the cyclic sweep", den));
}

HermiteBasis make_basis(int degree) {
  HermiteBasis b;
  if (degree == 3) {
    b.fl = {1, 0, -3, 2, 0, 0};  // q^2 (3 - 2q)
    b.fr = {0, 0, 3, -2, 0, 0};  // p^2 (3 - 2p)
    b.dl = {0, 1, -2, 1, 0, 0};  // p q^2
    b.dr = {0, 0, -1, 1, 0, 0};  // -p^2 q
  } else {
    b.fl = {1, 0, 0, -10, 15, -6};         // q^3 (1 + 3p + 6p^2)
    b.fr = {0, 0, 0, 10, -15, 6};          // p^3 (1 + 3q + 6q^2)
    b.dl = {0, 1, 0, -6, 8, -3};           // q^3 (p + 3p^2)
    b.dr = {0, 0, 0, -4, 7, -3};           // -p^3 (q + 3q^2)
    b.ddl = {0, 0, 0.5, -1.5, 1.5, -0.5};  // q^3 p^2 / 2
    b.ddr = {0, 0, 0, 0.5, -1.0, 0.5};     // p^3 q^2 / 2
  }
  return b;
}

}  // namespace

void solve_cyclic_tridiagonal(std::span<const double> a, std::span<const double> b, std::span<const double> c,
                              std::span<double> g) {
  const std::size_t n = g.size();
  if (n < 3 || a.size() != n || b.size() != n || c.size() != n)
    throw InternalError("solve_cyclic_tridiagonal: needs n >= 3 rows and equal sizes");
  std::vector<double> v(n), u(n), p(n), s(n), t(n);
  double vp = 0.0, up = 0.0, pp = 1.0;  // v_{-1}, u_{-1}, p_{-1}
  for (std::size_t i = 0; i < n; ++i) {
    const double den = b[i] + a[i] * vp;
    check_pivot(den);
    v[i] = -c[i] / den;
    u[i] = (g[i] - a[i] * up) / den;
    p[i] = -a[i] * pp / den;
    vp = v[i];
    up = u[i];
    pp = p[i];
  }
  s[n - 1] = 1.0;
  t[n - 1] = 0.0;
  for (std::size_t i = n - 1; i-- > 0;) {
    s[i] = v[i] * s[i + 1] + p[i];
    t[i] = v[i] * t[i + 1] + u[i];
  }
  const double den = 1.0 - p[n - 1] - v[n - 1] * s[0];
  check_pivot(den);
  const double zn = (u[n - 1] + v[n - 1] * t[0]) / den;
  for (std::size_t i = 0; i < n; ++i) g[i] = t[i] + s[i] * zn;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(g[i])) throw NumericalError("periodic spline: non-finite solution of the cyclic sweep");
}

void solve_cyclic_block_tridiagonal(std::span<const Block2> a, std::span<const Block2> b, std::span<const Block2> c,
                                    std::span<Vec2d> g) {
  const std::size_t n = g.size();
  if (n < 3 || a.size() != n || b.size() != n || c.size() != n)
    throw InternalError("solve_cyclic_block_tridiagonal: needs n >= 3 block rows and equal sizes");
  const Block2 id{1, 0, 0, 1};
  std::vector<Block2> v(n), p(n), s(n);
  std::vector<Vec2d> u(n), t(n);
  Block2 vp{0, 0, 0, 0}, pp = id;
  Vec2d up{0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const Block2 inv = inverse(add(b[i], mul(a[i], vp)));
    v[i] = neg(mul(inv, c[i]));
    u[i] = mul(inv, sub(g[i], mul(a[i], up)));
    p[i] = neg(mul(inv, mul(a[i], pp)));
    vp = v[i];
    up = u[i];
    pp = p[i];
  }
  s[n - 1] = id;
  t[n - 1] = {0, 0};
  for (std::size_t i = n - 1; i-- > 0;) {
    s[i] = add(mul(v[i], s[i + 1]), p[i]);
    t[i] = add(mul(v[i], t[i + 1]), u[i]);
  }
  // z_{n-1} = (I - P_{n-1} - V_{n-1} S_0)^{-1} (U_{n-1} + V_{n-1} T_0)
  const Block2 m = add(id, neg(add(p[n - 1], mul(v[n - 1], s[0]))));
  const Vec2d zn = mul(inverse(m), add(u[n - 1], mul(v[n - 1], t[0])));
  for (std::size_t i = 0; i < n; ++i) {
    g[i] = add(t[i], mul(s[i], zn));
    if (!std::isfinite(g[i][0]) || !std::isfinite(g[i][1]))
      throw NumericalError("periodic spline: non-finite solution of the cyclic block sweep");
  }
}

void periodic_cubic_slopes(std::span<const double> h, std::span<const double> df, std::span<double> d) {
  const std::size_t n = h.size();
  std::vector<double> a(n), b(n), c(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t km = (k + n - 1) % n;
    const double ia = 1.0 / h[km], ib = 1.0 / h[k];
    a[k] = ia;
    b[k] = 2.0 * (ia + ib);
    c[k] = ib;
    d[k] = 3.0 * (df[km] * ia * ia + df[k] * ib * ib);
  }
  solve_cyclic_tridiagonal(a, b, c, d);
}

void periodic_quintic_derivatives(std::span<const double> h, std::span<const double> df, std::span<double> d,
                                  std::span<double> dd) {
  const std::size_t n = h.size();
  std::vector<Block2> a(n), b(n), c(n);
  std::vector<Vec2d> g(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t km = (k + n - 1) % n;
    const double A = h[km], B = h[k];
    const double a2 = 1.0 / (A * A), a3 = a2 / A, a4 = a3 / A;
    const double b2 = 1.0 / (B * B), b3 = b2 / B, b4 = b3 / B;
    // Row 1: C4 continuity, eq. (72) corrected; row 2: C3 continuity, eq. (70).
    a[k] = {7.0 / 15.0 * a3, 1.0 / 15.0 * a2, -2.0 / 5.0 * a2, -1.0 / 20.0 / A};
    c[k] = {7.0 / 15.0 * b3, -1.0 / 15.0 * b2, 2.0 / 5.0 * b2, -1.0 / 20.0 / B};
    b[k] = {8.0 / 15.0 * (a3 + b3), -1.0 / 10.0 * (a2 - b2), -3.0 / 5.0 * (a2 - b2), 3.0 / 20.0 * (1.0 / A + 1.0 / B)};
    g[k] = {df[k] * b4 + df[km] * a4, df[k] * b3 - df[km] * a3};
  }
  solve_cyclic_block_tridiagonal(a, b, c, g);
  for (std::size_t k = 0; k < n; ++k) {
    d[k] = g[k][0];
    dd[k] = g[k][1];
  }
}

const HermiteBasis& hermite_basis(int degree) {
  static const HermiteBasis cubic = make_basis(3);
  static const HermiteBasis quintic = make_basis(5);
  if (degree == 3) return cubic;
  if (degree == 5) return quintic;
  throw InternalError(fmt::format("hermite_basis: degree {} is neither 3 nor 5", degree));
}

double poly_derivative(const std::array<double, 6>& c, double p, int order) {
  // d^order/dp^order of sum c_i p^i, by Horner on the differentiated coefficients.
  double r = 0.0;
  for (int i = 5; i >= order; --i) {
    double f = c[static_cast<std::size_t>(i)];
    for (int m = 0; m < order; ++m) f *= static_cast<double>(i - m);
    r = r * p + f;
  }
  return r;
}

}  // namespace aq::curvilinear

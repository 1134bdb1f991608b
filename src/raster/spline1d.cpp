// SPDX-License-Identifier: GPL-3.0-or-later
// Uniform-grid cubic spline slopes by the tridiagonal (Thomas) and cyclic (Sherman–Morrison) sweeps.
#include "raster/spline1d.hpp"

#include <vector>

namespace aq::raster {

namespace {
// Solves the tridiagonal system a_k x_{k-1} + b_k x_k + c_k x_{k+1} = r_k with a = c = 1 and
// b_0 = b0, b_{n-1} = bn, b_k = 4 otherwise. r is overwritten by the solution; work holds n.
void sweep(double* r, std::int64_t n, double b0, double bn, double* cp) {
  double b = b0;
  cp[0] = 1.0 / b;
  r[0] = r[0] / b;
  for (std::int64_t k = 1; k < n; ++k) {
    const double bk = (k == n - 1) ? bn : 4.0;
    const double m = bk - cp[k - 1];
    cp[k] = 1.0 / m;
    r[k] = (r[k] - r[k - 1]) / m;
  }
  for (std::int64_t k = n - 2; k >= 0; --k) r[k] -= cp[k] * r[k + 1];
}
}  // namespace

void spline_slopes(const double* f, double* d, std::int64_t n, double h, bool periodic, double* work) {
  double* r = work;
  double* cp = work + n;
  if (!periodic) {
    r[0] = 3.0 * (f[1] - f[0]) / h;
    r[n - 1] = 3.0 * (f[n - 1] - f[n - 2]) / h;
    for (std::int64_t k = 1; k < n - 1; ++k) r[k] = 3.0 * (f[k + 1] - f[k - 1]) / h;
    sweep(r, n, 2.0, 2.0, cp);
    for (std::int64_t k = 0; k < n; ++k) d[k] = r[k];
    return;
  }
  // Cyclic matrix A = T + u v^T with corner entries 1; Sherman–Morrison with gamma = -4:
  // T has b_0 = 4 - gamma, b_{n-1} = 4 - 1/gamma; u = (gamma, 0, .., 1), v = (1, 0, .., 1/gamma).
  const double gamma = -4.0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double fp = f[(k + 1) % n];
    const double fm = f[(k + n - 1) % n];
    r[k] = 3.0 * (fp - fm) / h;
  }
  std::vector<double> z(static_cast<std::size_t>(n), 0.0);
  z[0] = gamma;
  z[static_cast<std::size_t>(n - 1)] = 1.0;
  sweep(r, n, 4.0 - gamma, 4.0 - 1.0 / gamma, cp);
  sweep(z.data(), n, 4.0 - gamma, 4.0 - 1.0 / gamma, cp);
  const double vy = r[0] + r[n - 1] / gamma;
  const double vz = z[0] + z[static_cast<std::size_t>(n - 1)] / gamma;
  const double fac = vy / (1.0 + vz);
  for (std::int64_t k = 0; k < n; ++k) d[k] = r[k] - fac * z[static_cast<std::size_t>(k)];
}

}  // namespace aq::raster

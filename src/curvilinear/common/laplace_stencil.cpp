// SPDX-License-Identifier: GPL-3.0-or-later
// The mehrstellen stencil's weights and residual (see laplace_stencil.hpp).
#include "curvilinear/common/laplace_stencil.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/error.hpp"

namespace aq::curvilinear {

void check_laplace_shape(const Grid2D& g, const char* who) {
  const std::size_t n =
      static_cast<std::size_t>(std::max(g.nx_pts, 0)) * static_cast<std::size_t>(std::max(g.ny_pts, 0));
  if (g.nx_pts < 0 || g.ny_pts < 0 || g.x.size() != n || g.y.size() != n) {
    throw InternalError(
        fmt::format("{}: grid {}x{} has {} x and {} y values", who, g.nx_pts, g.ny_pts, g.x.size(), g.y.size()));
  }
}

StencilWeights laplace_weights(double dxi_over_deta, bool five_point) {
  const double rho = dxi_over_deta;
  if (!(rho > 0.0) || !std::isfinite(rho)) {
    throw NumericalError(fmt::format("laplace_weights: step ratio dxi/deta = {} is not positive and finite", rho));
  }
  StencilWeights w;
  if (five_point) {
    w.alpha = 1.0;
    w.beta = rho * rho;
    w.gamma = 0.0;
  } else {
    w.alpha = 6.0 - 2.0 * rho;
    w.beta = 6.0 * rho * rho - 2.0 * rho;
    w.gamma = rho;
  }
  w.delta = -2.0 * w.alpha - 2.0 * w.beta - 4.0 * w.gamma;
  return w;
}

void laplace_residual(const Grid2D& grid, double dxi_over_deta, bool five_point, std::vector<double>& rx,
                      std::vector<double>& ry) {
  check_laplace_shape(grid, "laplace_residual");
  const StencilWeights w = laplace_weights(dxi_over_deta, five_point);
  const int nx = grid.nx_pts;
  const int ny = grid.ny_pts;
  rx.assign(grid.x.size(), 0.0);
  ry.assign(grid.y.size(), 0.0);
  const std::size_t stride = static_cast<std::size_t>(nx);
  const double* x = grid.x.data();
  const double* y = grid.y.data();
  double* out_x = rx.data();
  double* out_y = ry.data();
  const double inv = 1.0 / std::fabs(w.delta);
#pragma omp parallel for default(none) shared(x, y, out_x, out_y) firstprivate(nx, ny, stride, w, inv) schedule(static)
  for (int j = 1; j < ny - 1; ++j) {
    for (int i = 1; i < nx - 1; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * stride + static_cast<std::size_t>(i);
      out_x[p] = apply_stencil(x, p, stride, w) * inv;
      out_y[p] = apply_stencil(y, p, stride, w) * inv;
    }
  }
}

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Refinement of a parent supergrid (see refine.hpp).
#include "curvilinear/common/refine.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <vector>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

// Fourth-order node derivatives of f[k·stride], k = 0..n−1 (n ≥ 5), per unit index step.
void derivatives(const double* f, int n, std::size_t stride, std::vector<double>& d) {
  d.assign(static_cast<std::size_t>(n), 0.0);
  const auto F = [&](int k) { return f[static_cast<std::size_t>(k) * stride]; };
  for (int k = 2; k + 2 < n; ++k) d[k] = (F(k - 2) - 8.0 * F(k - 1) + 8.0 * F(k + 1) - F(k + 2)) / 12.0;
  d[0] = (-25.0 * F(0) + 48.0 * F(1) - 36.0 * F(2) + 16.0 * F(3) - 3.0 * F(4)) / 12.0;
  d[1] = (-3.0 * F(0) - 10.0 * F(1) + 18.0 * F(2) - 6.0 * F(3) + F(4)) / 12.0;
  const int e = n - 1;
  d[e] = (25.0 * F(e) - 48.0 * F(e - 1) + 36.0 * F(e - 2) - 16.0 * F(e - 3) + 3.0 * F(e - 4)) / 12.0;
  d[e - 1] = (3.0 * F(e) + 10.0 * F(e - 1) - 18.0 * F(e - 2) + 6.0 * F(e - 3) - F(e - 4)) / 12.0;
}

// Where a fine supergrid index falls on the parent's: cell c and offset u in [0, 1].
struct Where {
  int cell = 0;
  double u = 0.0;
};

// Cubic Hermite on cell w of the line f (stride) with node derivatives d.
double hermite(const double* f, std::size_t stride, const std::vector<double>& d, Where w) {
  const double u = w.u, u2 = u * u, u3 = u2 * u;
  const double h00 = 2.0 * u3 - 3.0 * u2 + 1.0, h10 = u3 - 2.0 * u2 + u, h01 = -2.0 * u3 + 3.0 * u2, h11 = u3 - u2;
  const auto c = static_cast<std::size_t>(w.cell);
  return h00 * f[c * stride] + h10 * d[c] + h01 * f[(c + 1) * stride] + h11 * d[c + 1];
}

// Parent supergrid positions of fine supergrid indices first..first+count−1 along one direction:
// s = 2·lo − 1 + (S − 1)/r with exact integer arithmetic. False when one is outside 0..n−1.
bool positions(int lo, int r, int first, int count, int n, std::vector<Where>& out) {
  out.resize(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const std::int64_t num = static_cast<std::int64_t>(2 * lo - 1) * r + (first + k - 1);
    if (num < 0) return false;
    std::int64_t cell = num / r;
    const std::int64_t rem = num % r;
    double u = static_cast<double>(rem) / static_cast<double>(r);
    if (cell > n - 1 || (cell == n - 1 && rem != 0)) return false;
    if (cell == n - 1) {  // the parent's last point: end of the last cell
      cell = n - 2;
      u = 1.0;
    }
    out[static_cast<std::size_t>(k)] = {static_cast<int>(cell), u};
  }
  return true;
}

}  // namespace

Grid2D refine_supergrid(const Grid2D& parent, const RefineBox& box, int pad) {
  const int r = box.factor;
  if (r < 1 || r % 2 == 0 || pad < 0)
    throw InternalError(fmt::format("refine_supergrid: factor {} (odd >= 1) and pad {} (>= 0)", r, pad));
  const int nI = parent.nx_pts, nJ = parent.ny_pts;
  if (nI < 5 || nJ < 5) throw InternalError("refine_supergrid: the parent supergrid needs at least 5 x 5 points");
  const int L = box.L(), M = box.M();
  const int nS = 2 * L + 1 + 4 * pad, nT = 2 * M + 1 + 4 * pad;
  std::vector<Where> ws, wt;
  if (!positions(box.i_left, r, -2 * pad, nS, nI, ws) || !positions(box.j_bottom, r, -2 * pad, nT, nJ, wt))
    throw ConfigError(fmt::format(
        "nesting.parent_box: the refinement of the parent's psi cells I {}..{}, J {}..{} by {} with {} extra fine "
        "cells on every side "
        "reaches outside the parent grid (psi I 1..{}, J 1..{})",
        box.i_left, box.i_right, box.j_bottom, box.j_top, r, pad, (nI - 1) / 2, (nJ - 1) / 2));

  // Pass 1: along s, every parent row at the fine columns.
  const auto nSs = static_cast<std::size_t>(nS);
  std::vector<double> ax(static_cast<std::size_t>(nJ) * nSs), ay(ax.size());
#pragma omp parallel for schedule(static) default(none) shared(parent, ws, ax, ay, nI, nJ, nSs)
  for (int J = 0; J < nJ; ++J) {
    std::vector<double> dx, dy;
    const double* rx = &parent.x[parent.at(0, J)];
    const double* ry = &parent.y[parent.at(0, J)];
    derivatives(rx, nI, 1, dx);
    derivatives(ry, nI, 1, dy);
    for (std::size_t S = 0; S < nSs; ++S) {
      ax[static_cast<std::size_t>(J) * nSs + S] = hermite(rx, 1, dx, ws[S]);
      ay[static_cast<std::size_t>(J) * nSs + S] = hermite(ry, 1, dy, ws[S]);
    }
  }
  // Pass 2: along t, every fine column.
  Grid2D out(nS, nT);
#pragma omp parallel for schedule(static) default(none) shared(out, wt, ax, ay, nJ, nS, nT, nSs)
  for (int S = 0; S < nS; ++S) {
    std::vector<double> dx, dy;
    const double* cx = &ax[static_cast<std::size_t>(S)];
    const double* cy = &ay[static_cast<std::size_t>(S)];
    derivatives(cx, nJ, nSs, dx);
    derivatives(cy, nJ, nSs, dy);
    for (int T = 0; T < nT; ++T) {
      out.x[out.at(S, T)] = hermite(cx, nSs, dx, wt[static_cast<std::size_t>(T)]);
      out.y[out.at(S, T)] = hermite(cy, nSs, dy, wt[static_cast<std::size_t>(T)]);
    }
  }
  return out;
}

Grid2D unpad_supergrid(const Grid2D& padded, int pad) {
  const int nx = padded.nx_pts - 4 * pad, ny = padded.ny_pts - 4 * pad;
  if (pad < 0 || nx < 1 || ny < 1) throw InternalError(fmt::format("unpad_supergrid: pad {} too large", pad));
  Grid2D g(nx, ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      g.x[g.at(i, j)] = padded.x[padded.at(i + 2 * pad, j + 2 * pad)];
      g.y[g.at(i, j)] = padded.y[padded.at(i + 2 * pad, j + 2 * pad)];
    }
  return g;
}

}  // namespace aq::curvilinear

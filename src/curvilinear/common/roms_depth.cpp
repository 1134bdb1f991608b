// SPDX-License-Identifier: GPL-3.0-or-later
// Clip and r-factor smoothing of ROMS depths; the scheme and why it is deterministic are in
// roms_depth.hpp.
#include "curvilinear/common/roms_depth.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

constexpr int kMaxSweeps = 1000000;

void check_sizes(const std::vector<double>& h, const std::vector<std::uint8_t>& mask, int ni, int nj, const char* who) {
  const std::size_t n = static_cast<std::size_t>(std::max(ni, 0)) * static_cast<std::size_t>(std::max(nj, 0));
  if (ni < 1 || nj < 1 || h.size() != n || mask.size() != n)
    throw InternalError(
        fmt::format("{}: {} x {} points with {} depths and {} mask values", who, ni, nj, h.size(), mask.size()));
}

// Raises h[a] to c·h[b] when needed; true if it changed.
inline bool raise(std::vector<double>& h, std::size_t a, std::size_t b, double c) {
  const double need = c * h[b];
  if (need > h[a]) {
    h[a] = need;
    return true;
  }
  return false;
}

// One Gauss–Seidel visit of point (i, j): every wet face neighbour may raise it.
inline bool visit(std::vector<double>& h, const std::vector<std::uint8_t>& m, int ni, int nj, int i, int j, double c) {
  const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
  if (m[k] == 0) return false;
  bool changed = false;
  if (i > 0 && m[k - 1] != 0) changed |= raise(h, k, k - 1, c);
  if (i + 1 < ni && m[k + 1] != 0) changed |= raise(h, k, k + 1, c);
  const std::size_t row = static_cast<std::size_t>(ni);
  if (j > 0 && m[k - row] != 0) changed |= raise(h, k, k - row, c);
  if (j + 1 < nj && m[k + row] != 0) changed |= raise(h, k, k + row, c);
  return changed;
}

}  // namespace

double max_r_factor(const std::vector<double>& h, const std::vector<std::uint8_t>& mask, int ni, int nj) {
  check_sizes(h, mask, ni, nj, "max_r_factor");
  double r = 0.0;
  const auto pair = [&](std::size_t a, std::size_t b) {
    if (mask[a] == 0 || mask[b] == 0) return;
    const double s = h[a] + h[b];
    if (s > 0.0) r = std::max(r, std::fabs(h[a] - h[b]) / s);
  };
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i);
      if (i + 1 < ni) pair(k, k + 1);
      if (j + 1 < nj) pair(k, k + static_cast<std::size_t>(ni));
    }
  return r;
}

int smooth_r_factor(std::vector<double>& h, const std::vector<std::uint8_t>& mask, int ni, int nj, double rmax) {
  if (!(rmax >= 0.0 && rmax < 1.0))  // roms.rmax, validated at load
    throw InternalError(fmt::format("smooth_r_factor: rmax = {} is outside [0, 1)", rmax));
  check_sizes(h, mask, ni, nj, "smooth_r_factor");
  if (rmax == 0.0 || max_r_factor(h, mask, ni, nj) <= rmax) return 0;
  const double c = (1.0 - rmax) / (1.0 + rmax);
  int sweeps = 0;
  bool changed = true;
  while (changed) {
    if (sweeps >= kMaxSweeps)
      throw NumericalError(
          fmt::format("roms.rmax = {}: depth smoothing did not settle in {} sweeps", rmax, kMaxSweeps));
    changed = false;
    const bool forward = sweeps % 2 == 0;
    for (int jj = 0; jj < nj; ++jj) {
      const int j = forward ? jj : nj - 1 - jj;
      for (int ii = 0; ii < ni; ++ii) {
        const int i = forward ? ii : ni - 1 - ii;
        changed |= visit(h, mask, ni, nj, i, j, c);
      }
    }
    ++sweeps;
  }
  return sweeps;
}

DepthResult roms_depth(const std::vector<double>& hraw, const std::vector<std::uint8_t>& mask, int ni, int nj,
                       const DepthOptions& o) {
  // roms.hmin_m and roms.rmax are validated at load.
  if (!(o.hmin_m > 0.0) || !std::isfinite(o.hmin_m) || !(o.rmax >= 0.0 && o.rmax < 1.0))
    throw InternalError(fmt::format("roms_depth: hmin {} m (> 0), rmax {} ([0, 1))", o.hmin_m, o.rmax));
  check_sizes(hraw, mask, ni, nj, "roms_depth");

  DepthResult r;
  r.h.resize(hraw.size());
  for (std::size_t k = 0; k < hraw.size(); ++k) {
    if (!std::isfinite(hraw[k]))
      throw InternalError(fmt::format("roms_depth: hraw[{}] = {} is not finite", k, hraw[k]));
    r.h[k] = std::max(hraw[k], o.hmin_m);
    if (hraw[k] < o.hmin_m) {
      ++r.clipped;
      if (mask[k] != 0) ++r.clipped_wet;
    }
  }
  r.rx0_before = max_r_factor(r.h, mask, ni, nj);
  r.rx0_after = r.rx0_before;
  r.rx1_before = max_rx1(r.h, mask, ni, nj);
  r.rx1_after = r.rx1_before;
  if (o.rmax == 0.0 || r.rx0_before <= o.rmax) return r;

  const std::vector<double> before = r.h;
  r.sweeps = smooth_r_factor(r.h, mask, ni, nj, o.rmax);
  double sum_before = 0.0, sum_added = 0.0;
  for (std::size_t k = 0; k < r.h.size(); ++k) {
    if (mask[k] == 0) continue;
    sum_before += before[k];
    const double d = r.h[k] - before[k];
    if (d > 0.0) {
      ++r.smoothed;
      sum_added += d;
      r.max_deepening_m = std::max(r.max_deepening_m, d);
    }
  }
  r.volume_added_rel = sum_before > 0.0 ? sum_added / sum_before : 0.0;
  r.rx0_after = max_r_factor(r.h, mask, ni, nj);
  r.rx1_after = max_rx1(r.h, mask, ni, nj);
  return r;
}

double max_rx1(const std::vector<double>& h, const std::vector<std::uint8_t>& mask, int ni, int nj,
               const VerticalGrid& v) {
  check_sizes(h, mask, ni, nj, "max_rx1");
  const int n = std::max(v.n, 1);
  // Stretching C(s) at the w levels s = (k − N)/N, k = 0..N (Vstretching = 4).
  std::vector<double> s(static_cast<std::size_t>(n) + 1), cs(s.size());
  for (int k = 0; k <= n; ++k) {
    const double sk = static_cast<double>(k - n) / n;
    double c = v.theta_s > 0.0 ? (1.0 - std::cosh(v.theta_s * sk)) / (std::cosh(v.theta_s) - 1.0) : -sk * sk;
    if (v.theta_b > 0.0) c = (std::exp(v.theta_b * c) - 1.0) / (1.0 - std::exp(-v.theta_b));
    s[static_cast<std::size_t>(k)] = sk;
    cs[static_cast<std::size_t>(k)] = c;
  }
  const auto z = [&](double depth, int k) {  // Vtransform = 2, ζ = 0
    const auto q = static_cast<std::size_t>(k);
    return depth * (v.hc_m * s[q] + depth * cs[q]) / (v.hc_m + depth);
  };
  double worst = 0.0;
  const auto face = [&](std::size_t a, std::size_t b) {
    if (mask[a] == 0 || mask[b] == 0) return;
    for (int k = 1; k <= n; ++k) {
      const double num = std::fabs(z(h[a], k) - z(h[b], k) + z(h[a], k - 1) - z(h[b], k - 1));
      const double den = std::fabs(z(h[a], k) + z(h[b], k) - z(h[a], k - 1) - z(h[b], k - 1));
      if (den > 0.0) worst = std::max(worst, num / den);
    }
  };
  const auto at = [ni](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(ni) + static_cast<std::size_t>(i); };
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      if (i + 1 < ni) face(at(i, j), at(i + 1, j));
      if (j + 1 < nj) face(at(i, j), at(i, j + 1));
    }
  return worst;
}

}  // namespace aq::curvilinear

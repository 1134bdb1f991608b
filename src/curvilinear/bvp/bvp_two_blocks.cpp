// SPDX-License-Identifier: GPL-3.0-or-later
// Two-block orthogonal-family grids; see bvp_two_blocks.hpp.
#include "curvilinear/bvp/bvp_two_blocks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

// η^B at point y, interpolated linearly on the closest segment of B's interface column (i = 0).
double eta_on_interface(const SurfaceGrid& ref, const std::vector<double>& eta, Vec3 y) {
  double best = std::numeric_limits<double>::infinity(), value = 0.0;
  for (int j = 0; j + 1 < ref.ny_pts; ++j) {
    const Vec3 p = ref(0, j), q = ref(0, j + 1), d = q - p;
    const double t = std::clamp(dot(y - p, d) / dot(d, d), 0.0, 1.0);
    const double dist = norm(lerp(p, q, t) - y);
    if (dist < best) {
      best = dist;
      value = eta[ref.at(0, j)] + t * (eta[ref.at(0, j + 1)] - eta[ref.at(0, j)]);
    }
  }
  return value;
}

}  // namespace

TwoBlockResult orthogonal_bvp_two_blocks(const SurfaceGrid& a_initial, const SurfaceGrid& b_initial,
                                         const BvpOptions& o, const std::vector<double>& b_theta_levels,
                                         const std::function<void(SurfaceGrid&)>& b_project) {
  if (o.max_iterations < 1 || o.min_iterations < 1 || !(o.level_off >= 0.0))  // regional.bvp_iterations: at load
    throw InternalError(
        fmt::format("two blocks: max_iterations = {}, min_iterations = {}, level_off = {} (need >= 1, >= 1, >= 0)",
                    o.max_iterations, o.min_iterations, o.level_off));
  TwoBlockResult r;
  auto record = [&r](const SurfaceGrid& a, const SurfaceGrid& b) {
    const SurfaceOrthogonality qa = surface_orthogonality(a), qb = surface_orthogonality(b);
    // f_avg over both blocks, weighting by the cell counts (near-equal cell areas at the interface).
    const double na = static_cast<double>((a.nx_pts - 1) * (a.ny_pts - 1));
    const double nb = static_cast<double>((b.nx_pts - 1) * (b.ny_pts - 1));
    r.f_max.push_back(std::max(qa.f_max, qb.f_max));
    r.f_avg.push_back(std::sqrt((na * qa.f_avg * qa.f_avg + nb * qb.f_avg * qb.f_avg) / (na + nb)));
  };
  record(a_initial, b_initial);
  SurfaceGrid ref_a = a_initial, ref_b = b_initial;
  const int nq = static_cast<int>(o.eta_levels.size());
  for (int k = 1; k <= o.max_iterations; ++k) {
    const ThetaEta ta = solve_theta_eta(ref_a, o.solver), tb = solve_theta_eta(ref_b, o.solver);
    SurfaceGrid a = level_intersections(ref_a, ta.theta, ta.eta, o.theta_levels, o.eta_levels, o.interpolation);
    if (o.project) o.project(a);
    // B's η levels from A's interface nodes.
    std::vector<double> eb(static_cast<std::size_t>(nq));
    eb.front() = 0.0;
    eb.back() = 1.0;
    for (int q = 1; q + 1 < nq; ++q) {
      eb[static_cast<std::size_t>(q)] = eta_on_interface(ref_b, tb.eta, a(a.nx_pts - 1, q));
      if (!(eb[static_cast<std::size_t>(q)] > eb[static_cast<std::size_t>(q) - 1]))
        throw NumericalError(
            fmt::format("two blocks: block B's eta is not increasing along the interface at level "
                        "{} (the blocks do not share the interface)",
                        q));
    }
    SurfaceGrid b = level_intersections(ref_b, tb.theta, tb.eta, b_theta_levels, eb, o.interpolation);
    if (b_project) b_project(b);
    for (int q = 0; q < nq; ++q) b(0, q) = a(a.nx_pts - 1, q);
    record(a, b);
    r.eta_levels_b = eb;
    r.iterations = k;
    ref_a = std::move(a);
    ref_b = std::move(b);
    const std::size_t n = r.f_max.size();
    if (k >= o.min_iterations && bvp_leveled_off(r.f_max[n - 2], r.f_max[n - 1], o.level_off) &&
        bvp_leveled_off(r.f_avg[n - 2], r.f_avg[n - 1], o.level_off))
      break;
  }
  r.a = ref_a;
  r.b = ref_b;
  for (int q = 1; q + 1 < nq; ++q) {
    const Vec3 da = r.a(r.a.nx_pts - 1, q) - r.a(r.a.nx_pts - 2, q), db = r.b(1, q) - r.b(0, q);
    const double c = std::clamp(dot(da, db) / (norm(da) * norm(db)), -1.0, 1.0);
    r.max_kink = std::max(r.max_kink, std::acos(c));
  }
  return r;
}

}  // namespace aq::curvilinear

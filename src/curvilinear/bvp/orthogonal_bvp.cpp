// SPDX-License-Identifier: GPL-3.0-or-later
// Outer iteration of the orthogonal-family method; see orthogonal_bvp.hpp.
#include "curvilinear/bvp/orthogonal_bvp.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"

namespace aq::curvilinear {

bool bvp_leveled_off(double prev, double now, double tol) {
  if (now == prev) return true;
  return std::fabs(now - prev) <= tol * std::max(std::fabs(now), std::fabs(prev));
}

BvpResult orthogonal_bvp(const SurfaceGrid& initial, const BvpOptions& o, const ThetaEta* initial_solution) {
  if (o.max_iterations < 1 || o.min_iterations < 1 || !(o.level_off >= 0.0))  // regional.bvp_iterations: at load
    throw InternalError(
        fmt::format("bvp: max_iterations = {}, min_iterations = {}, level_off = {} (need >= 1, >= 1, >= 0)",
                    o.max_iterations, o.min_iterations, o.level_off));
  BvpResult r;
  const SurfaceOrthogonality q0 = surface_orthogonality(initial);
  r.f_max.push_back(q0.f_max);
  r.f_avg.push_back(q0.f_avg);
  SurfaceGrid reference = initial;
  std::vector<double> guess_theta, guess_eta;
  const auto np = static_cast<int>(o.theta_levels.size()), nq = static_cast<int>(o.eta_levels.size());
  double best = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= o.max_iterations; ++k) {
    const ThetaEta te = k == 1 && initial_solution != nullptr
                            ? *initial_solution
                            : solve_theta_eta(reference, o.solver, guess_theta, guess_eta);
    SurfaceGrid grid = level_intersections(reference, te.theta, te.eta, o.theta_levels, o.eta_levels, o.interpolation);
    if (o.project) o.project(grid);
    const SurfaceOrthogonality q = surface_orthogonality(grid);
    r.f_max.push_back(q.f_max);
    r.f_avg.push_back(q.f_avg);
    r.aspect_ratio.push_back(te.aspect_ratio());
    r.energy_product.push_back(te.energy_theta * te.energy_eta);
    r.cg_iterations.push_back(te.iterations_theta + te.iterations_eta);
    r.iterations = k;
    if (q.f_avg < best) {
      best = q.f_avg;
      r.grid = grid;
      r.best_iteration = k;
    }
    if (k >= o.min_iterations && bvp_leveled_off(r.f_max[r.f_max.size() - 2], q.f_max, o.level_off) &&
        bvp_leveled_off(r.f_avg[r.f_avg.size() - 2], q.f_avg, o.level_off))
      break;
    if (q.f_max < 1e-13) break;  // exact to round-off (orthogonal by construction)
    // The new grid is the next reference; its nodes sit on the levels, a good CG start.
    reference = std::move(grid);
    guess_theta.assign(reference.p.size(), 0.0);
    guess_eta.assign(reference.p.size(), 0.0);
    for (int j = 0; j < nq; ++j)
      for (int i = 0; i < np; ++i) {
        guess_theta[reference.at(i, j)] = o.theta_levels[static_cast<std::size_t>(i)];
        guess_eta[reference.at(i, j)] = o.eta_levels[static_cast<std::size_t>(j)];
      }
  }
  return r;
}

}  // namespace aq::curvilinear

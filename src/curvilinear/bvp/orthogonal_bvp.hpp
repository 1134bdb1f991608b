// SPDX-License-Identifier: GPL-3.0-or-later
// The orthogonal-family grid generator of seed 003 (digest orthogonal_bvp_and_elliptic.md A.1,
// A.8): outer iterations of
//
//   reference grid k−1 --solve_theta_eta--> θ, η --level_intersections--> grid k --project--> grid k
//
// starting from a given reference grid (usually transfinite_interpolation.hpp), with grid k the
// reference of iteration k+1. Node clustering comes from the levels θ_p, η_q (applied at every
// iteration). Stops when f_max and f_avg (surface_orthogonality.hpp) both change by less than
// `level_off` relative, or after max_iterations; the iterate with the smallest f_avg is returned
// (surface histories are not monotone, digest A.8). Deterministic (no random perturbation), serial.
#pragma once

#include <functional>
#include <vector>

#include "curvilinear/bvp/level_intersections.hpp"
#include "curvilinear/bvp/surface_grid.hpp"
#include "curvilinear/bvp/surface_orthogonality.hpp"
#include "curvilinear/bvp/theta_eta.hpp"

namespace aq::curvilinear {

struct BvpOptions {
  std::vector<double> theta_levels;  ///< θ_p, p = 0..P: 0 ... 1 strictly increasing (graded_levels)
  std::vector<double> eta_levels;    ///< η_q, q = 0..Q
  LevelInterpolation interpolation = LevelInterpolation::kLinear;
  int max_iterations = 10;  ///< outer iterations, ≥ 1
  int min_iterations = 2;   ///< outer iterations before the level-off test applies
  double level_off = 1e-2;  ///< relative change of f_max and f_avg below which iterating stops
  ThetaEtaOptions solver;
  /// Applied to every new grid before its quality is measured: boundary nodes back onto the true
  /// boundary, nodes back onto the surface (empty = none).
  std::function<void(SurfaceGrid&)> project;
};

struct BvpResult {
  SurfaceGrid grid;                    ///< the best iterate ((P+1) × (Q+1))
  int best_iteration = 0;              ///< its k (1-based)
  int iterations = 0;                  ///< outer iterations run
  std::vector<double> f_max, f_avg;    ///< k = 0 (the initial reference grid) .. iterations
  std::vector<double> aspect_ratio;    ///< sqrt(E(η)/E(θ)) per iteration (W/H of the conformal map)
  std::vector<double> energy_product;  ///< E(θ)·E(η) per iteration (≥ 1, → 1)
  std::vector<int> cg_iterations;      ///< CG iterations (θ + η) per iteration
};

/// Runs the outer iteration from `initial` (≥ 2 × 2 points, valid cells); `initial_solution`, when
/// given, is solve_theta_eta(initial) already computed (e.g. for the conformal modulus). Throws
/// InternalError for bad levels or options (regional.bvp_* are validated at load), NumericalError from the solver or
/// the tracing.
BvpResult orthogonal_bvp(const SurfaceGrid& initial, const BvpOptions& options,
                         const ThetaEta* initial_solution = nullptr);

/// The A.8 level-off test of one measure: |now − prev| ≤ tol · max(|now|, |prev|) (true when equal).
bool bvp_leveled_off(double prev, double now, double tol);

}  // namespace aq::curvilinear

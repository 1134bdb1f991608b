// SPDX-License-Identifier: GPL-3.0-or-later
// izogrid mode 3: the inverse problem for the boundary nodes (seed 000 Sec. 2.4, eqs. (22)–(26),
// Fig. 10 bottom; digest izogrid.md §7.2).
//
// Find parameters s_k of the boundary nodes on the spline contour such that the revised IZ89 map
// of the node polygon onto a rectangle puts them at *uniformly spaced* points of the rectangle's
// sides. Outer iteration m = 1, 2, ...:
//   1. z_k = C(s_k) on all four sides (the IZ89 working polygon is made of the nodes themselves);
//   2. M(m) passes of IZ89 (the inner-pass schedule below), stopped early at IZ89's tolerance;
//   3. on each rectangle side, t'_k = (distance from the side's first corner)/(side length);
//      residual r_m = max |t'_k − k/(n−1)| over all nodes;
//   4. nx re-chosen so the rectangle's cells are square (ny fixed): with W = (|S|+|N|)/2,
//      H = (|E|+|W|)/2, L − 1 = c·round((M − 1)/c · W/H), c = cell_multiple (2 for a supergrid);
//   5. each side separately, s_new at the uniform targets by Lagrange interpolation of s(t')
//      (eq. (26) with higher order than linear: 4 points by default).
// Stops when r_m ≤ tolerance with IZ89 converged for that iterate; the nodes returned are the
// ones whose residual was measured (no untested final update).
//
// Inner-pass schedule (ambiguity §13.1: the PDF text "M = √2m+5" has lost its superscripts):
//   kExponential  M(m) = ⌈2^((m+5)/2)⌉ = 8, 12, 16, 23, 32, ...   (default, measured to converge)
//   kSqrt         M(m) = ⌈√(2m+5)⌉     = 3, 3, 4, 4, 4, 5, ...     (IZ89 never converges within
//                 M passes, so the outer loop converges to a wrong fixed point that "looks"
//                 converged: measured on the Black Sea with full inner solves, 12 outer
//                 iterations, the measured residual dips to 3.5e-12 while the true one, with IZ89
//                 converged on the same nodes, is 2.7e-7; the exponential reading reaches a true
//                 9e-13 in 8 iterations, ~20× per iteration)
// In both, IZ89 stops earlier when it converges, and M is capped by max_inner_passes. By default
// the inner solves are also inexact early on (inner_relative_tolerance), which saves ~30% of the
// passes; the accepted iterate is always re-checked with IZ89 converged to round-off.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/log.hpp"
#include "curvilinear/common/boundary_nodes.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "grid_params/grid_kinds.hpp"

namespace aq::curvilinear {

/// Number of full IZ89 passes allowed at outer iteration m ≥ 1 (before the cap).
int inner_pass_count(InnerSchedule schedule, int m);

struct InverseOptions {
  InnerSchedule schedule = InnerSchedule::kExponential;
  /// Cap on the IZ89 passes of one outer iteration.
  int max_inner_passes = 64;
  /// IZ89 convergence: largest turning angle per pass, radians (see Iz89Options).
  double iz89_angle_tolerance = 1e-14;
  /// IZ89 round-off floor detection threshold, radians (see Iz89Options).
  double iz89_floor_threshold = 1e-10;
  /// Outer convergence: max |t' − t'∞| (fraction of the side length), > 0. Raised to the
  /// round-off floor 4e-18·Nb² when that is larger (1e-10 at Nb = 5000 boundary nodes).
  double tolerance = 1e-12;
  /// Stalled residual accepted as converged: when three successive iterates with IZ89 converged
  /// to round-off no longer halve the residual and it is at most this, the distribution has
  /// reached its round-off floor (seen at 4e-12 on a 4-point contour of 176 nodes, above the
  /// 4e-18·Nb² model). 0 = never.
  double floor_residual = 1e-10;
  /// Outer iterations before NumericalError (the message gives the residual reached).
  int max_outer_iterations = 40;
  /// Points of the Lagrange interpolation of s(t') in (26): 2 = linear (the paper's simplest
  /// case), 4 = cubic (default), up to 8.
  int interpolation_points = 4;
  /// Re-choose nx from the rectangle's aspect ratio (ny is never changed).
  bool auto_nx = true;
  /// L − 1 and M − 1 are multiples of this: 2 for a supergrid of (2nx+1)×(2ny+1) points, whose
  /// cells then number nx × ny in the final (ρ-point) grid; 1 for a plain grid.
  int cell_multiple = 2;
  /// nx is no longer changed once the residual is below this (avoids flipping between two
  /// values when ny·W/H is close to a half-integer).
  double nx_freeze_residual = 1e-5;
  /// Inexact inner solves: at outer iteration m IZ89 stops at a turning angle of
  /// max(iz89_angle_tolerance, inner_relative_tolerance · r_{m−1}); the accepted iterate is
  /// always re-checked with IZ89 converged to round-off. 0 = always converge IZ89 fully.
  double inner_relative_tolerance = 1e-2;
  /// Anderson acceleration of the outer loop over this many previous iterates (0 = plain
  /// fixed-point iteration as in the paper).
  int acceleration_depth = 0;
  /// Throw NumericalError at the iteration limit (false: return with converged = false).
  bool fail_on_limit = true;
  /// OpenMP threads for IZ89 (0 = default).
  int threads = 0;
};

struct InverseResult {
  BoundaryNodes nodes;                   ///< final node parameters (nx_pts may differ from the input)
  double aspect_ratio = 0.0;             ///< W/H of the rectangle of the final nodes
  double residual = 0.0;                 ///< residual of the final nodes
  double tolerance = 0.0;                ///< the tolerance applied (after the round-off floor)
  bool converged = false;                ///< residual ≤ tolerance (or at its floor) with IZ89 converged
  bool at_floor = false;                 ///< converged by the stalled-residual rule (floor_residual)
  std::vector<double> residual_history;  ///< r_m per outer iteration
  std::vector<double> aspect_history;    ///< W/H per outer iteration
  std::vector<int> nx_pts_history;       ///< L per outer iteration
  std::vector<int> inner_passes;         ///< IZ89 passes done per outer iteration
  std::vector<double> iz89_angle;        ///< IZ89's last max turning angle per outer iteration
  std::vector<double> rect_x, rect_y;    ///< IZ89 image (rectangle) of the final nodes
  int outer_iterations = 0;
  double seconds = 0.0;  ///< wall time
};

/// Measures the distribution of a straightened polygon: residual (max |t' − k/(n−1)|) and W/H.
struct RectangleMeasure {
  double residual = 0.0;
  double aspect_ratio = 0.0;
  std::array<double, 4> side_length{};  ///< S, E, N, W in the polygon's units
};
RectangleMeasure measure_rectangle(const std::vector<double>& x, const std::vector<double>& y,
                                   const BoundaryNodes& nodes);

/// Solves the inverse problem from `initial` (e.g. uniform_boundary_nodes()). Throws
/// NumericalError when max_outer_iterations pass without convergence (message: the residual
/// reached, the tolerance and the schedule), when IZ89 fails, or when a side's image is not
/// monotone; InternalError for bad options (tolerance ≤ 0, interpolation_points outside 2..8,
/// cell_multiple < 1, M − 1 not a multiple of cell_multiple: the config validates its keys at load).
InverseResult solve_inverse_problem(const SplineContour& contour, const BoundaryNodes& initial,
                                    const InverseOptions& options = {}, const Logger& log = Logger::null());

}  // namespace aq::curvilinear

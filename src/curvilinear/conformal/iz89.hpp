// SPDX-License-Identifier: GPL-3.0-or-later
// Revised Ives & Zacharias (1989) polygon -> rectangle straightening, "IZ89" (seed 000 Sec. 2.3
// eqs. (17)–(21) and Sec. 2.4; digest izogrid.md §5 and §6.2, the reconstruction validated by a
// prototype).
//
// One pass visits every vertex k counter-clockwise from the SW corner and applies the elementary
// conformal power map centred at z_k to all other vertices, which straightens vertex k (turning
// angle -> 0) or, at the four corners, makes the interior angle exactly π/2, keeping z_{k−1}
// and z_k fixed. In the identity-like real form of §5,
//
//     z'_j − z_k = (r_j/ℓ)^ε · Rot(ε θ_j) · (z_j − z_k),   ε = P − 1,  ℓ = |z_k − z_{k−1}|,
//
// with θ_j the argument of z_j − z_k measured from the backward ray z_k -> z_{k−1}, continuous
// along the contour from θ_{k+1} = −A_int (the interior angle) to θ_{k−1} = 0, and
// P = π/A_int (regular vertex) or (π/2)/A_int (corner). The paper's revisions are kept: no
// complex numbers; atan2 only of the turning angles (small near convergence, so the map tends
// to the identity and round-off does not accumulate); the 2π continuity of θ is recovered in
// parallel chunks (each chunk unwraps locally with integer winding numbers, then a short prefix
// over the chunks fixes the multiples of 2π at the joins). Integer windings make the result
// bit-identical for any number of threads. A guard like the original RECT clamp keeps the mapped
// angular span below 1.98π for wild contours.
//
// Cost O(Nb) per vertex, O(Nb²) per pass (measured ~18 ns per point update, i.e. 0.5 s per pass
// at Nb = 5228 on one core); about one decade of max |α| per pass down to a round-off floor that
// grows like Nb². Near the identity the power map uses short Taylor polynomials of exp, cos, sin.
#pragma once

#include <array>
#include <span>
#include <vector>

namespace aq::curvilinear {

struct Iz89Options {
  /// Passes before returning unconverged (the caller decides whether that is an error).
  int max_passes = 100;
  /// Converged when the largest turning angle of a pass (|α| at regular vertices, |α − π/2| at
  /// corners, radians) is at most this.
  double angle_tolerance = 1e-14;
  /// Also converged when the largest angle is below max(this, 1e-15·Nb²) and no longer falls by
  /// the usual decade per pass: the round-off floor, which grows like Nb² (4e-12 rad at Nb = 460,
  /// 4e-10 rad at Nb = 5228), radians.
  double floor_threshold = 1e-10;
  /// OpenMP threads. 0 = choose, chunk by chunk of 128 vertex maps, between one thread and the
  /// OpenMP default by timing both (each vertex map costs two barriers, which on a busy machine
  /// can cost far more than the work they split: measured 10× slower with 2 threads at load 9
  /// on 2 cores). > 0 = exactly this many. Results are bit-identical for any choice.
  int threads = 0;
  /// Polygons with fewer vertices always run on one thread (a vertex map must have thousands of
  /// points before splitting it pays for the barriers).
  int min_parallel_vertices = 2048;
};

struct Iz89Result {
  int passes = 0;                 ///< passes done
  bool converged = false;         ///< tolerance or round-off floor reached
  std::vector<double> max_angle;  ///< largest |turning angle| met during each pass, radians
  int clamped_maps = 0;           ///< vertex maps limited by the 1.98π guard (0 for sane contours)
};

/// Straightens the closed polygon (x, y) (Nb ≥ 4 vertices, counter-clockwise, simple) in place
/// into a rectangle whose corners are the vertices `corners` (SW, SE, NE, NW polygon indices in
/// increasing order, corners[0] = 0). Runs until converged or options.max_passes. The rectangle's
/// size and orientation are whatever the composition of maps leaves (the maps are similarity-
/// equivariant, so only shape matters). Throws InternalError for bad sizes or corner indices,
/// NumericalError if a vertex collapses (zero-length edge) or coordinates become non-finite.
Iz89Result iz89_straighten(std::span<double> x, std::span<double> y, const std::array<int, 4>& corners,
                           const Iz89Options& options = {});

}  // namespace aq::curvilinear

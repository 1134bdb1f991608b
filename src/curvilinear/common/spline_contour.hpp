// SPDX-License-Identifier: GPL-3.0-or-later
// The closed spline contour of a regional grid with exactly right-angled corners (izogrid mode 1;
// seed 000 Sec. 2.1–2.2, eqs. (5)–(15), Appendix 2 (55)–(91); digest izogrid.md §4).
//
// Control points are listed counter-clockwise starting at the SW corner; exactly four of them
// are corners (SW = point 0, then SE, NE, NW). Segment k joins point k to point k+1, segment
// N−1 closes the loop back to the SW corner:
//
//        NW *----<----<----* NE          sides (contour order, counter-clockwise):
//           |      north    |              south  SW -> SE    segments 0 .. kSE−1
//      west v               ^ east         east   SE -> NE    segments kSE .. kNE−1
//           |      south    |              north  NE -> NW    segments kNE .. kNW−1
//        SW *---->---->----* SE            west   NW -> SW    segments kNW .. N−1
//
// The polygon is "unfolded" into one smooth open line (eq. (9), range of the west side
// corrected to kNW..N): differences after SE are rotated 90° clockwise, after NE by 180°, after
// NW by 270°. One periodic cubic (C²) or quintic (C⁴) Hermite spline is fitted to the unfolded
// differences and each segment is rotated back with its side's rotation (eqs. (11)–(15) with the
// digest's corrected signs of δ''). The two tangents at a corner are then the same vector in two
// frames 90° apart: every corner is exactly 90°, whatever the control points.
//
// Parameter: the global contour parameter s runs from 0 at the SW corner over the knots
// s_0 = 0 < s_1 < ... < s_N (= period(), the SW corner again). The knot spacing is 1 (index
// parametrisation σ = k, (85)–(87)) or the iterated arc length of each segment ((62), (70)–(72)
// with Δs from the cubic spline, as the paper recommends for the quintic, §4.6).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "curvilinear/common/plane_point.hpp"
#include "grid_params/grid_kinds.hpp"

namespace aq::curvilinear {

/// The four sides in contour order. Node ordering along a side in the *grid* (positive ξ/η) is
/// south and north west->east, east and west south->north; the contour runs north and west
/// backwards.
enum class Side { kSouth = 0, kEast = 1, kNorth = 2, kWest = 3 };
/// "south", "east", "north", "west".
const char* side_name(Side side);

struct ContourOptions {
  /// 3 = cubic (C²), 5 = quintic (C⁴).
  int degree = 5;
  Parametrisation parametrisation = Parametrisation::kIndex;
  /// Arc-length parametrisation: stop when max |Δs_new/Δs_old − 1| < this (dimensionless).
  double arc_length_tolerance = 1e-14;
  /// Arc-length parametrisation: iterations before NumericalError.
  int arc_length_max_iterations = 100;
  /// Samples per spline segment for the self-intersection and orientation checks (≥ 8).
  int check_samples_per_segment = 64;
  /// Name used in error messages (the input file).
  std::string source = "contour";
};

/// A closed contour through the control points with four exact right-angle corners. Immutable
/// after construction; evaluation is thread-safe.
class SplineContour {
 public:
  /// Builds the spline. `x`, `y`: N ≥ 4 control points in plane units, counter-clockwise from the
  /// SW corner. `corner[k]` marks corners; point 0 is the SW corner whether marked or not.
  /// Throws InputError (naming `options.source`, point numbers counted from 1 and coordinates)
  /// for: a number of corners other than 4, fewer than 4 points, non-finite or repeated
  /// consecutive points, a clockwise contour, a self-intersecting spline (which segments and
  /// where). InternalError for a degree other than 3/5. NumericalError if the arc-length iteration
  /// does not converge.
  SplineContour(std::vector<double> x, std::vector<double> y, const std::vector<bool>& corner,
                const ContourOptions& options = {});

  [[nodiscard]] int num_points() const { return static_cast<int>(x_.size()); }
  [[nodiscard]] int degree() const { return degree_; }
  [[nodiscard]] Parametrisation parametrisation() const { return param_; }
  /// Control-point indices (0-based) of the SW, SE, NE, NW corners.
  [[nodiscard]] const std::array<int, 4>& corners() const { return corners_; }
  [[nodiscard]] const std::vector<double>& control_x() const { return x_; }
  [[nodiscard]] const std::vector<double>& control_y() const { return y_; }

  /// Total parameter s_N of the closed contour (N for the index parametrisation).
  [[nodiscard]] double period() const { return knots_.back(); }
  /// Knot s_k, k = 0..N.
  [[nodiscard]] double knot(int k) const { return knots_[static_cast<std::size_t>(k)]; }
  /// Parameter of the side's first corner in contour order (S: SW, E: SE, N: NE, W: NW).
  [[nodiscard]] double side_begin(Side side) const;
  /// Parameter of the side's last corner in contour order (W ends at period()).
  [[nodiscard]] double side_end(Side side) const;
  /// Global parameter of the point at fraction t ∈ [0, 1] of a side's parameter range, counted in
  /// the grid's positive direction (south, north: west to east; east, west: south to north), so
  /// t = 0 is the SW, SE, NW, SW corner of the south, east, north, west side respectively.
  [[nodiscard]] double side_parameter(Side side, double t) const;
  /// The side a segment (0..N−1) belongs to.
  [[nodiscard]] Side side_of_segment(int segment) const;

  /// Position at parameter s (taken modulo period()).
  [[nodiscard]] PlanePoint point(double s) const;
  /// Derivative d^order C/ds^order, order 1..degree, of the segment [s_k, s_{k+1}) containing s
  /// (mod period()). At a corner this is the outgoing side's derivative.
  [[nodiscard]] PlanePoint derivative(double s, int order = 1) const;
  /// Like derivative(), but s is clamped to the side's range and the side's own segments are used,
  /// so at a corner the result belongs to `side` (incoming or outgoing tangent).
  [[nodiscard]] PlanePoint side_derivative(Side side, double s, int order = 1) const;
  /// Position or derivative (order 0..degree) on segment k at local p = (s − s_k)/Δs_k ∈ [0, 1].
  [[nodiscard]] PlanePoint segment_eval(int segment, double p, int order = 0) const;
  /// Segment containing s (mod period()), 0..N−1.
  [[nodiscard]] int segment_of(double s) const;

  /// Arc length between parameters s0 ≤ s1 (s1 − s0 ≤ period(); may cross corners), in plane
  /// units, by 20-point Gauss–Legendre quadrature per segment piece (relative error ~1e-15).
  [[nodiscard]] double arc_length(double s0, double s1) const;
  /// Arc length of one side.
  [[nodiscard]] double side_length(Side side) const { return arc_length(side_begin(side), side_end(side)); }
  /// Signed curvature 1/r at s (positive for a left turn), (77)–(84).
  [[nodiscard]] double curvature(double s) const;

  /// Closed polyline of `per_segment` points per segment starting at the SW corner (the closing
  /// point is not repeated): N·per_segment points.
  [[nodiscard]] std::vector<PlanePoint> sample(int per_segment) const;

  /// Unfolded first derivatives d'_k (x and y components) at the knots, in the unfolded frame:
  /// what the periodic system solved for (exposed for tests and diagnostics).
  [[nodiscard]] const std::vector<double>& unfolded_dx() const { return dxu_; }
  [[nodiscard]] const std::vector<double>& unfolded_dy() const { return dyu_; }
  /// Iterations the arc-length parametrisation took (0 for the index parametrisation).
  [[nodiscard]] int arc_length_iterations() const { return arc_iterations_; }

 private:
  void fit(const std::vector<double>& h);
  void check_geometry(const ContourOptions& options) const;

  std::vector<double> x_, y_;
  std::array<int, 4> corners_{};
  int degree_ = 5;
  Parametrisation param_ = Parametrisation::kIndex;
  std::string source_;
  std::vector<double> knots_;  // N+1
  std::vector<double> h_;      // N
  std::vector<int> side_;      // per segment
  // Unfolded knot derivatives (periodic).
  std::vector<double> dxu_, dyu_, ddxu_, ddyu_;
  // Per segment, back-rotated Hermite data: slope and second derivative at both ends.
  struct SegmentData {
    double dlx, dly, drx, dry, ddlx, ddly, ddrx, ddry;
  };
  std::vector<SegmentData> seg_;
  int arc_iterations_ = 0;
};

}  // namespace aq::curvilinear

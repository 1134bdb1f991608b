// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary nodes by 1-D equidistribution (seed 004 Sec. 1; digest orthogonal_bvp_and_elliptic.md
// B.2): on each side, nodes such that (s_{k+1} − s_k) · w(x(s_{k+1/2})) is the same for every 1-D
// cell, so the nodes are denser where the control function w is large; w ≡ 1 gives equal arc length.
//
// Every curve is a dense polyline of support points (the paper's internal form). Iteration [DEV]:
// start uniform in arc length; each sweep freezes w_k at the cell midpoints, builds the piecewise
// constant density ρ = w_k and puts the new nodes at equal increments of W(s) = ∫ρ ds, under-relaxed
// with ω = 0.5; stop when max |Δs| < 1e-10·L or after 100 sweeps (the last iterate is kept).
#pragma once

#include <vector>

#include "curvilinear/common/boundary_nodes.hpp"
#include "curvilinear/common/plane_point.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "grid_params/control_function.hpp"

namespace aq::curvilinear {

/// A polyline with its cumulative arc length (`arc[0] = 0`, `arc.back()` = length).
struct ArcPolyline {
  std::vector<PlanePoint> points;
  std::vector<double> arc;

  ArcPolyline() = default;
  /// Two or more points; repeated consecutive points are allowed (zero-length pieces).
  explicit ArcPolyline(std::vector<PlanePoint> pts);
  [[nodiscard]] double length() const { return arc.empty() ? 0.0 : arc.back(); }
  /// Point at arc length a ∈ [0, length()] (clamped), linear on the piece containing it.
  [[nodiscard]] PlanePoint at(double a) const;
  /// Piece index k and fraction t ∈ [0, 1] of arc length a: the point is points[k] + t·(points[k+1] − points[k]).
  void locate(double a, int& k, double& t) const;
};

/// Arc-length positions of n ≥ 2 nodes on `line` equidistributing w (first 0, last length()).
std::vector<double> equidistribute(const ArcPolyline& line, int n, const ControlFunction& w);

/// Positions of n nodes on `line` (equidistribute() then at()).
std::vector<PlanePoint> equidistributed_points(const ArcPolyline& line, int n, const ControlFunction& w);

/// Boundary nodes of an nx_pts × ny_pts grid on the spline contour, equidistributing w on each
/// side. Each side is sampled with `samples_per_segment` points per spline segment; a node's
/// parameter is interpolated linearly in arc length between samples, so every node lies exactly on
/// the spline and the equidistribution holds to the sampling error. nx_pts, ny_pts ≥ 2.
BoundaryNodes equidistributed_boundary_nodes(const SplineContour& contour, int nx_pts, int ny_pts,
                                             const ControlFunction& w, int samples_per_segment = 64);

}  // namespace aq::curvilinear

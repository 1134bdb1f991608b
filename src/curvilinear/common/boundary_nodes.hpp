// SPDX-License-Identifier: GPL-3.0-or-later
// Boundary nodes of a regional grid on the spline contour, and izogrid mode 2: uniform filling
// of each side as the initial guess of the inverse problem (seed 000 Sec. 2.4 "initial
// approximation", Fig. 10 top; digest izogrid.md §7 and §7.1).
//
// Nodes are kept as contour parameters s (see spline_contour.hpp), so that moving a node means
// moving it along the contour. For an L×M grid (L nodes along ξ on the south and north sides,
// M along η on the east and west sides) there are Nb = 2(L−1) + 2(M−1) nodes, counter-clockwise
// from the SW corner, with the corners at polygon indices
//
//        2L+M−3 (NW) *--<--<--<--* L+M−2 (NE)
//                    v           ^
//             0 (SW) *-->-->-->--* L−1 (SE)
//
// and s increasing from 0 (SW) to period() (exclusive): the west side's last node is the SW
// corner again (index 0), whose parameter on that side is period().
#pragma once

#include <array>
#include <vector>

#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/spline_contour.hpp"

namespace aq::curvilinear {

/// Boundary nodes of an nx_pts × ny_pts grid as contour parameters, counter-clockwise from SW.
struct BoundaryNodes {
  int nx_pts = 0;         ///< L: nodes on the south and north sides, corners included (≥ 2)
  int ny_pts = 0;         ///< M: nodes on the east and west sides, corners included (≥ 2)
  std::vector<double> s;  ///< Nb = 2(L−1) + 2(M−1) parameters, increasing, s[0] = SW corner

  [[nodiscard]] int count() const { return 2 * (nx_pts - 1) + 2 * (ny_pts - 1); }
  /// Polygon index of corner c (0 = SW, 1 = SE, 2 = NE, 3 = NW).
  [[nodiscard]] std::array<int, 4> corner_indices() const {
    return {0, nx_pts - 1, nx_pts + ny_pts - 2, 2 * nx_pts + ny_pts - 3};
  }
  /// Number of nodes on a side, both corners included (L for south/north, M for east/west).
  [[nodiscard]] int side_count(Side side) const {
    return (side == Side::kSouth || side == Side::kNorth) ? nx_pts : ny_pts;
  }
};

/// Parameters of one side's nodes in contour order, both corners included; increasing (the
/// west side ends with period() for the SW corner).
std::vector<double> side_parameters(const SplineContour& contour, const BoundaryNodes& nodes, Side side);
/// Stores a side's parameters (contour order, corners included, as from side_parameters()).
/// When nodes.nx_pts/ny_pts change, set all four sides in order S, E, N, W after resizing s.
void set_side_parameters(BoundaryNodes& nodes, Side side, const std::vector<double>& params);
/// Polygon index of the k-th node of a side in contour order (k = 0..side_count−1).
int polygon_index(const BoundaryNodes& nodes, Side side, int k);

/// Positions of the nodes (the IZ89 working polygon), counter-clockwise from SW.
void node_positions(const SplineContour& contour, const BoundaryNodes& nodes, std::vector<double>& x,
                    std::vector<double>& y);

/// Writes the node positions into the boundary rows/columns of `grid` (which must be
/// nodes.nx_pts × nodes.ny_pts, InternalError otherwise): south j = 0, east i = L−1, north
/// j = M−1, west i = 0, in the Grid2D index convention (grid2d.hpp).
void set_grid_boundary(const SplineContour& contour, const BoundaryNodes& nodes, Grid2D& grid);

struct UniformOptions {
  /// Stop the step correction when the last chord differs from the step h by less than
  /// tolerance × h (dimensionless), or when it stops improving below 1e-9·h (the round-off
  /// floor: every node carries ~1 ulp of its parameter, ~1e-13·h for 100 nodes).
  double tolerance = 1e-14;
  /// Step corrections per side before NumericalError.
  int max_iterations = 60;
};

struct UniformStats {
  std::array<int, 4> iterations{};  ///< step corrections used per side (S, E, N, W)
  std::array<double, 4> step{};     ///< final chord step per side, plane units
};

/// Mode 2 (§7.1): on each side, nodes at equal chord distance h from corner to corner. Each node
/// is found from the previous one by safeguarded Newton on |C(s) − C(s_prev)| = h (the first
/// crossing along the contour); h starts from the control-point polyline length and is
/// corrected by the miss at the next corner (secant on the last chord minus h), to round-off.
/// nx_pts, ny_pts ≥ 2 (InternalError otherwise). Throws NumericalError if the correction
/// does not converge (the message names the side and the miss).
BoundaryNodes uniform_boundary_nodes(const SplineContour& contour, int nx_pts, int ny_pts,
                                     const UniformOptions& options = {}, UniformStats* stats = nullptr);

}  // namespace aq::curvilinear

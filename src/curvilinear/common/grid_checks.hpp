// SPDX-License-Identifier: GPL-3.0-or-later
// Quality of a planar curvilinear grid: the izogrid `checkort` diagnostics (seed 000 Sec. 2.6,
// eqs. (44)–(52); digest izogrid.md §10) and the seed-004 cell criteria f1–f4 (digest
// orthogonal_bvp_and_elliptic.md B.5).
//
// Cell (i, j) has corners 1 = (i, j), 2 = (i+1, j), 3 = (i+1, j+1), 4 = (i, j+1), counter-clockwise
// for a valid cell, and is stored at index j·(nx_pts−1) + i:
//
//        4 = (i,j+1) +-----------+ 3 = (i+1,j+1)        north edge  a1 = P3 − P4
//                    |           |                      south edge  a0 = P2 − P1
//         west edge  |  (i, j)   |  east edge           west edge   b0 = P4 − P1
//         b0         |           |  b1                  east edge   b1 = P3 − P2
//        1 = (i,j)   +-----------+ 2 = (i+1,j)
//
// Orthogonality errors are ε = cos∠(ℓξ, ℓη) = (ℓξ·ℓη)/(|ℓξ||ℓη|), eq. (48): positive when the angle
// between the ξ and η lines is acute.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "curvilinear/common/grid2d.hpp"

namespace aq::curvilinear {

/// Where a quality field lives: on cells ((nx_pts−1)·(ny_pts−1) values) or on nodes (nx_pts·ny_pts).
enum class FieldLocation { kCell, kNode };

/// One criterion: its per-cell or per-node values and grid-level statistics.
struct QualityField {
  std::string name;       ///< netCDF variable name, e.g. "ortho_err_50"
  std::string long_name;  ///< one line for tables and attributes
  FieldLocation location = FieldLocation::kCell;
  /// true: an error (ideal 0); worst = max |v|, average = mean |v|, rms = sqrt(mean v²).
  /// false: a seed-004 score (ideal 1); worst = min v, average = mean v, rms = NaN.
  bool is_error = true;
  std::vector<double> values;  ///< signed values, row-major (j · n_i + i); NaN where not defined
  double worst = 0.0;
  double average = 0.0;
  double rms = 0.0;
  int worst_i = -1;  ///< cell or node index of the worst value (-1 if no value is defined)
  int worst_j = -1;
  int count = 0;  ///< number of values entering the statistics
};

struct CheckOptions {
  /// ρ = Δξ/Δη of the computational grid; ≤ 0 means "estimate it with estimate_step_ratio".
  double dxi_over_deta = 0.0;
  /// Laplace residual of the 5-point instead of the 9-point operator.
  bool five_point = false;
  /// Control function w(x, y) of criterion f3 (seed 004 (4.1)), evaluated at the cell centroid;
  /// empty means w ≡ 1 (f3 then measures uniformity of cell areas).
  std::function<double(double x, double y)> weight;
  /// Only the cell fields (46), (50), (51) and f1–f4: skip the spline form (52) and the Laplace
  /// residual (left empty), for callers that evaluate criteria every few iterations.
  bool cells_only = false;
};

struct GridQuality {
  int nx_pts = 0;
  int ny_pts = 0;
  double dxi_over_deta = 1.0;       ///< the ρ used (given or estimated)
  QualityField ortho_46;            ///< cells: equal-diagonal form (46)
  QualityField ortho_50;            ///< cells: length-weighted form (50)
  QualityField ortho_52;            ///< nodes: spline form (52); interior nodes only (NaN on the boundary)
  QualityField isotropy_51;         ///< cells: |ℓξ|/(ρ|ℓη|) − 1 with harmonic-mean lengths (51)
  QualityField laplace_residual;    ///< nodes: |L z|/|δ| / local spacing; interior nodes only
  QualityField f1;                  ///< cells: convexity, min triangle area / (½ cell area), ≤ 1
  QualityField f2;                  ///< cells: orthogonality, min sin(interior angle), ≤ 1
  QualityField f3;                  ///< cells: area law min(wS/C, C/wS), ≤ 1
  QualityField f4;                  ///< cells: aspect ratio, shortest/longest side, ≤ 1
  double isotropy_ratio_min = 0.0;  ///< range of |ℓξ|/|ℓη| (51), unnormalised (target ρ)
  double isotropy_ratio_max = 0.0;
  int non_convex_cells = 0;  ///< cells with f1 ≤ 0 (degenerate, non-convex, inverted)
  /// One message per field that is NaN where it is defined (every cell; interior nodes for the
  /// node fields), naming the first such cell / node and its corner coordinates. ±∞ are not
  /// listed: they are the documented worst values of degenerate cells (f1 = −∞ inverted, isotropy
  /// and residual +∞ for a zero side) and show as the field's worst. Non-empty = the check failed.
  std::vector<std::string> non_finite;

  /// All fields in table order.
  [[nodiscard]] std::vector<const QualityField*> fields() const;
};

/// Computes every criterion. Requires nx_pts, ny_pts ≥ 2 and finite coordinates (the spline form
/// and the Laplace residual need ≥ 3 points in each direction and are left empty otherwise).
/// Throws InputError for a grid that is too small or has non-finite nodes (naming the node);
/// a NaN criterion from finite nodes is listed in GridQuality::non_finite.
GridQuality check_grid(const Grid2D& grid, const CheckOptions& options = {});

/// ρ = Δξ/Δη estimated from the grid as Σ_cells(|a0| + |a1|) / Σ_cells(|b0| + |b1|) (ξ-edge over
/// η-edge lengths, see the cell picture above): a conformal grid has |ℓξ|/|ℓη| = ρ in every cell up
/// to the discretisation error. For files that do not record their steps. Returns 1 for a grid
/// with fewer than 2 points in a direction or zero η-edge length.
double estimate_step_ratio(const Grid2D& grid);

}  // namespace aq::curvilinear

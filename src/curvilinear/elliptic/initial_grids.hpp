// SPDX-License-Identifier: GPL-3.0-or-later
// Initial (algebraic) grids of seed 004 Sec. 2 (digest orthogonal_bvp_and_elliptic.md B.3): classic
// transfinite interpolation (TFI), TFI with internal sections and normalised blending functions,
// and STAR for star-shaped domains; plus the test whether interior coordinate lines cross the
// boundary. Every function takes a Grid2D whose boundary rows/columns are set (grid2d.hpp: south
// j = 0, east i = L−1, north j = M−1, west i = 0) and fills the interior; q1 = i/(L−1), q2 = j/(M−1).
//
// Sections (q1 = const curves, "A¹_l" of the paper) are grid columns i = m_l given completely
// (boundary nodes included); the Boolean sum is
//
//   F(q1, q2) = Σ_l α_l(q1) A¹_l(q2),   x = F + (1 − q2)(x(q1, 0) − F(q1, 0)) + q2 (x(q1, 1) − F(q1, 1))
//
// with the smooth blending α_l = φ^F_l φ^B_l, φ(t) = sin²(πt/2), of the paper's (2.1) divided by
// Σ_k α_k: the paper's α_l are not a partition of unity (Σα = 0.5 at q = 0.5 for L = 2), which
// distorts even a rectangle; normalised, TFI reproduces any grid that is a tensor product of its
// boundary distributions. Without internal sections, classic TFI (linear blending both ways).
#pragma once

#include <vector>

#include "curvilinear/elliptic/boundary_equidistribution.hpp"
#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/common/plane_point.hpp"
#include "grid_params/control_function.hpp"

namespace aq::curvilinear {

/// Normalised blending weights α_l(q), l = 0..L−1, of sections at increasing q_sections (first 0,
/// last 1, L ≥ 2): Σα = 1, α_l(q_k) = δ_lk, smooth (C¹) in q. Writes `alpha` (resized to L).
void blending_weights(const std::vector<double>& q_sections, double q, std::vector<double>& alpha);

/// The paper's raw α_l(q) (2.1), not normalised (for the test that shows why normalisation is needed).
void raw_blending_weights(const std::vector<double>& q_sections, double q, std::vector<double>& alpha);

/// An internal section q1 = column/(L−1): the grid column `column` (0 < column < L−1) is a curve from
/// the south node (column, 0) through `points` (plane units; may be empty = straight) to the north
/// node (column, M−1). As a row section (SectionLines::kRows) `column` is the row j, q2 = j/(M−1),
/// and the curve runs from the west node (0, j) to the east node (L−1, j).
struct Section {
  int column = 0;
  std::vector<PlanePoint> points;
};
/// Which coordinate lines the sections are: q1 = const (columns, the paper's A¹) or q2 = const
/// (rows, A²). TFI interpolates between the sections of one direction.
enum class SectionLines { kColumns, kRows };

/// Fills the nodes of a section column: a Catmull–Rom curve from the south node through the interior
/// points to the north node, sampled densely, with M nodes placed by 1-D equidistribution of w.
void set_section_column(Grid2D& grid, const Section& section, const ControlFunction& w);

/// TFI of the interior from the boundary and the section columns already set in `grid` (columns
/// strictly increasing, inside 1..L−2; none = classic TFI). InternalError for bad columns.
void tfi_fill(Grid2D& grid, const std::vector<int>& section_columns);

/// The grid with ξ and η exchanged: node (i, j) becomes (j, i). Exchanging them twice, or together
/// with x and y, keeps the orientation.
Grid2D transposed(const Grid2D& grid);

/// TFI of `grid` (boundary set) with internal sections along columns or rows: sets each section's
/// nodes (set_section_column, on the transposed grid for rows) and fills the interior (tfi_fill).
/// Sections must increase inside 1..L−2 (columns) or 1..M−2 (rows).
void tfi_with_sections(Grid2D& grid, const std::vector<Section>& sections, SectionLines lines,
                       const ControlFunction& w);

/// Kernel of a counter-clockwise simple polygon (the points from which the whole polygon is
/// visible), by clipping its bounding box with the inner half-plane of every edge. Empty when the
/// polygon is not star-shaped (or the kernel has zero area).
std::vector<PlanePoint> polygon_kernel(const std::vector<PlanePoint>& polygon);

/// STAR (seed 004 Sec. 2): the pole is the centroid of the kernel of the boundary-node polygon; the
/// middle row j = (M−1)/2 runs west node → pole → east node, each row below (above) it runs along
/// the segments joining the west, south (north) and east boundary nodes to the pole, and every row
/// gets its L nodes by 1-D equidistribution of w. Throws InputError ("not star-shaped") when the
/// kernel is empty. Returns the pole.
PlanePoint star_fill(Grid2D& grid, const ControlFunction& w);

/// The ring of boundary nodes counter-clockwise from SW (south, east, north reversed, west reversed).
std::vector<PlanePoint> boundary_ring(const Grid2D& grid);

/// Number of cells whose signed area is ≤ 0 or whose opposite edges cross (self-intersecting).
int self_intersecting_cells(const Grid2D& grid);

/// Number of segments between consecutive nodes of interior coordinate lines (rows 1..M−2 and
/// columns 1..L−2, including their end segments at the boundary) that properly intersect a segment
/// of the boundary-node ring (seed 004's "grid crosses the boundary" flag). Uses a bin grid.
int boundary_crossings(const Grid2D& grid);

}  // namespace aq::curvilinear

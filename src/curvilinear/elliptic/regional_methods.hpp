// SPDX-License-Identifier: GPL-3.0-or-later
// The seed-004 generators as regional methods (digest orthogonal_bvp_and_elliptic.md B.2–B.6): the
// pipeline (regional.hpp) builds the contour as for the conformal method, then, for method tfi,
// star, ed2, rl or best, puts the boundary nodes by 1-D equidistribution of w on each side
// (boundary_equidistribution.hpp) and builds the supergrid with build_method_grid(). The result is
// the same Grid2D as the Laplace fill's, so every file and check downstream is unchanged.
//
//   tfi   classic TFI, or TFI with the internal sections of `sections` (initial_grids.hpp)
//   star  STAR from the kernel's centroid; refused (InputError) when the domain is not star-shaped
//   ed2   ED2 from the tfi grid (elliptic_grids.hpp)
//   rl    Ryskin–Leal from the tfi grid
//   best  candidates STAR (when star-shaped), classic TFI, TFI with sections (those given, else one
//         straight section at q1 = 1/2) and the conformal grid; B.6 chooses one (grid_selection.hpp)
//         and best_final (ed2 or rl) runs from it; the elliptic grid is kept only if B.6 between it
//         and the chosen grid (ties to the chosen one) picks it, so best is never worse than the winner
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/log.hpp"
#include "curvilinear/common/boundary_nodes.hpp"
#include "curvilinear/elliptic/elliptic_grids.hpp"
#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/elliptic/grid_selection.hpp"
#include "curvilinear/elliptic/initial_grids.hpp"
#include "curvilinear/common/projection.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "grid_params/control_function.hpp"
#include "grid_params/regional_params.hpp"

namespace aq::curvilinear {

/// What build_method_grid() did.
struct MethodRun {
  Grid2D grid;
  BoundaryNodes nodes;                     ///< the boundary nodes of `grid` (the conformal ones if `best` chose it)
  std::string initial;                     ///< the initial grid used ("tfi", "tfi+1 section", "star", "conformal", ...)
  std::optional<EllipticResult> elliptic;  ///< ed2, rl, best
  std::vector<Candidate> candidates;       ///< best: every candidate built
  Selection selection;                     ///< best
  int self_intersecting_cells = 0;         ///< of the initial grid
  int boundary_crossings = 0;              ///< of the initial grid
  bool elliptic_rejected = false;      ///< `grid` is the initial one: the elliptic grid folded it, or (best) was worse
  std::string rejected_because;        ///< "folded" or "worse than <initial>" when elliptic_rejected
  std::vector<Candidate> final_check;  ///< best: {the chosen candidate, the elliptic grid} as compared by B.6
};

/// Sea depth (m, positive down) at a longitude and latitude (degrees); NaN where unknown (taken as 0).
using DepthSampler = std::function<double(double lon_deg, double lat_deg)>;

/// w · (1 + a·|∇h|/max|∇h|), h the depth from `depth`, sampled with w on a 257 × 257 lattice over
/// `box` = {x_min, x_max, y_min, y_max} (plane units) padded by 2 %; |∇h| by central differences in
/// plane units. a > 0. A flat sea (max|∇h| = 0) leaves w unchanged.
ControlFunction depth_weighted(const ControlFunction& w, double a, std::array<double, 4> box,
                               const Projection& projection, const DepthSampler& depth);

/// The internal sections of a run: `params.sections` (columns nearest q1·(L−1), inside 1..L−2) or
/// `params.sections_eta` (rows nearest q2·(M−1), inside 1..M−2), strictly increasing (ConfigError
/// otherwise); points projected when lon/lat.
struct RegionalSections {
  std::vector<Section> sections;
  SectionLines lines = SectionLines::kColumns;
};
RegionalSections regional_sections(const RegionalParams& params, int nx_pts, int ny_pts, const Projection& projection);

/// The candidate criteria of `grid` (f1..f4 for w, folded cells, boundary crossings).
Candidate make_candidate(std::string name, const Grid2D& grid, const ControlFunction& w);

/// Builds the grid of `params.method` (not conformal) on boundary `nodes` of `contour`. For best,
/// `conformal_grid` and `conformal_nodes` (may be null) add the conformal candidate. Logs the
/// selection table and the elliptic iterations on `log`. Throws as the methods do.
MethodRun build_method_grid(const RegionalParams& params, const SplineContour& contour, const BoundaryNodes& nodes,
                            const Projection& projection, const ControlFunction& w, const Grid2D* conformal_grid,
                            const BoundaryNodes* conformal_nodes, const Logger& log);

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// The regional izogrid pipeline, stages 0–4 (seed 000 Sec. 1 "modes"; digest izogrid.md §1;
// ARCHITECTURE §5): map -> contour -> uniform boundary nodes -> inverse problem -> Laplace fill.
// With params.method other than conformal, stage 2 puts the boundary nodes by equidistribution,
// stage 3 is skipped and stage 4 runs the seed-004 method (regional_methods.hpp).
// Each stage can be the last one (the seed's `mode`); everything built so far is returned so the
// caller can draw it (io/regional_pictures.hpp) or write it (io/xygrid_netcdf.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/log.hpp"
#include "core/report.hpp"
#include "curvilinear/common/boundary_nodes.hpp"
#include "curvilinear/common/grid2d.hpp"
#include "curvilinear/conformal/inverse_problem.hpp"
#include "curvilinear/conformal/laplace_fill.hpp"
#include "curvilinear/common/projection.hpp"
#include "curvilinear/bvp/regional_bvp.hpp"
#include "curvilinear/elliptic/regional_methods.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "grid_params/regional_params.hpp"

namespace aq::curvilinear {

struct RegionalResult {
  Stage completed = Stage::kMap;  ///< the last stage run
  RegionalParams params;          ///< the parameters used

  // Stage 0: map.
  std::optional<Projection> projection;
  std::vector<double> control_x, control_y;  ///< control points in the plane (plane units)
  std::vector<bool> control_corner;

  // Stage 1: contour.
  std::optional<SplineContour> contour;        ///< the spline the grid is built on
  std::optional<SplineContour> cubic_contour;  ///< spline_type = 4: the cubic, for the picture only
  std::vector<PlanePoint> contour_samples;     ///< closed polyline of `contour`, 32 points/segment
  std::array<double, 4> side_length{};         ///< arc length of S, E, N, W, plane units

  // Stage 2: uniform boundary nodes (the initial guess), for an (2nx0+1) × (2ny+1) supergrid.
  BoundaryNodes uniform_nodes;
  UniformStats uniform_stats;
  int nx_initial = 0;  ///< nx0: the first guess used (params.nx or guessed from the side lengths)

  // Stage 3: inverse problem.
  BoundaryNodes nodes;       ///< final boundary nodes of the (2nx+1) × (2ny+1) supergrid
  InverseResult inverse;     ///< residual history, W/H history, passes, the rectangle
  double aspect_ratio = 0;   ///< W/H of the conformal rectangle
  int nx = 0;                ///< cells along ξ of the final grid (supergrid 2nx+1 points)
  int ny = 0;                ///< cells along η of the final grid (supergrid 2ny+1 points)
  double dxi_over_deta = 0;  ///< ρ = Δξ/Δη of the supergrid's computational steps

  // Stage 4: the filled supergrid (conformal), or the grid of a seed-004 method.
  Grid2D grid;
  LaplaceResult laplace;
  std::optional<MethodRun> method_run;  ///< method != conformal: initial grid, ED2/RL, best's selection

  // method = bvp: stages 3–4 are one bvp stage (regional_bvp.hpp); its history is here.
  std::optional<BvpResult> bvp;

  /// Wall seconds per stage (map, contour, uniform, conformal, grid); 0 for stages not run.
  std::array<double, 5> stage_seconds{};

  /// Positions of `uniform_nodes` / `nodes` in the plane (counter-clockwise from SW).
  [[nodiscard]] std::vector<PlanePoint> node_points(const BoundaryNodes& n) const;
};

/// Runs the stages up to and including `stop_after` (the caller derives it from params.mode with
/// stage_from_mode() or from a command-line override; params.mode itself is not consulted). Logs one "regional <stage>:
/// done ..." line per stage and, when `report` is given, adds the stages and a "regional" section (parameters, nx, ny,
/// W/H, residual history, timings). Throws ConfigError listing every out-of-range parameter (validate_regional_params:
/// the config reader reports the same at load, with positions), InputError for a bad contour (corners,
/// self-intersection, orientation, points at a projection singularity), NumericalError when the inverse problem or the
/// fill does not converge. Preconditions (config/regional.cpp checks them at load; InternalError otherwise): a method
/// other than conformal does not stop after kConformal; `depth` (may be null) supplies the bathymetry of
/// params.weight_depth > 0 for the methods that use the weight.
RegionalResult run_regional(const RegionalParams& params, Stage stop_after, const Logger& log = Logger::null(),
                            Report* report = nullptr, const DepthSampler* depth = nullptr);

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// Parameters of a regional izogrid run (seed 000 Appendix 1; digest izogrid.md §2.2). One plain
// struct with a default for every field; the izogrid-file parser (izogrid_file.hpp) and the TOML
// config fill it. Field names follow the seed's input-file keys where it has them (the izogrid
// key is given in brackets); the rest are aquatoria extensions with the key named likewise.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grid_params/control_function.hpp"
#include "grid_params/grid_kinds.hpp"
#include "grid_params/projection_params.hpp"

namespace aq::curvilinear {

struct RegionalParams {
  static constexpr double kAuto = std::numeric_limits<double>::quiet_NaN();

  // --- run control ---------------------------------------------------------------------------
  /// [mode] stage after which to stop: 0 map, 1 contour, 2 uniform nodes, 3 inverse problem,
  /// 4 grid (with picture), 5 grid (no picture). 0..5.
  int mode = 4;
  /// [npass] the seed's iteration multiplier (empirically 4..10). aquatoria iterates to
  /// `tolerance` instead, so this is accepted, range-checked (≥ 1) and echoed only.
  int npass = 4;

  // --- map (mode 0) --------------------------------------------------------------------------
  /// [proj], [rlat], [rlon], [rota], [lat1], [lat2], [uscale], [radius]: the conformal projection
  /// of the map (projection_params.hpp documents each field and its range).
  ProjectionParams projection;
  /// [west_edge], [east_edge], [south_edge], [north_edge] geographic limits of the pictures
  /// only, degrees (longitudes within ±360, latitudes within ±90); NaN = fit the contour. They
  /// never change the grid.
  double west_edge = kAuto;
  double east_edge = kAuto;
  double south_edge = kAuto;
  double north_edge = kAuto;
  /// [latlongrid] graticule spacing of the pictures, degrees, > 0 (coarsened tenfold until at most 200
  /// lines cross the map each way).
  double latlongrid = 2.0;
  /// [gshhs_data] the seed's coastline source (a GSHHS file or c/l/i/h/f). aquatoria draws the
  /// coastline from the bathymetry; accepted and echoed only.
  std::string gshhs_data = "i";
  /// [lwidth] line-width multiplier of the pictures, > 0.
  double lwidth = 1.0;

  // --- contour (mode 1) ----------------------------------------------------------------------
  /// [spline_type] 3 = cubic, 5 = quintic, 4 = both drawn and the quintic used for the grid.
  int spline_type = 5;
  /// [param] curve parameter: "index" (σ = k, default) or "arclength" (iterated, §4.6).
  Parametrisation param = Parametrisation::kIndex;
  /// [points] what the control points are: false = plane units (the seed's files), true =
  /// longitude/latitude in degrees (projected in stage 0).
  bool points_lonlat = false;
  /// Control points counter-clockwise from the SW corner: x (or longitude), y (or latitude).
  std::vector<double> x;
  std::vector<double> y;
  /// Corner marks (point 0 is the SW corner whether marked or not; exactly 3 more).
  std::vector<bool> corner;

  // --- grid size and boundary nodes (modes 2, 3) ---------------------------------------------
  /// [nx] cells along ξ of the final (ρ-point) grid; the supergrid has 2nx+1 points. Only a
  /// first guess when auto_nx (re-chosen from the rectangle's aspect ratio). 0 = guess from the
  /// contour's side lengths. ≥ 0.
  int nx = 0;
  /// [ny] cells along η of the final grid (kept; pick one divisible by many processor counts);
  /// the supergrid has 2ny+1 points. ≥ 1.
  int ny = 50;
  /// [auto_nx] re-choose nx so the cells are square (the seed always does).
  bool auto_nx = true;

  // --- inverse problem (mode 3) --------------------------------------------------------------
  /// [schedule] IZ89 passes per outer iteration: "exponential" 2^((m+5)/2) (default) or "sqrt"
  /// √(2m+5) — the two readings of the paper's garbled formula (see inverse_problem.hpp).
  InnerSchedule schedule = InnerSchedule::kExponential;
  /// [tolerance] outer convergence, max |t' − t'∞| as a fraction of the side, > 0.
  double tolerance = 1e-12;
  /// [max_outer] outer iterations before NumericalError, ≥ 1.
  int max_outer = 40;
  /// [max_inner] cap on the IZ89 passes of one outer iteration, ≥ 1.
  int max_inner = 64;
  /// [interp_points] Lagrange points in the node update (26): 2 (linear) .. 8; default 4.
  int interp_points = 4;
  /// [inner_rtol] inexact inner solves: IZ89 angle tolerance relative to the last residual,
  /// ≥ 0 (0 = always converge IZ89 fully).
  double inner_rtol = 1e-2;
  /// [anderson] Anderson acceleration depth of the outer loop, 0..8 (0 = the paper's plain loop).
  int anderson = 0;

  // --- bvp method (seed 003; regional_bvp.hpp) ------------------------------------------------
  /// [surface] bvp only: "plane" (the projection plane) or "sphere" (3-D, no map projection; the
  /// written _xygrid.nc holds the sphere grid's nodes projected to the plane).
  RegionalSurface surface = RegionalSurface::kPlane;
  /// [bvp_iterations] bvp: at most this many outer iterations (stops earlier when f_max and f_avg
  /// change by < 1 %), 1..50.
  int bvp_iterations = 10;
  /// [bvp_interpolation] bvp: "linear" (the paper's examples) or "cubic" level-line interpolation.
  LevelInterpolation bvp_interpolation = LevelInterpolation::kLinear;
  /// [bvp_ratio_xi], [bvp_ratio_eta] bvp node clustering through the levels: the last level step
  /// along ξ (west -> east) or η (south -> north) over the first, geometric in between; 1 = uniform.
  double bvp_ratio_xi = 1.0;
  double bvp_ratio_eta = 1.0;
  /// bvp multi-block (TOML only: regional.block2_points, block2_corners, block2_nx): a second
  /// block east of the first, its west side the first block's east side (the same curve), in the
  /// same units as x, y. Empty = one block. The two grids are merged into one supergrid.
  std::vector<double> x2, y2;
  std::vector<bool> corner2;
  /// Cells along ξ of the second block's ρ grid; 0 = from its conformal modulus.
  int nx2 = 0;

  // --- fill (mode 4) -------------------------------------------------------------------------
  /// [solver] Laplace solver: "dst" (direct, default) or "sor" (the paper's 4-colour SOR).
  LaplaceSolver solver = LaplaceSolver::kDst;
  /// [xygrid] output netCDF file name of the planar grid.
  std::string xygrid = "xygrid.nc";

  // --- method; seed 004 methods (regional_methods.hpp) ----------------------------------------
  /// [method] grid generator: conformal (default: inverse problem + Laplace fill, seed 000), bvp
  /// (seed 003: θ, η equations, nodes at level-line intersections), tfi, star, ed2, rl, best (seed 004).
  GridMethod method = GridMethod::kConformal;
  /// [weight] control function w(x, y) ≥ 1 of the boundary nodes, sections, STAR rows and ED2, a
  /// formula in plane coordinates (control_function.hpp), parsed where it is read; "1" = uniform.
  ControlFunction weight;
  /// [weight_depth] a ≥ 0 of w = weight · (1 + a·|∇h|/max|∇h|) from the [input] bathymetry (app
  /// only; 0 = off).
  double weight_depth = 0.0;
  /// [relaxation] ω of the ED2/RL Picard update, (0, 1].
  double relaxation = 0.7;
  /// [elliptic_tolerance] ED2/RL stop: largest node move / diameter, > 0 (and f, f_o settled); ED2/RL
  /// also stop when the averages f_o settle (elliptic_grids.hpp).
  double elliptic_tolerance = 1e-4;
  /// [elliptic_criteria_tolerance] ED2/RL stop: f, f_o "settled" when they change by less than this
  /// between checks 5 iterations apart, (0, 1). Smaller runs longer (1e-5 usually to the cap).
  double elliptic_criteria_tolerance = 1e-3;
  /// [elliptic_iterations] ED2/RL Picard iterations at most, ≥ 1.
  int elliptic_iterations = 400;
  /// [best_final] the elliptic method `best` runs from the chosen initial grid: ed2 or rl.
  GridMethod best_final = GridMethod::kEd2;
  /// Internal sections of TFI (TOML `sections` only): each {q1, x1, y1, x2, y2, ...}: the section
  /// at the grid column nearest q1·(L−1), 0 < q1 < 1, through the optional interior points (plane
  /// units, or lon/lat when points = lonlat).
  std::vector<std::vector<double>> sections;
  /// Internal sections along η (TOML `sections_eta` only): each {q2, x1, y1, ...}: the section at
  /// the grid row nearest q2·(M−1), 0 < q2 < 1, from the west side to the east side. Not together
  /// with `sections`: TFI blends between the sections of one direction.
  std::vector<std::vector<double>> sections_eta;

  // --- execution and provenance --------------------------------------------------------------
  /// [threads] OpenMP threads for IZ89 and the fill; 0 = the OpenMP default. Results do not
  /// depend on it.
  int threads = 0;
  /// Where the parameters came from (file name), used in messages.
  std::string source = "regional";
  /// The input file's text, for provenance in output files (may be empty).
  std::string input_text;
};

/// Checks every field's range and throws one ConfigError listing all problems ("<source>: <key> =
/// <value>: why"). The control points are checked when the contour is built (InputError: corner
/// count, repeated or non-finite points, orientation, self-intersection); here only that x, y and
/// corner have equal lengths and that latitudes are within ±90 when points_lonlat.
void validate_regional_params(const RegionalParams& p);

/// The problems validate_regional_params() reports, as (key, message) pairs (key as in the
/// izogrid file, "points" for the control points), for callers that add file:line.
std::vector<std::pair<std::string, std::string>> regional_params_problems(const RegionalParams& p);

}  // namespace aq::curvilinear

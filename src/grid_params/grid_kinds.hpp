// SPDX-License-Identifier: GPL-3.0-or-later
// The vocabulary of a regional grid run: the kinds a user chooses by name (projection, contour
// parametrisation, inner-pass schedule, level interpolation, Laplace solver, generator method,
// surface, units of the control points, the stage to stop after, the ROMS distances). Each enum has
// ONE name table (core/enum_names.hpp) that the izogrid-file reader, the TOML config, the run
// report and the pictures read. They sit below both `config` (which parses them) and
// `curvilinear` (which acts on them), so the config never links the solvers. Namespace
// aq::curvilinear: they are that stage's types, kept where both can see them.
#pragma once

#include <array>
#include <span>

#include "core/enum_names.hpp"

namespace aq::curvilinear {

/// [proj] The conformal projection of the map (curvilinear/common/projection.hpp). The izogrid
/// file writes the two-letter codes in any case; the long names are accepted too.
enum class ProjectionKind {
  kMercator,       ///< "ME": rotated (oblique) Mercator
  kLambertConic,   ///< "LC": Lambert conformal conic
  kStereographic,  ///< "ST": oblique / polar stereographic
};
inline constexpr std::array<EnumName<ProjectionKind>, 6> kProjectionKindNames{{
    {ProjectionKind::kMercator, "ME", "rotated Mercator"},
    {ProjectionKind::kLambertConic, "LC", "Lambert conformal conic"},
    {ProjectionKind::kStereographic, "ST", "stereographic"},
    {ProjectionKind::kMercator, "mercator", ""},
    {ProjectionKind::kLambertConic, "lambert", ""},
    {ProjectionKind::kStereographic, "stereographic", ""},
}};
constexpr std::span<const EnumName<ProjectionKind>> enum_names(ProjectionKind) { return kProjectionKindNames; }

/// [param] Knot parametrisation of the contour spline (spline_contour.hpp).
enum class Parametrisation {
  kIndex,      ///< σ_k = k: no iteration, well conditioned (default)
  kArcLength,  ///< knot spacing = arc length of each segment, iterated with the cubic spline
};
inline constexpr std::array<EnumName<Parametrisation>, 3> kParametrisationNames{{
    {Parametrisation::kIndex, "index", "sigma = k, no iteration"},
    {Parametrisation::kArcLength, "arclength", "knots spaced by arc length, iterated"},
    {Parametrisation::kArcLength, "arc_length", ""},
}};
constexpr std::span<const EnumName<Parametrisation>> enum_names(Parametrisation) { return kParametrisationNames; }

/// [points] What the control points are.
enum class PointUnits { kPlane, kLonLat };
inline constexpr std::array<EnumName<PointUnits>, 2> kPointUnitsNames{{
    {PointUnits::kPlane, "plane", "plane units of the projection (the seed's files)"},
    {PointUnits::kLonLat, "lonlat", "longitude, latitude in degrees"},
}};
constexpr std::span<const EnumName<PointUnits>> enum_names(PointUnits) { return kPointUnitsNames; }

/// [schedule] IZ89 passes allowed per outer iteration of the inverse problem (inverse_problem.hpp).
enum class InnerSchedule {
  kExponential,  ///< M(m) = ceil(2^((m+5)/2))
  kSqrt,         ///< M(m) = ceil(sqrt(2m+5))
};
inline constexpr std::array<EnumName<InnerSchedule>, 2> kInnerScheduleNames{{
    {InnerSchedule::kExponential, "exponential", "2^((m+5)/2) passes at outer iteration m"},
    {InnerSchedule::kSqrt, "sqrt", "sqrt(2m+5) passes"},
}};
constexpr std::span<const EnumName<InnerSchedule>> enum_names(InnerSchedule) { return kInnerScheduleNames; }

/// [bvp_interpolation] Interpolation of the level lines of the bvp method (level_intersections.hpp).
enum class LevelInterpolation { kLinear, kCubic };
inline constexpr std::array<EnumName<LevelInterpolation>, 2> kLevelInterpolationNames{{
    {LevelInterpolation::kLinear, "linear", "the paper's examples"},
    {LevelInterpolation::kCubic, "cubic", "cubic level-line interpolation"},
}};
constexpr std::span<const EnumName<LevelInterpolation>> enum_names(LevelInterpolation) {
  return kLevelInterpolationNames;
}

/// [solver] Solver of the Laplace fill (laplace_fill.hpp): direct (DST) or SOR.
enum class LaplaceSolver { kDst, kSor };
inline constexpr std::array<EnumName<LaplaceSolver>, 2> kLaplaceSolverNames{{
    {LaplaceSolver::kDst, "dst", "direct, FFTW"},
    {LaplaceSolver::kSor, "sor", "the paper's 4-colour Chebyshev SOR"},
}};
constexpr std::span<const EnumName<LaplaceSolver>> enum_names(LaplaceSolver) { return kLaplaceSolverNames; }

/// [method] How the grid is built from the contour: the conformal izogrid pipeline (seed 000), the
/// orthogonal-family boundary-value problem (seed 003, regional_bvp.hpp) or one of seed 004's
/// generators (regional_methods.hpp).
enum class GridMethod { kConformal, kBvp, kTfi, kStar, kEd2, kRl, kBest };
inline constexpr std::array<EnumName<GridMethod>, 7> kGridMethodNames{{
    {GridMethod::kConformal, "conformal", "izogrid: inverse problem and Laplace fill, seed 000"},
    {GridMethod::kBvp, "bvp", "seed 003: theta/eta equations, level-line intersections"},
    {GridMethod::kTfi, "tfi", "transfinite interpolation"},
    {GridMethod::kStar, "star", "star-shaped domains only"},
    {GridMethod::kEd2, "ed2", "adaptive elliptic ED2"},
    {GridMethod::kRl, "rl", "Ryskin-Leal"},
    {GridMethod::kBest, "best", "the best by the f1-f4 criteria"},
}};
constexpr std::span<const EnumName<GridMethod>> enum_names(GridMethod) { return kGridMethodNames; }
/// True for seed 004's methods (tfi, star, ed2, rl, best): boundary nodes by equidistribution of the
/// control function `weight` (regional_methods.hpp); false for conformal and bvp.
constexpr bool uses_weight(GridMethod m) { return m != GridMethod::kConformal && m != GridMethod::kBvp; }

/// [surface] Where the bvp method solves: in the projection plane or on the sphere (seed 003 Sec. 3.2).
enum class RegionalSurface { kPlane, kSphere };
inline constexpr std::array<EnumName<RegionalSurface>, 2> kRegionalSurfaceNames{{
    {RegionalSurface::kPlane, "plane", "the projection plane"},
    {RegionalSurface::kSphere, "sphere", "on the sphere, no projection"},
}};
constexpr std::span<const EnumName<RegionalSurface>> enum_names(RegionalSurface) { return kRegionalSurfaceNames; }

/// The stages of a regional run, numbered as the seed's modes 0–4 (mode 5 = kGrid without a
/// picture). regional.stop_after and --stop-after take the names or the mode digits.
enum class Stage { kMap = 0, kContour = 1, kUniform = 2, kConformal = 3, kGrid = 4 };
inline constexpr std::array<EnumName<Stage>, 11> kStageNames{{
    {Stage::kMap, "map", "the projection and the control points"},
    {Stage::kContour, "contour", "the spline contour"},
    {Stage::kUniform, "uniform", "uniform boundary nodes"},
    {Stage::kConformal, "conformal", "the inverse problem (conformal method only)"},
    {Stage::kGrid, "grid", "the whole grid and its files"},
    {Stage::kMap, "0", ""},
    {Stage::kContour, "1", ""},
    {Stage::kUniform, "2", ""},
    {Stage::kConformal, "3", ""},
    {Stage::kGrid, "4", ""},
    {Stage::kGrid, "5", ""},
}};
constexpr std::span<const EnumName<Stage>> enum_names(Stage) { return kStageNames; }
/// Stage of a seed mode 0..5 (4 and 5 are kGrid). Precondition: 0 <= mode <= 5 (regional.mode is
/// validated at load); InternalError otherwise.
Stage stage_from_mode(int mode);

/// [roms] distances: how the ROMS metrics measure lengths (cgrid.hpp).
enum class DistanceModel {
  kSphere,  ///< great circles on a sphere of radius CGridOptions::earth_radius_m
  kWgs84,   ///< geodesics on the WGS84 ellipsoid (GeographicLib)
};
inline constexpr std::array<EnumName<DistanceModel>, 2> kDistanceModelNames{{
    {DistanceModel::kSphere, "sphere", "great circles on a sphere of roms.earth_radius_m"},
    {DistanceModel::kWgs84, "wgs84", "geodesics on the WGS84 ellipsoid"},
}};
constexpr std::span<const EnumName<DistanceModel>> enum_names(DistanceModel) { return kDistanceModelNames; }

}  // namespace aq::curvilinear

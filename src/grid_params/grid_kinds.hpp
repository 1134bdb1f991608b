// The vocabulary of a regional grid run: the kinds a user chooses by name (projection, contour
// parametrisation, inner-pass schedule, level interpolation, Laplace solver, generator method,
// surface). They sit below both `config` (which parses them) and `curvilinear` (which acts on
// them), so the config never links the solvers. Namespace aq::curvilinear: they are that stage's
// types, kept where both can see them.
#pragma once

#include <string>
#include <string_view>

namespace aq::curvilinear {

enum class ProjectionKind {
  kMercator,       ///< "ME": rotated (oblique) Mercator
  kLambertConic,   ///< "LC": Lambert conformal conic
  kStereographic,  ///< "ST": oblique / polar stereographic
};
/// Parses "ME", "LC", "ST" (case-insensitive) or "mercator", "lambert", "stereographic".
/// Throws ConfigError naming the value otherwise.
ProjectionKind parse_projection_kind(std::string_view text);
/// The two-letter code ("ME", "LC", "ST").
std::string projection_code(ProjectionKind kind);

/// Knot parametrisation of the contour spline (spline_contour.hpp).
enum class Parametrisation {
  kIndex,      ///< σ_k = k: no iteration, well conditioned (default)
  kArcLength,  ///< knot spacing = arc length of each segment, iterated with the cubic spline
};

/// IZ89 passes allowed per outer iteration of the inverse problem (inverse_problem.hpp).
enum class InnerSchedule {
  kExponential,  ///< M(m) = ceil(2^((m+5)/2))
  kSqrt,         ///< M(m) = ceil(sqrt(2m+5))
};
/// Parses "exponential" or "sqrt"; ConfigError otherwise.
InnerSchedule parse_inner_schedule(std::string_view text);
/// "exponential" or "sqrt".
const char* inner_schedule_name(InnerSchedule schedule);

/// Interpolation of the level lines of the bvp method (level_intersections.hpp).
enum class LevelInterpolation { kLinear, kCubic };

/// Solver of the Laplace fill (laplace_fill.hpp): direct (DST) or SOR.
enum class LaplaceSolver { kDst, kSor };

/// How the grid is built from the contour (key `method`): the conformal izogrid pipeline (seed 000),
/// the orthogonal-family boundary-value problem (seed 003, regional_bvp.hpp) or one of seed 004's
/// generators (regional_methods.hpp).
enum class GridMethod { kConformal, kBvp, kTfi, kStar, kEd2, kRl, kBest };
/// "conformal", "bvp", "tfi", "star", "ed2", "rl", "best".
const char* grid_method_name(GridMethod m);
/// Inverse of grid_method_name(); false for an unknown name.
bool parse_grid_method(std::string_view text, GridMethod& out);
/// True for seed 004's methods (tfi, star, ed2, rl, best): boundary nodes by equidistribution of the
/// control function `weight` (regional_methods.hpp); false for conformal and bvp.
constexpr bool uses_weight(GridMethod m) { return m != GridMethod::kConformal && m != GridMethod::kBvp; }
/// Where the bvp method solves: in the projection plane or directly on the sphere (seed 003 Sec. 3.2).
enum class RegionalSurface { kPlane, kSphere };

}  // namespace aq::curvilinear

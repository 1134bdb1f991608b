// SPDX-License-Identifier: GPL-3.0-or-later
// Validation of RegionalParams (seed 000 Appendix 1 ranges; digest izogrid.md §2.2).
#include "grid_params/regional_params.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/error.hpp"
#include "core/timer.hpp"

namespace aq::curvilinear {

namespace {
// Bytes per supergrid point held by a regional run at its peak (grids, metrics, the quality maps
// and the solvers' work arrays; a generous bound, used only to refuse absurd sizes early).
constexpr double kSupergridBytes = 400.0;
}  // namespace

std::vector<std::pair<std::string, std::string>> regional_params_problems(const RegionalParams& p) {
  std::vector<std::pair<std::string, std::string>> bad;
  auto check = [&](bool ok, const char* key, const std::string& value, const char* what) {
    if (!ok) bad.emplace_back(key, fmt::format("{} = {}: {}", key, value, what));
  };
  auto num = [](double v) { return fmt::format("{}", v); };
  check(p.mode >= 0 && p.mode <= 5, "mode", std::to_string(p.mode), "must be 0..5");
  check(p.npass >= 1, "npass", std::to_string(p.npass), "must be >= 1");
  // The projection (uscale = 1e-300 once failed in the C-grid stage, a Lambert cylinder in the map).
  for (auto& problem : projection_problems(p.projection)) bad.push_back(std::move(problem));
  check(p.latlongrid > 0.0 && std::isfinite(p.latlongrid), "latlongrid", num(p.latlongrid), "must be positive");
  check(p.lwidth > 0.0 && std::isfinite(p.lwidth), "lwidth", num(p.lwidth), "must be positive");
  check(p.spline_type >= 3 && p.spline_type <= 5, "spline_type", std::to_string(p.spline_type),
        "must be 3 (cubic), 4 (both, quintic used) or 5 (quintic)");
  check(p.nx >= 0, "nx", std::to_string(p.nx), "must be >= 0 (0 = guess)");
  check(p.ny >= 1, "ny", std::to_string(p.ny), "must be >= 1");
  {
    // The supergrid is (2nx+1) x (2ny+1) points (nx = ny when guessed), about kSupergridBytes
    // each over the stages; sized in floating point, so no int overflow reaches the stages (ny =
    // 200000 failed after 15 s inside the boundary-node stage).
    // With auto_nx, nx is re-chosen from the aspect ratio: taken as at least ny here.
    const double nx = p.auto_nx ? std::max(p.nx, p.ny) : (p.nx > 0 ? p.nx : p.ny);
    const double sx = 2.0 * std::max(nx, 1.0) + 1.0, sy = 2.0 * std::max(p.ny, 1) + 1.0;
    const double need = sx * sy * kSupergridBytes, limit = 0.8 * static_cast<double>(physical_memory_bytes());
    if (p.ny >= 1 && p.nx >= 0 && need > limit)
      bad.emplace_back(p.nx > p.ny ? "nx" : "ny",
                       fmt::format("nx = {}, ny = {}: a supergrid of about {:.0f} x {:.0f} points needs about {:.1f} "
                                   "GB, more than the {:.1f} GB of 80% of this machine's memory",
                                   p.nx, p.ny, sx, sy, need / 1e9, limit / 1e9));
  }
  check(p.tolerance > 0.0 && p.tolerance < 1.0, "tolerance", num(p.tolerance), "must be within (0, 1)");
  check(p.max_outer >= 1, "max_outer", std::to_string(p.max_outer), "must be >= 1");
  check(p.max_inner >= 1, "max_inner", std::to_string(p.max_inner), "must be >= 1");
  check(p.interp_points >= 2 && p.interp_points <= 8, "interp_points", std::to_string(p.interp_points),
        "must be within 2..8");
  check(p.inner_rtol >= 0.0 && p.inner_rtol <= 1.0, "inner_rtol", num(p.inner_rtol), "must be within [0, 1]");
  check(p.anderson >= 0 && p.anderson <= 8, "anderson", std::to_string(p.anderson), "must be within 0..8");
  check(p.bvp_iterations >= 1 && p.bvp_iterations <= 50, "bvp_iterations", std::to_string(p.bvp_iterations),
        "must be within 1..50");
  check(p.bvp_ratio_xi > 0.0 && p.bvp_ratio_xi <= 100.0, "bvp_ratio_xi", num(p.bvp_ratio_xi),
        "must be within (0, 100] (1 = uniform)");
  check(p.bvp_ratio_eta > 0.0 && p.bvp_ratio_eta <= 100.0, "bvp_ratio_eta", num(p.bvp_ratio_eta),
        "must be within (0, 100] (1 = uniform)");
  check(p.method == GridMethod::kBvp || p.surface == RegionalSurface::kPlane, "surface", "sphere",
        "only the bvp method solves on the sphere (set method = bvp)");
  check(p.nx2 >= 0, "block2_nx", std::to_string(p.nx2), "must be >= 0 (0 = from the conformal modulus)");
  check(p.x2.empty() || p.method == GridMethod::kBvp, "block2_points", std::to_string(p.x2.size()) + " points",
        "a second block needs method = bvp");
  if (p.x2.size() != p.y2.size() || p.corner2.size() != p.x2.size())
    bad.emplace_back("block2_points", fmt::format("block2_points: {} x, {} y and {} corner marks differ in number",
                                                  p.x2.size(), p.y2.size(), p.corner2.size()));
  check(p.threads >= 0, "threads", std::to_string(p.threads), "must be >= 0 (0 = default)");
  check(!p.xygrid.empty(), "xygrid", "''", "must name a file");
  check(p.weight_depth >= 0.0 && std::isfinite(p.weight_depth), "weight_depth", num(p.weight_depth),
        "must be >= 0 (0 = no bathymetry weight)");
  check(p.relaxation > 0.0 && p.relaxation <= 1.0, "relaxation", num(p.relaxation), "must be within (0, 1]");
  check(p.elliptic_tolerance > 0.0 && p.elliptic_tolerance < 1.0, "elliptic_tolerance", num(p.elliptic_tolerance),
        "must be within (0, 1)");
  check(p.elliptic_criteria_tolerance > 0.0 && p.elliptic_criteria_tolerance < 1.0, "elliptic_criteria_tolerance",
        num(p.elliptic_criteria_tolerance), "must be within (0, 1)");
  check(p.elliptic_iterations >= 1, "elliptic_iterations", std::to_string(p.elliptic_iterations), "must be >= 1");
  check(p.best_final == GridMethod::kEd2 || p.best_final == GridMethod::kRl, "best_final",
        std::string(name_of(p.best_final)), "must be ed2 or rl");
  for (const auto& [key, q, list] :
       {std::tuple{"sections", "q1", &p.sections}, std::tuple{"sections_eta", "q2", &p.sections_eta}}) {
    for (std::size_t k = 0; k < list->size(); ++k) {
      const auto& sec = (*list)[k];
      if (sec.empty() || !(sec[0] > 0.0 && sec[0] < 1.0) || sec.size() % 2 != 1)
        bad.emplace_back(key, fmt::format("{}[{}]: expected [{}, x1, y1, x2, y2, ...] with 0 < {} < 1 and pairs of "
                                          "coordinates",
                                          key, k + 1, q, q));
    }
  }
  if (!p.sections.empty() && !p.sections_eta.empty())
    bad.emplace_back("sections_eta",
                     "cannot be combined with sections: TFI blends between the sections of one "
                     "direction (give q1 sections or q2 sections)");
  // The picture's window: longitudes within ±360°, latitudes within ±90° (-1e300 once reached the
  // coastline stage as an empty window naming no key).
  for (const auto& [key, v] : {std::pair{"west_edge", p.west_edge}, std::pair{"east_edge", p.east_edge}})
    check(std::isnan(v) || (v >= -360.0 && v <= 360.0), key, num(v), "must be a longitude within [-360, 360]");
  for (const auto& [key, v] : {std::pair{"south_edge", p.south_edge}, std::pair{"north_edge", p.north_edge}})
    check(std::isnan(v) || (v >= -90.0 && v <= 90.0), key, num(v), "must be a latitude within [-90, 90]");
  if (std::isfinite(p.south_edge) && std::isfinite(p.north_edge))
    check(p.south_edge < p.north_edge, "south_edge", num(p.south_edge), "must be below north_edge");
  // Control points.
  if (p.x.size() != p.y.size() || p.corner.size() != p.x.size()) {
    bad.emplace_back("points", fmt::format("control points: {} x, {} y and {} corner marks differ in number",
                                           p.x.size(), p.y.size(), p.corner.size()));
  } else {
    if (p.points_lonlat)
      for (std::size_t k = 0; k < p.y.size(); ++k)
        if (std::fabs(p.y[k]) > 90.0)
          bad.emplace_back("points", fmt::format("control point {}: latitude {} outside [-90, 90]", k + 1, p.y[k]));
  }
  return bad;
}

void validate_regional_params(const RegionalParams& p) {
  const auto bad = regional_params_problems(p);
  if (bad.empty()) return;
  std::string msg = fmt::format("{}: invalid regional parameters:", p.source);
  for (const auto& b : bad) msg += "\n  " + b.second;
  throw ConfigError(msg);
}

}  // namespace aq::curvilinear

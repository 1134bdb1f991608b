// SPDX-License-Identifier: GPL-3.0-or-later
// Validation of the projection fields (see projection_params.hpp).
#include "grid_params/projection_params.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace aq::curvilinear {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// tan(pi/4 + phi/2), the Mercator/LC isometric-latitude kernel.
double t_iso(double phi) { return std::tan(0.25 * std::numbers::pi + 0.5 * phi); }

}  // namespace

std::vector<std::pair<std::string, std::string>> projection_problems(const ProjectionParams& p) {
  std::vector<std::pair<std::string, std::string>> bad;
  const auto check = [&](bool ok, const char* key, double value, const std::string& what) {
    if (!ok) bad.emplace_back(key, fmt::format("{} = {}: {}", key, value, what));
  };
  check(std::isfinite(p.rlat_deg) && std::fabs(p.rlat_deg) <= 90.0, "rlat", p.rlat_deg, "must be within [-90, 90]");
  check(std::isfinite(p.rlon_deg), "rlon", p.rlon_deg, "must be a finite longitude");
  check(std::isfinite(p.rota_deg), "rota", p.rota_deg, "must be a finite angle");
  check(p.uscale >= 1e-9 && p.uscale <= 1e3, "uscale", p.uscale,
        "must be within [1e-9, 1e3] (plane units = unit-sphere radians / uscale; the seed's 0.001)");
  check(p.radius_m > 0.0 && std::isfinite(p.radius_m), "radius", p.radius_m, "must be positive (metres)");
  if (!bad.empty() && bad.front().first == "rlat") return bad;  // the pole checks need a latitude
  const bool at_pole = std::fabs(p.rlat_deg) > 90.0 - 1e-9;
  if (p.kind == ProjectionKind::kMercator)
    check(!at_pole, "rlat", p.rlat_deg, "a Mercator centre cannot be a pole: it has no east direction (use proj = ST)");
  if (p.kind != ProjectionKind::kLambertConic) return bad;
  check(!at_pole, "rlat", p.rlat_deg, "a Lambert conic origin at a pole is singular (use proj = ST)");
  const double lat1 = std::isnan(p.lat1_deg) ? p.rlat_deg : p.lat1_deg;
  const double lat2 = std::isnan(p.lat2_deg) ? lat1 : p.lat2_deg;
  const auto parallel_ok = [](double v) { return std::isfinite(v) && std::fabs(v) < 90.0 - 1e-9; };
  check(parallel_ok(lat1), "lat1", lat1, "an LC standard parallel must be inside (-90, 90)");
  check(parallel_ok(lat2), "lat2", lat2, "an LC standard parallel must be inside (-90, 90)");
  if (!parallel_ok(lat1) || !parallel_ok(lat2) || at_pole) return bad;
  const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad;
  const double n = std::fabs(p1 - p2) < 1e-12 ? std::sin(p1)
                                              : std::log(std::cos(p1) / std::cos(p2)) / std::log(t_iso(p2) / t_iso(p1));
  if (!(std::fabs(n) > 1e-6))
    bad.emplace_back("lat1", fmt::format("lat1 = {}, lat2 = {}: the LC standard parallels give a cylinder (cone "
                                         "constant {:.3g}); use proj = ME",
                                         lat1, lat2, n));
  return bad;
}

}  // namespace aq::curvilinear

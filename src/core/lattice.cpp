// SPDX-License-Identifier: GPL-3.0-or-later
// Lattice validation.
#include "core/lattice.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/types.hpp"

namespace aq {

double mercator_y_deg(double lat_deg) {
  const double p = lat_deg * kDegToRad;
  return std::asinh(std::tan(p)) * kRadToDeg;
}

double mercator_lat_deg(double y_deg) { return std::atan(std::sinh(y_deg * kDegToRad)) * kRadToDeg; }

double Lattice::size_scale(double y) const {
  const double c = std::cos(lat_of_row(y) * kDegToRad);
  return mercator() ? c : std::sqrt(c);
}

Lattice Lattice::make_mercator(double step0_deg, int levels, double lon0_deg, double lat_max_deg) {
  if (!(lat_max_deg >= 1.0 && lat_max_deg <= 89.5))
    throw InternalError(fmt::format(
        "Lattice::make_mercator: rows to {}° (1..89.5: the Mercator lattice cannot reach the pole)", lat_max_deg));
  Lattice l = make(step0_deg, levels, lon0_deg);
  // Whole level-0 squares per hemisphere; 1e-9 keeps a φ_max whose ordinate is a whole number of
  // squares (85.0511° for Δ0 = 4°) from taking one more.
  const auto m0 = static_cast<std::int64_t>(std::ceil(mercator_y_deg(lat_max_deg) / l.step0_deg - 1e-9));
  l.kind = LatticeKind::kMercator;
  l.y0_deg = -static_cast<double>(m0) * l.step0_deg;
  l.ny = (2 * m0) << levels;
  l.ny_global = l.ny;
  return l;
}

std::string Lattice::step_problem(double step0_deg) {
  const double arcsec = step0_deg * 3600.0;
  const double rounded = std::round(arcsec);
  // "Within rounding": a decimal of 16 or 17 significant digits is within 1e-12 relative of the
  // arc-second value it stands for; 1e-6" is far above that and far below any other valid step.
  if (!(step0_deg > 0.0) || !std::isfinite(step0_deg) || std::abs(arcsec - rounded) > 1e-6 || rounded < 1.0) {
    return fmt::format(
        "Δ0 = {:.9g}\" is not a whole number of arc-seconds (to within 1e-6\"); Δ0 must divide 180° in whole "
        "arc-seconds, e.g. 4, 2, 1, 0.5, 16/60 = {}",
        arcsec, 960.0 / 3600.0);
  }
  if (std::fmod(648000.0, rounded) != 0.0) {
    return fmt::format("Δ0 = {}\" does not divide 180° = 648000\" (need 648000 % Δ0\" == 0), e.g. 4, 2, 1, 0.5, 16/60",
                       rounded);
  }
  return {};
}

Lattice Lattice::make(double step0_deg, int levels, double lon0_deg) {
  // The configuration's values are validated at load (quadtree.step_deg by step_problem()).
  const std::string problem = step_problem(step0_deg);
  if (!problem.empty()) throw InternalError(fmt::format("Lattice::make: Δ0 = {}°: {}", step0_deg, problem));
  const double rounded = std::round(step0_deg * 3600.0);
  if (levels < 0 || levels > 20) throw InternalError(fmt::format("Lattice::make: L = {} is outside 0..20", levels));
  if (!std::isfinite(lon0_deg)) throw InternalError(fmt::format("Lattice::make: λ0 = {}° is not finite", lon0_deg));
  Lattice l;
  l.lon0_deg = lon0_deg;
  // The lattice is the whole arc-second value, not the typed decimal: a step within rounding of
  // it (16' typed as 0.2666666666666667 rather than 0.26666666666666666) would otherwise put the
  // last lattice row at φ = -90 + ny·Δ_L = 90.00000000000003°, beyond the pole (the authalic
  // latitude and the cell areas there are NaN). rounded / 3600 gives -90 + ny·Δ_L = 90 exactly
  // for every valid Δ0 and L (the assertion below keeps it so).
  l.step0_deg = rounded / 3600.0;
  l.levels = levels;
  l.n0 = static_cast<std::int64_t>(648000.0 / rounded);
  l.ny = l.n0 << levels;
  l.nx = 2 * l.ny;
  l.nx_global = l.nx;
  l.ny_global = l.ny;
  if (l.lat_of(0) != -90.0 || l.lat_of(l.ny) != 90.0)
    throw InternalError(fmt::format("lattice Δ0 = {}\", L = {}: the rows end at φ = {:.17g}, not at ±90°", rounded,
                                    levels, l.lat_of(l.ny)));
  return l;
}

Lattice Lattice::window(const Lattice& g, std::int64_t i_first, std::int64_t nx, std::int64_t j_first,
                        std::int64_t ny) {
  const std::int64_t sq = g.pixels_per_square(0);
  if (g.windowed() || i_first % sq != 0 || nx % sq != 0 || j_first % sq != 0 || ny % sq != 0 || nx <= 0 || ny <= 0)
    throw InternalError(fmt::format("lattice window [{}, +{}) x [{}, +{}) is not made of whole level-0 squares of "
                                    "the global lattice ({} pixels)",
                                    i_first, nx, j_first, ny, sq));
  Lattice w = g;
  if (nx < g.nx_global) {
    // Columns start in [0, nx_global): the window begins at or east of λ0, running past the seam if it must.
    w.i_origin = ((i_first % g.nx_global) + g.nx_global) % g.nx_global;
    w.nx = nx;
  }
  const std::int64_t j_lo = std::max<std::int64_t>(0, j_first);
  const std::int64_t j_hi = std::min(g.ny_global, j_first + ny);
  if (j_hi <= j_lo) throw InternalError("lattice window: no row inside the lattice");
  w.j_origin = j_lo;
  w.ny = j_hi - j_lo;
  return w;
}

double Lattice::col_of_lon(double lon_deg) const {
  double x = (wrap_lon_deg(lon_deg, lon0_deg) - lon0_deg) / pixel_deg();
  if (periodic()) {
    if (x >= static_cast<double>(nx)) x -= static_cast<double>(nx);
    return x < 0.0 ? 0.0 : x;
  }
  // A window: the copy of λ (mod 360) nearest the window's middle.
  x -= static_cast<double>(i_origin);
  const auto g = static_cast<double>(nx_global);
  const double mid = 0.5 * static_cast<double>(nx);
  while (x - mid > 0.5 * g) x -= g;
  while (mid - x > 0.5 * g) x += g;
  return x;
}

}  // namespace aq

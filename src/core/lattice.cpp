// Lattice validation.
#include "core/lattice.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"

namespace aq {

Lattice Lattice::make(double step0_deg, int levels, double lon0_deg) {
  const double arcsec = step0_deg * 3600.0;
  const double rounded = std::round(arcsec);
  if (!(step0_deg > 0.0) || std::abs(arcsec - rounded) > 1e-6 || rounded < 1.0 || std::fmod(648000.0, rounded) != 0.0) {
    throw ConfigError(
        fmt::format("quadtree.step_deg = {}: Δ0 must divide 180° exactly (in whole arc-seconds, 648000 % Δ0\" == 0), "
                    "e.g. 4, 2, 1, 0.5, 16/60",
                    step0_deg));
  }
  if (levels < 0 || levels > 20) {
    throw ConfigError(fmt::format("quadtree.levels = {}: must be between 0 and 20", levels));
  }
  if (!std::isfinite(lon0_deg)) throw ConfigError("quadtree.lon0_deg: must be a finite number");
  Lattice l;
  l.lon0_deg = lon0_deg;
  l.step0_deg = step0_deg;
  l.levels = levels;
  l.n0 = static_cast<std::int64_t>(648000.0 / rounded);
  l.ny = l.n0 << levels;
  l.nx = 2 * l.ny;
  return l;
}

}  // namespace aq

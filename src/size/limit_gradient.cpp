// SPDX-License-Identifier: GPL-3.0-or-later
// Nearest-source propagation for the gradient limit and distances (see limit_gradient.hpp).
#include "size/limit_gradient.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace aq::size {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Propagation {
  const FieldGrid& grid;
  const std::vector<double>& base;  // the sources' own values
  double g;
  std::vector<double>& val;
  std::vector<std::int32_t>& src;
  std::int64_t nx, ny;

  // The value source s gives cell (i, j).
  [[nodiscard]] double value_from(std::int32_t s, std::int64_t i, std::int64_t j) const {
    const std::int64_t si = s % nx, sj = s / nx;
    double ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0;
    grid.unit(si, sj, ax, ay, az);
    grid.unit(i, j, bx, by, bz);
    const double dx = ax - bx, dy = ay - by, dz = az - bz;
    return base[static_cast<std::size_t>(s)] + g * kEarthRadiusKm * chord_angle(std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  // Offers cell (i, j) the source of cell m; true when it took it.
  bool relax(std::int64_t i, std::int64_t j, std::int64_t m) {
    const std::int32_t s = src[static_cast<std::size_t>(m)];
    const std::int64_t k = j * nx + i;
    if (s < 0 || s == src[static_cast<std::size_t>(k)]) return false;
    const double v = value_from(s, i, j);
    if (!(v < val[static_cast<std::size_t>(k)])) return false;
    val[static_cast<std::size_t>(k)] = v;
    src[static_cast<std::size_t>(k)] = s;
    return true;
  }
  // Row j from row jn (the row already swept), then round the row both ways. Returns changes.
  std::int64_t row(std::int64_t j, std::int64_t jn) {
    std::int64_t changed = 0;
    if (jn >= 0 && jn < ny) {
#pragma omp parallel for reduction(+ : changed) schedule(static) if (nx >= 4096)
      for (std::int64_t i = 0; i < nx; ++i) {
        const std::int64_t base_n = jn * nx;
        changed += relax(i, j, base_n + i) ? 1 : 0;
        changed += relax(i, j, base_n + (i == 0 ? nx - 1 : i - 1)) ? 1 : 0;
        changed += relax(i, j, base_n + (i == nx - 1 ? 0 : i + 1)) ? 1 : 0;
      }
    }
    const Lattice& lat = grid.lattice();
    if (!lat.mercator() && ((j == 0 && lat.pole_row(0)) || (j == ny - 1 && lat.pole_row(lat.ny))) && nx % 2 == 0 &&
        lat.periodic()) {  // across the pole (not on a window lattice away from the poles)
      for (std::int64_t i = 0; i < nx; ++i) changed += relax(i, j, j * nx + (i + nx / 2) % nx) ? 1 : 0;
    }
    // Left to right, then on round the seam while values still improve; the same leftwards.
    for (std::int64_t t = 1; t < 2 * nx; ++t) {
      const std::int64_t i = t % nx, from = (t - 1) % nx;
      const bool c = relax(i, j, j * nx + from);
      changed += c ? 1 : 0;
      if (t >= nx && !c) break;
    }
    for (std::int64_t t = 1; t < 2 * nx; ++t) {
      const std::int64_t i = nx - 1 - t % nx, from = nx - 1 - (t - 1) % nx;
      const bool c = relax(i, j, j * nx + from);
      changed += c ? 1 : 0;
      if (t >= nx && !c) break;
    }
    return changed;
  }
};

int propagate(const FieldGrid& grid, const std::vector<double>& base, double g, std::vector<double>& val,
              std::vector<std::int32_t>& src) {
  const std::int64_t nx = grid.nx(), ny = grid.ny();
  if (grid.cells() > std::numeric_limits<std::int32_t>::max())
    throw InternalError(fmt::format("size: a grid of {} cells is too large for the propagation", grid.cells()));
  src.assign(static_cast<std::size_t>(grid.cells()), -1);
  for (std::size_t k = 0; k < src.size(); ++k)
    if (val[k] < kInf) src[k] = static_cast<std::int32_t>(k);
  Propagation p{grid, base, g, val, src, nx, ny};
  int sweeps = 0;
  for (; sweeps < 8;) {
    std::int64_t changed = 0;
    for (std::int64_t j = 0; j < ny; ++j) changed += p.row(j, j - 1);
    for (std::int64_t j = ny - 1; j >= 0; --j) changed += p.row(j, j + 1);
    sweeps += 2;
    if (changed == 0) break;
  }
  return sweeps;
}

}  // namespace

int limit_gradient(const FieldGrid& grid, std::vector<double>& h, double g, std::vector<std::int32_t>* source) {
  if (static_cast<std::int64_t>(h.size()) != grid.cells())
    throw InternalError(fmt::format("size: {} values for a grid of {} cells", h.size(), grid.cells()));
  if (!(g >= 0.0) || !std::isfinite(g)) throw InternalError(fmt::format("size: gradient limit {} is not >= 0", g));
  const std::vector<double> base = h;
  std::vector<std::int32_t> src;
  const int sweeps = propagate(grid, base, g, h, src);
  if (source != nullptr) *source = std::move(src);
  return sweeps;
}

std::vector<double> distance_to(const FieldGrid& grid, const std::vector<std::uint8_t>& is_source,
                                std::vector<std::int32_t>* source) {
  std::vector<double> d(static_cast<std::size_t>(grid.cells()), kInf);
  for (std::size_t k = 0; k < d.size(); ++k)
    if (is_source[k] != 0) d[k] = 0.0;
  const std::vector<double> base = d;
  std::vector<std::int32_t> src;
  propagate(grid, base, 1.0, d, src);
  if (source != nullptr) *source = std::move(src);
  return d;
}

}  // namespace aq::size

// SPDX-License-Identifier: GPL-3.0-or-later
// The size field's grid (see field_grid.hpp).
#include "size/field_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>

#include "core/error.hpp"
#include "core/types.hpp"

namespace aq::size {

FieldGrid::FieldGrid(const Lattice& lat, int level) : lat_(lat), level_(level) {
  if (level < 0 || level > lat.levels)
    throw InternalError(fmt::format("size: grid level {} outside 0..{}", level, lat.levels));
  const std::int64_t s = lat.pixels_per_square(level);
  nx_ = lat.nx / s;
  ny_ = lat.ny / s;
  const double step_rad = lat.step0_deg / static_cast<double>(std::int64_t{1} << level) * kDegToRad;
  lat_deg_.resize(static_cast<std::size_t>(ny_));
  sin_lat_.resize(lat_deg_.size());
  cos_lat_.resize(lat_deg_.size());
  dx_km_.resize(lat_deg_.size());
  dy_km_.resize(lat_deg_.size());
  for (std::int64_t j = 0; j < ny_; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const double centre = (static_cast<double>(j) + 0.5) * static_cast<double>(s);
    lat_deg_[ju] = lat.lat_of_row(centre);
    sin_lat_[ju] = std::sin(lat_deg_[ju] * kDegToRad);
    cos_lat_[ju] = std::cos(lat_deg_[ju] * kDegToRad);
    dx_km_[ju] = kEarthRadiusKm * step_rad * cos_lat_[ju];
    // Mercator rows are conformal squares; lon-lat rows are Δ_c of latitude apart.
    dy_km_[ju] = lat.mercator() ? dx_km_[ju] : kEarthRadiusKm * step_rad;
  }
  sin_lon_.resize(static_cast<std::size_t>(nx_));
  cos_lon_.resize(sin_lon_.size());
  for (std::int64_t i = 0; i < nx_; ++i) {
    const double lon = lon_deg(i) * kDegToRad;
    sin_lon_[static_cast<std::size_t>(i)] = std::sin(lon);
    cos_lon_[static_cast<std::size_t>(i)] = std::cos(lon);
  }
}

double FieldGrid::lon_deg(std::int64_t i) const {
  return lat_.lon0_deg + (static_cast<double>(i + lat_.square_origin_i(level_)) + 0.5) * lat_.step0_deg /
                             static_cast<double>(std::int64_t{1} << level_);
}

double FieldGrid::distance_km(std::int64_t k, std::int64_t m) const {
  double ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0;
  unit(k % nx_, k / nx_, ax, ay, az);
  unit(m % nx_, m / nx_, bx, by, bz);
  const double dx = ax - bx, dy = ay - by, dz = az - bz;
  return kEarthRadiusKm * chord_angle(std::sqrt(dx * dx + dy * dy + dz * dz));
}

std::vector<std::int32_t> FieldGrid::filled_counts(const Bitmap& filled) const {
  if (filled.nx() != lat_.nx || filled.ny() != lat_.ny)
    throw InternalError(fmt::format("size: filled set is {}x{} pixels but the lattice is {}x{}", filled.nx(),
                                    filled.ny(), lat_.nx, lat_.ny));
  const std::int64_t s = pixels_per_cell(), nx = nx_, ny = ny_;
  std::vector<std::int32_t> count(static_cast<std::size_t>(cells()), 0);
#pragma omp parallel for default(none) shared(filled, count, s, nx, ny) schedule(static)
  for (std::int64_t j = 0; j < ny; ++j) {
    std::int32_t* out = count.data() + j * nx;
    for (std::int64_t pj = j * s; pj < (j + 1) * s; ++pj) {
      const std::uint64_t* row = filled.row(pj);
      if (s >= 64) {
        const std::int64_t words = s / 64;
        for (std::int64_t i = 0; i < nx; ++i) {
          std::int32_t n = 0;
          for (std::int64_t w = i * words; w < (i + 1) * words; ++w) n += std::popcount(row[w]);
          out[i] += n;
        }
      } else {
        const std::uint64_t mask = (std::uint64_t{1} << s) - 1;
        for (std::int64_t i = 0; i < nx; ++i) {
          const std::int64_t p = i * s;
          out[i] += std::popcount((row[p >> 6] >> (p & 63)) & mask);
        }
      }
    }
  }
  return count;
}

int choose_grid_level(const Lattice& lat, int requested, std::int64_t max_cells) {
  if (requested >= 0) return std::min(requested, lat.levels);
  int level = lat.levels;
  while (level > 0 && (lat.nx >> (lat.levels - level)) * (lat.ny >> (lat.levels - level)) > max_cells) --level;
  return level;
}

}  // namespace aq::size

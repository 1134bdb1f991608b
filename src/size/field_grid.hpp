// SPDX-License-Identifier: GPL-3.0-or-later
// The grid the target size field lives on (ARCHITECTURE §4.10): the level-c squares of the
// pixel lattice (core/lattice.hpp), in the lattice's own frame (rotated, lon-lat or Mercator
// rows). Cell (i, j) is the level-c square (a = i, b = j); columns are periodic (i = nx is
// i = 0). Its centre is at λ′ = λ0 + (i + ½)·Δ_c and at the latitude of the fractional pixel row
// (j + ½)·2^(L−c); distances between cells are great-circle distances in that frame, which are
// the geographic ones because a pole rotation is an isometry of the sphere.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"

namespace aq::size {

/// Mean Earth radius (km), the same sphere as quadtree::square_size_km.
inline constexpr double kEarthRadiusKm = 6371.0088;

class FieldGrid {
 public:
  /// The level-`level` grid of `lat` (0 <= level <= L; throws InternalError otherwise).
  FieldGrid(const Lattice& lat, int level);

  [[nodiscard]] const Lattice& lattice() const { return lat_; }
  [[nodiscard]] int level() const { return level_; }
  [[nodiscard]] std::int64_t nx() const { return nx_; }
  [[nodiscard]] std::int64_t ny() const { return ny_; }
  [[nodiscard]] std::int64_t cells() const { return nx_ * ny_; }
  [[nodiscard]] std::int64_t index(std::int64_t i, std::int64_t j) const { return j * nx_ + i; }
  /// Pixels per cell side: 2^(L − c).
  [[nodiscard]] std::int64_t pixels_per_cell() const { return lat_.pixels_per_square(level_); }

  /// Centre of cell (i, j) in the lattice frame (degrees).
  [[nodiscard]] double lon_deg(std::int64_t i) const;
  [[nodiscard]] double lat_deg(std::int64_t j) const { return lat_deg_[static_cast<std::size_t>(j)]; }
  /// Cell sides on the sphere (km): along the row (λ) and along the column.
  [[nodiscard]] double dx_km(std::int64_t j) const { return dx_km_[static_cast<std::size_t>(j)]; }
  [[nodiscard]] double dy_km(std::int64_t j) const { return dy_km_[static_cast<std::size_t>(j)]; }
  /// Great-circle distance (km) between the centres of cells k and m (flat indices).
  [[nodiscard]] double distance_km(std::int64_t k, std::int64_t m) const;
  /// Unit vector of the centre of cell (i, j) in the lattice frame.
  void unit(std::int64_t i, std::int64_t j, double& x, double& y, double& z) const {
    const auto iu = static_cast<std::size_t>(i), ju = static_cast<std::size_t>(j);
    x = cos_lat_[ju] * cos_lon_[iu];
    y = cos_lat_[ju] * sin_lon_[iu];
    z = sin_lat_[ju];
  }

  /// Per cell, how many of its pixels are in `filled` (lat.nx × lat.ny). Parallel over cell rows.
  [[nodiscard]] std::vector<std::int32_t> filled_counts(const Bitmap& filled) const;

 private:
  Lattice lat_;
  int level_ = 0;
  std::int64_t nx_ = 0, ny_ = 0;
  std::vector<double> lat_deg_, sin_lat_, cos_lat_, dx_km_, dy_km_;
  std::vector<double> sin_lon_, cos_lon_;
};

/// The level the field is computed on: `requested` when >= 0 (at most L), else the finest level
/// whose grid has at most `max_cells` cells (at least level 0).
[[nodiscard]] int choose_grid_level(const Lattice& lat, int requested, std::int64_t max_cells = std::int64_t{1} << 20);

/// Angle (radians) subtended by a chord of length c (0 <= c <= 2) of the unit sphere:
/// 2·asin(c/2), by its series below c = 0.25 (relative error < 1e-9) and asin above.
[[nodiscard]] inline double chord_angle(double c) {
  if (c < 0.25) {
    const double c2 = c * c;
    return c * (1.0 + c2 * (1.0 / 24.0 + c2 * (3.0 / 640.0 + c2 * (5.0 / 7168.0 + c2 * (35.0 / 294912.0)))));
  }
  return 2.0 * std::asin(std::min(1.0, 0.5 * c));
}

}  // namespace aq::size

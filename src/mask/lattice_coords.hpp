// SPDX-License-Identifier: GPL-3.0-or-later
// Named conversions between the index spaces of the mask stage (ARCHITECTURE §3, seed 002 §2):
// pixels (i, j), lattice vertices (I, J), K-windows (lower-left pixel), lattice (rotated) degrees
// and geographic degrees. Every place that converts goes through these functions.
//
//   φ = -90 + (j+1)Δ  +-------+-------+
//                     | (i,j) |(i+1,j)|      pixel (i, j) has lower-left vertex (I, J) = (i, j)
//   φ = -90 +  j   Δ  o-------+-------+      and centre (λ0 + (i+½)Δ, -90 + (j+½)Δ)
//                   λ0+iΔ   λ0+(i+1)Δ        i is periodic mod nx, j in [0, ny), J in [0, ny]
//
// A K-window "at (i, j)" is the K×K block of pixels [i, i+K) × [j, j+K) (i wraps over the seam).
// With a PoleRotation the λ, φ above are rotated coordinates; `to_geographic` maps them back.
// On the Mercator lattice the row coordinate maps to φ through Lattice::lat_of_row (the Mercator
// ordinate is linear in j, φ is not); every function here goes through it.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "core/types.hpp"

namespace aq::mask {

/// A pixel (or window lower-left pixel, or lattice vertex) by its integer lattice indices.
struct PixelIJ {
  std::int64_t i = 0;  ///< column, 0 <= i < nx
  std::int64_t j = 0;  ///< row, 0 <= j < ny (vertices: 0 <= J <= ny)
  friend bool operator==(const PixelIJ&, const PixelIJ&) = default;
};

/// A point in geographic or lattice (rotated) degrees.
struct LonLat {
  double lon_deg = 0.0;
  double lat_deg = 0.0;
};

/// Row-major pixel index j·nx + i.
[[nodiscard]] inline PixelIndex pixel_index(PixelIJ p, std::int64_t nx) { return p.j * nx + p.i; }

/// Lattice (rotated) coordinates of vertex (I, J); I may be any integer (periodic).
[[nodiscard]] inline LonLat vertex_lattice_deg(const Lattice& lat, std::int64_t I, std::int64_t J) {
  return {lat.lon_of(I), lat.lat_of(J)};
}

/// Lattice (rotated) coordinates of a point given in fractional pixel units (x along λ from the
/// seam, y along the rows from row 0).
[[nodiscard]] inline LonLat lattice_xy_to_deg(const Lattice& lat, double x, double y) {
  return {lat.lon_at(x), lat.lat_of_row(y)};
}

/// Fractional pixel coordinates of a lattice-degree point: x in [0, nx), y in [0, ny] (beyond
/// that range on the Mercator lattice for |φ| above its rows, and on a window lattice for points
/// outside the window: see on_lattice).
inline void deg_to_lattice_xy(const Lattice& lat, LonLat p, double& x, double& y) {
  x = lat.col_of_lon(p.lon_deg);
  y = lat.row_of_lat(p.lat_deg);
}

/// Whether the fractional row y (deg_to_lattice_xy) lies on the lattice's rows: always on the
/// global lon-lat lattice, whose rows reach the poles; on the Mercator lattice and on a window
/// 0 <= y <= ny (the caps beyond the Mercator rows are dry by construction, so nothing there is
/// in a pixel set of the run).
[[nodiscard]] inline bool on_lattice_rows(const Lattice& lat, double y) {
  return (!lat.mercator() && lat.ny == lat.ny_global) || (y >= 0.0 && y <= static_cast<double>(lat.ny));
}

/// Whether the point (x, y) of deg_to_lattice_xy lies on the lattice: its row (on_lattice_rows)
/// and, on a window that does not span all longitudes, 0 <= x <= nx.
[[nodiscard]] inline bool on_lattice(const Lattice& lat, double x, double y) {
  return on_lattice_rows(lat, y) && (lat.periodic() || (x >= 0.0 && x <= static_cast<double>(lat.nx)));
}

/// Lattice (rotated) coordinates of the centre of pixel (i, j).
[[nodiscard]] inline LonLat pixel_center_lattice_deg(const Lattice& lat, PixelIJ p) {
  return lattice_xy_to_deg(lat, static_cast<double>(p.i) + 0.5, static_cast<double>(p.j) + 0.5);
}

/// Lattice (rotated) coordinates of the centre of the K-window at (i, j).
[[nodiscard]] inline LonLat window_center_lattice_deg(const Lattice& lat, PixelIJ w, int k) {
  const double h = 0.5 * static_cast<double>(k);
  return lattice_xy_to_deg(lat, static_cast<double>(w.i) + h, static_cast<double>(w.j) + h);
}

/// Lattice (rotated) -> geographic degrees (identity without rotation; λ in (-180, 180] with).
[[nodiscard]] inline LonLat lattice_to_geographic(const PoleRotation& rot, LonLat p) {
  LonLat g;
  rot.to_geographic(p.lon_deg, p.lat_deg, g.lon_deg, g.lat_deg);
  return g;
}

/// Geographic -> lattice (rotated) degrees.
[[nodiscard]] inline LonLat geographic_to_lattice(const PoleRotation& rot, LonLat p) {
  LonLat r;
  rot.to_rotated(p.lon_deg, p.lat_deg, r.lon_deg, r.lat_deg);
  return r;
}

/// Maps whole rows of lattice points to geographic coordinates, for sampling rotated lattices:
/// one sin/cos per column and per row instead of per point. The rotation matrix is recovered from
/// PoleRotation's images of the rotated x, y, z axes (only its public interface is used);
/// results agree with PoleRotation::to_geographic to about 1e-13° (tested to 1e-10°).
class LatticeRowMapper {
 public:
  /// Columns at fractional pixel positions x_k (λ' = λ0 + x_k·Δ).
  LatticeRowMapper(const Lattice& lattice, const PoleRotation& rot, const std::vector<double>& x);
  /// Geographic λ (-180, 180] and φ of the columns on the lattice row at fractional position y
  /// (φ' = -90 + y·Δ); lon and lat hold x.size() values.
  void map_row(double y, double* lon_deg, double* lat_deg) const { map_row(y, 0, size(), lon_deg, lat_deg); }
  /// The same for columns k0..k1-1 only (lon and lat hold k1 - k0 values).
  void map_row(double y, std::size_t k0, std::size_t k1, double* lon_deg, double* lat_deg) const;
  [[nodiscard]] std::size_t size() const { return cos_lon_.size(); }

 private:
  Lattice lattice_;
  std::array<double, 9> m_{};  ///< rotated xyz -> geographic xyz, row-major
  std::vector<double> cos_lon_, sin_lon_;
};

/// Great-circle angle between two points, degrees in [0, 180] (haversine form, accurate for
/// small angles).
[[nodiscard]] inline double angular_distance_deg(LonLat a, LonLat b) {
  const double p1 = a.lat_deg * kDegToRad, p2 = b.lat_deg * kDegToRad;
  const double dp = p2 - p1, dl = (b.lon_deg - a.lon_deg) * kDegToRad;
  const double s = std::sin(0.5 * dp), t = std::sin(0.5 * dl);
  const double h = s * s + std::cos(p1) * std::cos(p2) * t * t;
  return 2.0 * std::asin(std::sqrt(h < 1.0 ? h : 1.0)) * kRadToDeg;
}

}  // namespace aq::mask

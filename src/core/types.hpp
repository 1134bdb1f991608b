// SPDX-License-Identifier: GPL-3.0-or-later
// Index types and angle helpers shared by every stage (ARCHITECTURE §3).
// Pixel and lattice indices are 64-bit: a 15" lattice has 3.7e9 pixels.
#pragma once

#include <cmath>
#include <cstdint>

namespace aq {

using PixelIndex = std::int64_t;  ///< index of a pixel or lattice vertex, row-major (j * nx + i)
using NodeId = std::int64_t;      ///< 0-based node number of a mesh
using ElementId = std::int64_t;   ///< 0-based element number of a mesh

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

/// Longitude wrapped into [lon0_deg, lon0_deg + 360).
inline double wrap_lon_deg(double lon_deg, double lon0_deg) {
  double d = std::fmod(lon_deg - lon0_deg, 360.0);
  if (d < 0.0) d += 360.0;
  if (d >= 360.0) d -= 360.0;
  return lon0_deg + d;
}

/// Non-negative remainder of a by m (m > 0): the periodic column index.
inline std::int64_t wrap_index(std::int64_t a, std::int64_t m) {
  const std::int64_t r = a % m;
  return r < 0 ? r + m : r;
}

}  // namespace aq

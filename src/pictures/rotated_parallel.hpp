// Geographic positions of the points of one parallel of a rotated frame, for the preview's
// background (preview_png.cpp): a map row at rotated latitude φ' and fixed rotated longitudes
// λ'_0 .. λ'_{n-1} (the column centres) needs the geographic (λ, φ) of every point, which is
// an atan2 and an asin each. Here the points are taken in runs of kRun; in each run only the
// middle point gets them, and the others are found from it by angle differences:
//
//   g = geographic unit vector of a point, r = that of the run's middle point, ρ = √(g_x² + g_y²)
//   λ = λ_r + atan(z_λ),  z_λ = (g_y r_x − g_x r_y) / (g_x r_x + g_y r_y)   = tan(λ − λ_r)
//   φ = φ_r + atan(z_φ),  z_φ = (g_z ρ_r − ρ r_z) / (ρ ρ_r + g_z r_z)       = tan(φ − φ_r)
//   atan(z) = z − z³/3 + z⁵/5 − z⁷/7 + z⁹/9 − z¹¹/11 for |z| < kMaxTan = 1/8
//             (truncation below (1/8)¹³/13 = 1.4e-13 rad)
// which is a square root and a division a point instead of two inverse trigonometric calls.
//
// A run where some |z| reaches kMaxTan (near a geographic pole λ turns fast; or a denominator is
// ≤ 0), or that comes within 0.57° of a geographic pole (cos φ ≤ kMinCosLat, where asin itself
// loses digits: its rounding error grows as 1/cos φ) takes atan2 and asin at every point. The
// result differs from exact_positions (atan2 and asin at every point) by less than
// kMaxErrorDeg; the seam needs no care (λ is wrapped into [-180, 180] like atan2's). Each row
// depends only on its inputs, so rows may be computed in any order, on any thread, with the
// same bits.
#pragma once

#include <array>
#include <vector>

#include "core/rotation.hpp"

namespace aq::io {

class RotatedParallel {
 public:
  /// Points at rotated longitudes `rlon_deg` (degrees) of the frame of `rotation`.
  RotatedParallel(const PoleRotation& rotation, const std::vector<double>& rlon_deg);

  [[nodiscard]] int size() const { return static_cast<int>(cos_lon_.size()); }

  /// lon_deg[x], lat_deg[x] (x < size()): geographic position of (λ'_x, φ' = rlat_deg), degrees;
  /// lon in [-180, 180]. Within kMaxErrorDeg of exact_positions.
  void positions(double rlat_deg, double* lon_deg, double* lat_deg) const;
  /// The same with atan2 and asin at every point (the reference).
  void exact_positions(double rlat_deg, double* lon_deg, double* lat_deg) const;

  static constexpr int kRun = 16;
  static constexpr double kMaxTan = 0.125;
  static constexpr double kMinCosLat = 0.01;
  /// Bound on |positions − exact_positions| (degrees; 1e-10° is 11 µm on the Earth): the series'
  /// 1.4e-13 rad (8e-12°) plus rounding. The tests measure at most 1e-11° on rows from pole to
  /// pole for several rotations.
  static constexpr double kMaxErrorDeg = 1e-10;

 private:
  // Geographic unit vector of point x on the parallel with cos/sin φ' = cp, sp.
  void unit_vector(double cp, double sp, int x, double g[3]) const;

  std::array<std::array<double, 3>, 3> axes_{};  // geographic unit vectors of the rotated x, y, z axes
  std::vector<double> cos_lon_, sin_lon_;
};

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Pole rotation (ARCHITECTURE §4.7, seed 002 Fig. 8): a rotated spherical system whose North
// pole sits at geographic (λp, φp). Implemented as a 3×3 rotation matrix R = Rz(λp)·Ry(90°-φp):
// the rotated system's North pole maps to (λp, φp) and the rotated meridian λ' = 0 passes through
// the geographic North pole's side (λ' = 180° points to the geographic North pole when φp < 90).
// Round trips are exact to ~1e-13°.
#pragma once

#include <array>

namespace aq {

class PoleRotation {
 public:
  /// Identity rotation.
  PoleRotation() = default;
  /// Rotated North pole at geographic (pole_lon_deg, pole_lat_deg); pole_lat_deg in [-90, 90].
  PoleRotation(double pole_lon_deg, double pole_lat_deg);

  /// Rotated (λ', φ') -> geographic (λ, φ), degrees; λ in (-180, 180].
  void to_geographic(double rlon_deg, double rlat_deg, double& lon_deg, double& lat_deg) const;
  /// The same from the sines and cosines of λ' and φ' (radians of the degrees given above), for
  /// callers that map whole rows: bit for bit what to_geographic gives (it calls this), the
  /// identity included only when the caller passes the angles themselves (see identity()).
  void to_geographic(double cos_rlon, double sin_rlon, double cos_rlat, double sin_rlat, double& lon_deg,
                     double& lat_deg) const;
  /// Geographic -> rotated, degrees; λ' in (-180, 180].
  void to_rotated(double lon_deg, double lat_deg, double& rlon_deg, double& rlat_deg) const;
  [[nodiscard]] bool identity() const { return identity_; }
  /// Sine of the geographic latitude of the rotated point (λ', φ') given by cos/sin of λ' and φ':
  /// the geographic z of its unit vector, one dot product (no inverse trigonometry).
  [[nodiscard]] double geographic_sin_lat(double cos_rlon, double sin_rlon, double cos_rlat, double sin_rlat) const {
    return m_[6] * cos_rlat * cos_rlon + m_[7] * cos_rlat * sin_rlon + m_[8] * sin_rlat;
  }

 private:
  std::array<double, 9> m_{1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< rotated xyz -> geographic xyz, row-major
  bool identity_ = true;
};

}  // namespace aq

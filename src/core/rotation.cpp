// SPDX-License-Identifier: GPL-3.0-or-later
// Pole rotation by a rotation matrix.
#include "core/rotation.hpp"

#include <cmath>

#include "core/types.hpp"

namespace aq {

namespace {
void to_xyz(double lon_deg, double lat_deg, double v[3]) {
  const double lo = lon_deg * kDegToRad;
  const double la = lat_deg * kDegToRad;
  v[0] = std::cos(la) * std::cos(lo);
  v[1] = std::cos(la) * std::sin(lo);
  v[2] = std::sin(la);
}
void from_xyz(const double v[3], double& lon_deg, double& lat_deg) {
  lon_deg = std::atan2(v[1], v[0]) * kRadToDeg;
  lat_deg = std::atan2(v[2], std::hypot(v[0], v[1])) * kRadToDeg;
}
}  // namespace

PoleRotation::PoleRotation(double pole_lon_deg, double pole_lat_deg) {
  identity_ = (pole_lat_deg == 90.0 && pole_lon_deg == 0.0);
  // Ry(θ) with θ = 90° - φp tilts the z axis toward +x; Rz(λp) turns it to longitude λp.
  const double t = (90.0 - pole_lat_deg) * kDegToRad;
  const double p = pole_lon_deg * kDegToRad;
  const double ct = std::cos(t), st = std::sin(t), cp = std::cos(p), sp = std::sin(p);
  // R = Rz(p) * Ry(t)
  m_ = {cp * ct, -sp, cp * st, sp * ct, cp, sp * st, -st, 0.0, ct};
}

void PoleRotation::to_geographic(double rlon_deg, double rlat_deg, double& lon_deg, double& lat_deg) const {
  if (identity_) {
    lon_deg = rlon_deg;
    lat_deg = rlat_deg;
    return;
  }
  const double lo = rlon_deg * kDegToRad;
  const double la = rlat_deg * kDegToRad;
  to_geographic(std::cos(lo), std::sin(lo), std::cos(la), std::sin(la), lon_deg, lat_deg);
}

void PoleRotation::to_geographic(double cos_rlon, double sin_rlon, double cos_rlat, double sin_rlat, double& lon_deg,
                                 double& lat_deg) const {
  const double v[3] = {cos_rlat * cos_rlon, cos_rlat * sin_rlon, sin_rlat};
  const double g[3] = {m_[0] * v[0] + m_[1] * v[1] + m_[2] * v[2], m_[3] * v[0] + m_[4] * v[1] + m_[5] * v[2],
                       m_[6] * v[0] + m_[7] * v[1] + m_[8] * v[2]};
  from_xyz(g, lon_deg, lat_deg);
}

void PoleRotation::to_rotated(double lon_deg, double lat_deg, double& rlon_deg, double& rlat_deg) const {
  if (identity_) {
    rlon_deg = lon_deg;
    rlat_deg = lat_deg;
    return;
  }
  double g[3];
  to_xyz(lon_deg, lat_deg, g);
  const double v[3] = {m_[0] * g[0] + m_[3] * g[1] + m_[6] * g[2],  // transpose = inverse
                       m_[1] * g[0] + m_[4] * g[1] + m_[7] * g[2], m_[2] * g[0] + m_[5] * g[1] + m_[8] * g[2]};
  from_xyz(v, rlon_deg, rlat_deg);
}

}  // namespace aq

// SPDX-License-Identifier: GPL-3.0-or-later
// Row mapping of rotated lattice points to geographic coordinates (see lattice_coords.hpp).
#include "mask/lattice_coords.hpp"

namespace aq::mask {

namespace {
std::array<double, 3> unit_vector(LonLat p) {
  const double lo = p.lon_deg * kDegToRad, la = p.lat_deg * kDegToRad;
  return {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
}
}  // namespace

LatticeRowMapper::LatticeRowMapper(const Lattice& lattice, const PoleRotation& rot, const std::vector<double>& x)
    : lattice_(lattice), cos_lon_(x.size()), sin_lon_(x.size()) {
  // Column c of the matrix is the geographic image of rotated axis c: (0,0), (90,0), (0,90).
  const std::array<LonLat, 3> axes = {LonLat{0.0, 0.0}, LonLat{90.0, 0.0}, LonLat{0.0, 90.0}};
  for (std::size_t c = 0; c < 3; ++c) {
    const std::array<double, 3> g = unit_vector(lattice_to_geographic(rot, axes[c]));
    for (std::size_t r = 0; r < 3; ++r) m_[r * 3 + c] = g[r];
  }
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double lo = lattice_xy_to_deg(lattice, x[k], 0.0).lon_deg * kDegToRad;
    cos_lon_[k] = std::cos(lo);
    sin_lon_[k] = std::sin(lo);
  }
}

void LatticeRowMapper::map_row(double y, std::size_t k0, std::size_t k1, double* lon_deg, double* lat_deg) const {
  const double la = lattice_xy_to_deg(lattice_, 0.0, y).lat_deg * kDegToRad;
  const double cl = std::cos(la), sl = std::sin(la);
  // g = M·v with v = (cl·cos λ', cl·sin λ', sl); the sl terms are the same for the whole row.
  const double z0 = m_[2] * sl, z1 = m_[5] * sl, z2 = m_[8] * sl;
  const double a0 = m_[0] * cl, b0 = m_[1] * cl, a1 = m_[3] * cl, b1 = m_[4] * cl, a2 = m_[6] * cl, b2 = m_[7] * cl;
  for (std::size_t k = k0; k < k1; ++k) {
    const double g0 = a0 * cos_lon_[k] + b0 * sin_lon_[k] + z0;
    const double g1 = a1 * cos_lon_[k] + b1 * sin_lon_[k] + z1;
    const double g2 = a2 * cos_lon_[k] + b2 * sin_lon_[k] + z2;
    lon_deg[k - k0] = std::atan2(g1, g0) * kRadToDeg;
    lat_deg[k - k0] = std::atan2(g2, std::hypot(g0, g1)) * kRadToDeg;
  }
}

}  // namespace aq::mask

// Geographic positions along a parallel of a rotated frame (see rotated_parallel.hpp).
#include "pictures/rotated_parallel.hpp"

#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace aq::io {

namespace {

// atan(z) for |z| < 1/8 (RotatedParallel::kMaxTan): the Taylor series to z¹¹.
inline double atan_small(double z) {
  const double z2 = z * z;
  return z * (1.0 + z2 * (-1.0 / 3.0 + z2 * (1.0 / 5.0 + z2 * (-1.0 / 7.0 + z2 * (1.0 / 9.0 - z2 / 11.0)))));
}

// A longitude in degrees, at most 360° outside [-180, 180], wrapped into it.
inline double wrap_lon_deg(double lon) {
  if (lon > 180.0) return lon - 360.0;
  if (lon < -180.0) return lon + 360.0;
  return lon;
}

}  // namespace

RotatedParallel::RotatedParallel(const PoleRotation& rotation, const std::vector<double>& rlon_deg) {
  // The rotated x, y, z axes (λ', φ') = (0, 0), (90, 0), (0, 90) in geographic coordinates,
  // taken from PoleRotation itself so that the positions agree with the mesh's.
  const double axes[3][2] = {{0.0, 0.0}, {90.0, 0.0}, {0.0, 90.0}};
  for (std::size_t k = 0; k < 3; ++k) {
    double lon = 0, lat = 0;
    rotation.to_geographic(axes[k][0], axes[k][1], lon, lat);
    const double lo = lon * kDegToRad, la = lat * kDegToRad;
    axes_[k] = {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
  }
  cos_lon_.resize(rlon_deg.size());
  sin_lon_.resize(rlon_deg.size());
  for (std::size_t x = 0; x < rlon_deg.size(); ++x) {
    cos_lon_[x] = std::cos(rlon_deg[x] * kDegToRad);
    sin_lon_[x] = std::sin(rlon_deg[x] * kDegToRad);
  }
}

void RotatedParallel::unit_vector(double cp, double sp, int x, double g[3]) const {
  const auto i = static_cast<std::size_t>(x);
  for (std::size_t k = 0; k < 3; ++k)
    g[k] = cp * (cos_lon_[i] * axes_[0][k] + sin_lon_[i] * axes_[1][k]) + sp * axes_[2][k];
}

void RotatedParallel::exact_positions(double rlat_deg, double* lon_deg, double* lat_deg) const {
  const double cp = std::cos(rlat_deg * kDegToRad), sp = std::sin(rlat_deg * kDegToRad);
  for (int x = 0; x < size(); ++x) {
    double g[3];
    unit_vector(cp, sp, x, g);
    lon_deg[x] = std::atan2(g[1], g[0]) * kRadToDeg;
    lat_deg[x] = std::asin(std::clamp(g[2], -1.0, 1.0)) * kRadToDeg;
  }
}

void RotatedParallel::positions(double rlat_deg, double* lon_deg, double* lat_deg) const {
  const double cp = std::cos(rlat_deg * kDegToRad), sp = std::sin(rlat_deg * kDegToRad);
  const int n = size();
  for (int x0 = 0; x0 < n; x0 += kRun) {
    const int m = std::min(kRun, n - x0);
    double g[kRun][3];
    for (int i = 0; i < m; ++i) unit_vector(cp, sp, x0 + i, g[i]);
    const double* r = g[m / 2];
    const double rho_r = std::sqrt(r[0] * r[0] + r[1] * r[1]);
    double z_lon[kRun], z_lat[kRun];
    bool near = true;
    for (int i = 0; i < m; ++i) {
      const double rho = std::sqrt(g[i][0] * g[i][0] + g[i][1] * g[i][1]);
      const double x = g[i][0] * r[0] + g[i][1] * r[1], y = g[i][1] * r[0] - g[i][0] * r[1];
      const double p = rho * rho_r + g[i][2] * r[2], q = g[i][2] * rho_r - rho * r[2];
      // False for a denominator <= 0 and for NaN; the quotients are used only when all are true.
      near = near && std::abs(y) < kMaxTan * x && std::abs(q) < kMaxTan * p && rho > kMinCosLat;
      z_lon[i] = y / x;
      z_lat[i] = q / p;
    }
    if (!near) {
      for (int i = 0; i < m; ++i) {
        lon_deg[x0 + i] = std::atan2(g[i][1], g[i][0]) * kRadToDeg;
        lat_deg[x0 + i] = std::asin(std::clamp(g[i][2], -1.0, 1.0)) * kRadToDeg;
      }
      continue;
    }
    // The middle point's own z are 0 (the same products subtracted), so it gets what
    // exact_positions gives.
    const double lon_r = std::atan2(r[1], r[0]), lat_r = std::asin(std::clamp(r[2], -1.0, 1.0));
    for (int i = 0; i < m; ++i) {
      lon_deg[x0 + i] = wrap_lon_deg((lon_r + atan_small(z_lon[i])) * kRadToDeg);
      lat_deg[x0 + i] = (lat_r + atan_small(z_lat[i])) * kRadToDeg;
    }
  }
}

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Conformal projections (digest izogrid.md §3; Snyder 1987, "Map projections: a working manual",
// eqs. for the oblique Mercator via sphere rotation, stereographic (21-4) and Lambert conformal
// conic (15-1)–(15-5) on the sphere).
#include "curvilinear/common/projection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"

namespace aq::curvilinear {

namespace {

// tan(pi/4 + phi/2), the Mercator/LC isometric-latitude kernel.
double t_iso(double phi) { return std::tan(0.25 * kPi + 0.5 * phi); }

}  // namespace

Projection::Projection(const ProjectionParams& params) : p_(params) {
  if (const auto bad = projection_problems(p_); !bad.empty()) {
    std::string why;
    for (const auto& [key, text] : bad) why += (why.empty() ? "" : "; ") + text;
    throw ConfigError("projection: " + why);
  }

  const double phi0 = p_.rlat_deg * kDegToRad;
  const double lam0 = p_.rlon_deg * kDegToRad;
  const double th = p_.rota_deg * kDegToRad;
  cos_rota_ = std::cos(th);
  sin_rota_ = std::sin(th);

  // m = Rx(rota) * Ry(phi0) * Rz(-lam0): geographic unit vector -> centred frame (digest §3).
  const double cl = std::cos(lam0), sl = std::sin(lam0), cp = std::cos(phi0), sp = std::sin(phi0);
  // Rows of Ry*Rz: X2, Y2, Z2.
  const double r2[3][3] = {{cp * cl, cp * sl, sp}, {-sl, cl, 0.0}, {-sp * cl, -sp * sl, cp}};
  for (int c = 0; c < 3; ++c) {
    m_[0][c] = r2[0][c];
    m_[1][c] = cos_rota_ * r2[1][c] - sin_rota_ * r2[2][c];
    m_[2][c] = sin_rota_ * r2[1][c] + cos_rota_ * r2[2][c];
  }

  if (p_.kind == ProjectionKind::kLambertConic) {
    const double lat1 = std::isnan(p_.lat1_deg) ? p_.rlat_deg : p_.lat1_deg;
    const double lat2 = std::isnan(p_.lat2_deg) ? lat1 : p_.lat2_deg;
    const double p1 = lat1 * kDegToRad, p2 = lat2 * kDegToRad;
    double n = 0.0;
    if (std::fabs(p1 - p2) < 1e-12) {
      n = std::sin(p1);
    } else {
      n = std::log(std::cos(p1) / std::cos(p2)) / std::log(t_iso(p2) / t_iso(p1));
    }
    lc_n_ = n;
    lc_f_ = std::cos(p1) * std::pow(t_iso(p1), n) / n;
    lc_rho0_ = lc_f_ / std::pow(t_iso(phi0), n);
  }
}

PlanePoint Projection::forward(double lon_deg, double lat_deg) const {
  const double phi = lat_deg * kDegToRad;
  const double lam = lon_deg * kDegToRad;
  double u = 0.0, v = 0.0;
  if (p_.kind == ProjectionKind::kLambertConic) {
    const double dlam = (wrap_lon_deg(lon_deg, p_.rlon_deg - 180.0) - p_.rlon_deg) * kDegToRad;
    const double rho = lc_f_ / std::pow(t_iso(phi), lc_n_);
    const double a = lc_n_ * dlam;
    const double u0 = rho * std::sin(a);
    const double v0 = lc_rho0_ - rho * std::cos(a);
    u = cos_rota_ * u0 - sin_rota_ * v0;
    v = sin_rota_ * u0 + cos_rota_ * v0;
  } else {
    const double cphi = std::cos(phi);
    const double px = cphi * std::cos(lam), py = cphi * std::sin(lam), pz = std::sin(phi);
    const double x3 = m_[0][0] * px + m_[0][1] * py + m_[0][2] * pz;
    const double y3 = m_[1][0] * px + m_[1][1] * py + m_[1][2] * pz;
    const double z3 = m_[2][0] * px + m_[2][1] * py + m_[2][2] * pz;
    if (p_.kind == ProjectionKind::kMercator) {
      u = std::atan2(y3, x3);
      v = std::asinh(z3 / std::hypot(x3, y3));  // = ln tan(pi/4 + phi'/2)
    } else {
      const double k = 2.0 / (1.0 + x3);
      u = k * y3;
      v = k * z3;
    }
  }
  return {u / p_.uscale, v / p_.uscale};
}

GeoPoint Projection::inverse(double x, double y) const {
  const double u = x * p_.uscale, v = y * p_.uscale;
  double lon = 0.0, lat = 0.0;
  if (p_.kind == ProjectionKind::kLambertConic) {
    const double u0 = cos_rota_ * u + sin_rota_ * v;
    const double v0 = -sin_rota_ * u + cos_rota_ * v;
    const double sn = lc_n_ > 0.0 ? 1.0 : -1.0;
    const double dy = lc_rho0_ - v0;
    const double rho = sn * std::hypot(u0, dy);
    const double a = std::atan2(sn * u0, sn * dy);
    const double phi = 2.0 * std::atan(std::pow(lc_f_ / rho, 1.0 / lc_n_)) - 0.5 * kPi;
    lat = phi * kRadToDeg;
    lon = p_.rlon_deg + a / lc_n_ * kRadToDeg;
  } else {
    double x3 = 0.0, y3 = 0.0, z3 = 0.0;
    if (p_.kind == ProjectionKind::kMercator) {
      const double cphi = 1.0 / std::cosh(v);  // cos(phi'), phi' = atan(sinh v)
      z3 = std::tanh(v);
      x3 = cphi * std::cos(u);
      y3 = cphi * std::sin(u);
    } else {
      const double r2 = u * u + v * v;
      const double den = 4.0 + r2;
      x3 = (4.0 - r2) / den;
      y3 = 4.0 * u / den;
      z3 = 4.0 * v / den;
    }
    const double px = m_[0][0] * x3 + m_[1][0] * y3 + m_[2][0] * z3;
    const double py = m_[0][1] * x3 + m_[1][1] * y3 + m_[2][1] * z3;
    const double pz = m_[0][2] * x3 + m_[1][2] * y3 + m_[2][2] * z3;
    lat = std::atan2(pz, std::hypot(px, py)) * kRadToDeg;
    lon = std::atan2(py, px) * kRadToDeg;
  }
  return {wrap_lon_deg(lon, p_.rlon_deg - 180.0), lat};
}

double Projection::metres_per_unit(double x, double y) const {
  const double u = x * p_.uscale, v = y * p_.uscale;
  const double k = p_.radius_m * p_.uscale;
  switch (p_.kind) {
    case ProjectionKind::kMercator:
      return k / std::cosh(v);
    case ProjectionKind::kStereographic:
      return k * 4.0 / (4.0 + u * u + v * v);
    case ProjectionKind::kLambertConic: {
      const double u0 = cos_rota_ * u + sin_rota_ * v;
      const double v0 = -sin_rota_ * u + cos_rota_ * v;
      const double rho = std::hypot(u0, lc_rho0_ - v0);
      const double phi = 2.0 * std::atan(std::pow(lc_f_ / (lc_n_ > 0.0 ? rho : -rho), 1.0 / lc_n_)) - 0.5 * kPi;
      return k * std::cos(phi) / (std::fabs(lc_n_) * rho);
    }
  }
  return k;
}

}  // namespace aq::curvilinear

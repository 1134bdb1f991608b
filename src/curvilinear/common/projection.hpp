// SPDX-License-Identifier: GPL-3.0-or-later
// Conformal projections between geographic coordinates (degrees) and the izogrid plane
// (seed 000 Sec. 2.1, Appendix 1; digest izogrid.md §3). Sphere of radius R; no ellipsoid.
//
// Every projection puts its centre (rlat, rlon) at the plane origin and is conformal, so a grid
// that is orthogonal and isotropic in the plane stays so on the sphere. Plane units follow the
// seed's "graph paper": the unit-sphere projection coordinates (u, v), in radians near the
// centre, divided by `uscale` (x = u/uscale, y = v/uscale; with uscale = 0.001 one unit is
// 1 mrad ≈ 6.371 km on the Earth at the centre). Kinds (NCAR EZMAP two-letter codes):
//
//   ME  rotated Mercator: the sphere is rotated so (rlat, rlon) becomes (0°, 0°) of a new
//       lat/lon system (φ', λ'); u = λ', v = asinh(tan φ'). "Equator" and central meridian of the
//       rotated system are the plane's axes.
//   ST  oblique (or polar, |rlat| = 90) stereographic tangent at (rlat, rlon):
//       with c the angular distance from the centre, |(u,v)| = 2 tan(c/2).
//   LC  Lambert conformal conic, normal aspect, standard parallels lat1, lat2 (both = rlat when
//       not given: the tangent cone), central meridian rlon, origin at (rlat, rlon). EZMAP gives
//       PLAT/ROTA the meaning of standard parallels for LC; aquatoria keeps rlat/rlon/rota as
//       centre and rotation for every kind and takes the parallels from lat1/lat2 instead.
//
// `rota` (degrees) rotates the map counter-clockwise about the centre: the plane's +y axis
// points at azimuth rota, measured clockwise from north at the centre (rota = 0: +y is north,
// +x is east). For ME the rotation is about the centre's axis of the sphere, for ST and LC it is
// the same rotation applied in the plane (identical near the centre).
//
//   plane (units = rad/uscale)          sphere
//        ^ y (azimuth rota)
//        |                              (rlat, rlon) -> (0, 0)
//   -----+-----> x (azimuth rota + 90°)
//        |
#pragma once

#include <limits>
#include <string>
#include <string_view>

#include "curvilinear/common/plane_point.hpp"
#include "grid_params/grid_kinds.hpp"
#include "grid_params/projection_params.hpp"

namespace aq::curvilinear {

/// Geographic point, degrees.
struct GeoPoint {
  double lon_deg = 0.0;
  double lat_deg = 0.0;
};

/// A conformal sphere <-> plane projection. Immutable and cheap to copy; thread-safe.
/// Forward and inverse agree to ~1e-13 degrees (round trips are tested to 1e-12).
class Projection {
 public:
  /// Validates the parameters (projection_problems(): the config reports the same at load, with
  /// positions): ConfigError naming every bad key and value.
  explicit Projection(const ProjectionParams& params);

  /// Plane coordinates of (lon, lat) in degrees (any longitude; |lat| <= 90). Points where the
  /// projection is singular (the rotated poles for ME, the antipode of the centre for ST, the
  /// pole opposite to the cone's apex for LC) give non-finite coordinates.
  [[nodiscard]] PlanePoint forward(double lon_deg, double lat_deg) const;
  /// Geographic coordinates of a plane point; longitude in [rlon - 180, rlon + 180).
  [[nodiscard]] GeoPoint inverse(double x, double y) const;

  /// Local scale of the map at plane point (x, y): metres on the sphere per plane unit (the same
  /// in every direction, the map being conformal). Equals radius_m * uscale at the centre for
  /// ME and ST (and at the standard parallel of a tangent LC).
  [[nodiscard]] double metres_per_unit(double x, double y) const;

  [[nodiscard]] const ProjectionParams& params() const { return p_; }

 private:
  ProjectionParams p_;
  // Rotation taking geographic unit vectors to the frame with the centre at (1,0,0), +y3 along
  // the plane's x axis and +z3 along its y axis (ME and ST); LC uses only the plane rotation.
  double m_[3][3] = {};
  double cos_rota_ = 1.0, sin_rota_ = 0.0;
  // LC constants (unit sphere): cone constant n, F and the radius rho0 at the origin.
  double lc_n_ = 0.0, lc_f_ = 0.0, lc_rho0_ = 0.0;
};

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// The conformal projection of a regional grid's map (curvilinear/common/projection.hpp draws it):
// its fields, defined once for the izogrid keys (RegionalParams::projection) and every projection
// the program makes itself (a block's, a parent grid's), and their one validation. The izogrid
// key of each field is in brackets.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "grid_params/grid_kinds.hpp"

namespace aq::curvilinear {

struct ProjectionParams {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();

  /// [proj] ME (rotated Mercator), LC (Lambert conformal conic) or ST (stereographic).
  ProjectionKind kind = ProjectionKind::kMercator;
  /// [rlat] latitude of the centre (plane origin), degrees, [-90, 90]; |rlat| < 90 for ME and LC.
  double rlat_deg = 0.0;
  /// [rlon] longitude of the centre (plane origin; LC central meridian), degrees, finite.
  double rlon_deg = 0.0;
  /// [rota] azimuth of the plane's +y axis, degrees clockwise from north at the centre, finite.
  double rota_deg = 0.0;
  /// [lat1], [lat2] LC only: standard parallels, degrees in (-90, 90), same hemisphere or one of
  /// them 0 is fine, lat1 = -lat2 is not (the cone degenerates into Mercator). NaN = rlat (the
  /// tangent cone).
  double lat1_deg = kUnset;
  double lat2_deg = kUnset;
  /// [uscale] plane units per unit-sphere radian is 1/uscale, within [1e-9, 1e3] (the seed's
  /// 0.001: one unit is 1 mrad ≈ 6.371 km at the centre; outside that range the plane coordinates
  /// of any region under- or overflow in the metrics).
  double uscale = 0.001;
  /// [radius] sphere radius, metres, > 0.
  double radius_m = 6371000.0;
};

/// What is wrong with `p`, as (izogrid key, message) pairs: a non-finite angle, rlat outside
/// [-90, 90], uscale outside [1e-9, 1e3], a radius that is not positive, an ME or LC centre at a
/// pole, LC standard parallels at a pole or giving a cylinder (lat1 = -lat2). Empty when it is a
/// projection.
std::vector<std::pair<std::string, std::string>> projection_problems(const ProjectionParams& p);

}  // namespace aq::curvilinear

// SPDX-License-Identifier: GPL-3.0-or-later
// A point or vector of the izogrid projection plane (plane units, see projection.hpp).
#pragma once

namespace aq::curvilinear {

/// Point or vector of the projection plane, in plane units.
struct PlanePoint {
  double x = 0.0;
  double y = 0.0;
};

}  // namespace aq::curvilinear

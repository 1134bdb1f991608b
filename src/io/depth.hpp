// SPDX-License-Identifier: GPL-3.0-or-later
// The depth every writer stores: metres below the datum, positive down (ADCIRC DP, CF
// sea_floor_depth_below_geoid), from the mesh's elevation (negative below sea level).
#pragma once

namespace aq::io {

/// -elevation, with an elevation of 0 giving +0 (never "-0" in a text file).
inline double depth_below_datum_m(double elevation_m) { return 0.0 - elevation_m; }

}  // namespace aq::io

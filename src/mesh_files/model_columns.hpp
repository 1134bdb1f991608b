// SPDX-License-Identifier: GPL-3.0-or-later
// The numbers the model formats write for a node or a triangle, one function each, used by the
// writers (fort14_writer, schism_writer, fesom_writer) and by whoever hands the same numbers over
// as arrays (the Python package's Run.model_mesh), so the arrays are the files' numbers:
//
//   fort.14, hgrid.gr3      longitude in [-180, 180), latitude, depth below the datum (m, positive
//                           down); triangles anticlockwise (the mesh's order)
//   FESOM2 nod2d/aux3d      longitude in [-180, 180), latitude; the bottom in metres, negative, 0
//                           where the elevation is >= 0; elem2d.out triangles clockwise (n1 n3 n2)
#pragma once

#include <array>

#include "core/types.hpp"
#include "io/depth.hpp"

namespace aq::io {

/// Longitude (degrees) every model file writes: wrapped into [-180, 180).
inline double model_lon_deg(double lon_deg) { return wrap_lon_deg(lon_deg, -180.0); }

/// fort.14 / hgrid.gr3 depth (m, positive down) of a node of elevation `elevation_m`.
inline double fort14_depth_m(double elevation_m) { return depth_below_datum_m(elevation_m); }

/// FESOM2 aux3d.out bottom (m, negative; FESOM negates positive values, so a node at or above the
/// datum is written as 0, not as a depth) of a node of elevation `elevation_m`.
inline double fesom_bottom_m(double elevation_m) { return elevation_m < 0.0 ? elevation_m : 0.0; }

/// FESOM2 elem2d.out corners of the mesh triangle `t` (anticlockwise): n1 n3 n2, clockwise.
inline std::array<NodeId, 3> fesom_triangle(const std::array<NodeId, 3>& t) { return {t[0], t[2], t[1]}; }

}  // namespace aq::io

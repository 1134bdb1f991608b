// SPDX-License-Identifier: GPL-3.0-or-later
// Triangles on the unit sphere: unit vectors, signed areas and angles (used by the geographic
// mesh, the shape quality of the files and the open-boundary snapping of regional meshes).
#pragma once

#include <array>

namespace aq::mesh {

/// Unit vector of (λ, φ) in degrees.
std::array<double, 3> unit_vector_deg(double lon_deg, double lat_deg);
/// Signed area (steradians, anticlockwise seen from outside positive) of the geodesic triangle
/// a, b, c on the unit sphere (Van Oosterom & Strackee 1983).
double spherical_triangle_area(const std::array<double, 3>& a, const std::array<double, 3>& b,
                               const std::array<double, 3>& c);
/// Angles (degrees) of the spherical triangle with vertices at unit vectors a, b, c.
std::array<double, 3> spherical_angles_deg(const std::array<double, 3>& a, const std::array<double, 3>& b,
                                           const std::array<double, 3>& c);

}  // namespace aq::mesh

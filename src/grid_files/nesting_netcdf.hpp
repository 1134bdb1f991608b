// SPDX-License-Identifier: GPL-3.0-or-later
// Nesting data of a regional grid in the global mesh, as netCDF (`<name>_nesting.nc`, written
// beside the ROMS grid file; ARCHITECTURE §6). One record per boundary point of the regional
// C-grid (ρ, u and v points of the four open boundaries; corner points appear once per side):
//
//   dimensions:  point = N, vertex = 3
//   variables:
//     byte   point_type(point)          0 rho, 1 u, 2 v
//     byte   boundary(point)            ROMS boundary index: 1 west, 2 south, 3 east, 4 north
//     int    xi_index(point), eta_index(point)   0-based index into that point type's ROMS array
//                                       (xi_rho/eta_rho, xi_u/eta_u or xi_v/eta_v)
//     double lon(point), lat(point)     geographic position, degrees
//     double x(point), y(point)         position in the regional projection plane (its units)
//     int64  element(point)             0-based triangle of the global mesh holding the point;
//                                       -1 outside the global wet mesh (over its land)
//     int64  element_nodes(point, vertex)  the triangle's global node ids (0-based; -1 outside)
//     double weights(point, vertex)     barycentric weights in the global lattice plane (sum 1;
//                                       0 outside): value(p) = Σ w_k value(node_k); the plane is
//                                       λ′, φ′ on the lon-lat lattice and λ′ and the Mercator
//                                       ordinate of φ′ on the Mercator one (lattice_kind)
//     byte   element_level(point)       quadtree level of the element (-1 outside)
//     double global_element_size(point) the element's leg length, metres
//     double regional_cell_size(point)  the regional grid's cell size there, metres
//     double refinement_ratio(point)    global_element_size / regional_cell_size (NaN outside)
//   global attributes: title, Conventions, history, regional_grid, global_config, global_mesh
//     (nodes/triangles), lattice (kind, Δ0, L, λ0; y0 on the Mercator lattice), pole rotation,
//     points_outside, refinement_ratio
//     (median over the points inside), staggering (how ρ/u/v come from the supergrid).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/attribute_value.hpp"

namespace aq::io {

struct NestingFile {
  // Per point.
  std::vector<std::int8_t> point_type, boundary, element_level;
  std::vector<std::int32_t> xi_index, eta_index;
  std::vector<double> lon, lat, x, y;
  std::vector<std::int64_t> element;
  std::vector<std::array<std::int64_t, 3>> element_nodes;
  std::vector<std::array<double, 3>> weights;
  std::vector<double> global_element_size_m, regional_cell_size_m, refinement_ratio;
  // Global attributes (name, text or number), written in order after the fixed ones.
  std::string title = "aquatoria nesting data: regional boundary points in the global mesh";
  std::string history;
  std::vector<std::pair<std::string, AttributeValue>> attributes;

  [[nodiscard]] std::size_t size() const { return point_type.size(); }
};

/// Writes the file (netCDF-4). Throws InternalError when the per-point arrays differ in length,
/// OutputError naming `path` on any netCDF failure.
void write_nesting(const std::filesystem::path& path, const NestingFile& data);

/// Reads a file written by write_nesting (the per-point variables and the text/number attributes).
/// Throws InputError naming `path` when it is missing or malformed.
NestingFile read_nesting(const std::filesystem::path& path);

}  // namespace aq::io

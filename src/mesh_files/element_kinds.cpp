// SPDX-License-Identifier: GPL-3.0-or-later
// Element kinds of the writers.
#include "mesh_files/element_kinds.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace aq::io {

ElementKinds default_element_kinds(const mesh::Mesh& mesh) {
  return mesh.triangles.empty() && !mesh.squares.empty() ? ElementKinds::kSquares : ElementKinds::kTriangles;
}

void check_elements(const mesh::Mesh& mesh, ElementKinds kinds) {
  const auto n = static_cast<std::size_t>(mesh.node_count());
  if (mesh.node_j.size() != n || mesh.lon_deg.size() != n || mesh.lat_deg.size() != n || mesh.depth_m.size() != n ||
      mesh.node_flags.size() != n) {
    throw InternalError(fmt::format("mesh node arrays have inconsistent sizes ({} nodes)", n));
  }
  if (has_triangles(kinds)) {
    if (mesh.triangles.empty() && !mesh.squares.empty()) {
      throw InternalError(
          fmt::format("writer asked for triangles (mesh.elements = \"{}\") but the mesh has only squares", kinds));
    }
    if (mesh.triangle_level.size() != mesh.triangles.size()) {
      throw InternalError("mesh.triangle_level has a different size than mesh.triangles");
    }
  }
  if (has_squares(kinds)) {
    if (mesh.square_level.size() != mesh.squares.size()) {
      throw InternalError("mesh.square_level has a different size than mesh.squares");
    }
    if (!mesh.square_midside.empty() && mesh.square_midside.size() != mesh.squares.size()) {
      throw InternalError("mesh.square_midside has a different size than mesh.squares");
    }
  }
  if (mesh.boundary_edge_loop.size() != mesh.boundary_edges.size() && !mesh.boundary_edge_loop.empty()) {
    throw InternalError("mesh.boundary_edge_loop has a different size than mesh.boundary_edges");
  }
}

}  // namespace aq::io

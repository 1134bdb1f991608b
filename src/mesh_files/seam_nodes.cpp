// SPDX-License-Identifier: GPL-3.0-or-later
// Seam duplicates of the λ–φ plane view.
#include "mesh_files/seam_nodes.hpp"

namespace aq::io {

std::array<bool, 2> SeamNodes::edge_unwrapped(const mesh::Mesh& mesh, const std::array<NodeId, 2>& e) {
  const std::int64_t ia = mesh.node_i[e[0]], ib = mesh.node_i[e[1]];
  const std::int64_t half = mesh.lattice.nx / 2;
  if (ia == 0 && ib == 0) {
    const bool north = mesh.node_j[e[1]] > mesh.node_j[e[0]];
    return {north, north};
  }
  return {ia == 0 && ib > half, ib == 0 && ia > half};
}

SeamNodes::SeamNodes(const mesh::Mesh& mesh, ElementKinds kinds) : node_count_(mesh.node_count()) {
  std::vector<NodeId> found;
  const std::int64_t half = mesh.lattice.nx / 2;
  auto scan = [&](const NodeId* nodes, int k) {
    std::int64_t max_i = 0;
    bool zero = false;
    for (int a = 0; a < k; ++a) {
      const std::int64_t i = mesh.node_i[nodes[a]];
      max_i = std::max(max_i, i);
      zero = zero || i == 0;
    }
    if (!zero || max_i <= half) return;
    for (int a = 0; a < k; ++a)
      if (mesh.node_i[nodes[a]] == 0) found.push_back(nodes[a]);
  };
  if (has_triangles(kinds)) {
    for (const auto& t : mesh.triangles) scan(t.data(), 3);
  }
  if (has_squares(kinds)) {
    std::array<NodeId, kMaxSquarePolygon> poly{};
    for (ElementId s = 0; s < mesh.square_count(); ++s) scan(poly.data(), square_polygon(mesh, s, poly));
  }
  for (const auto& e : mesh.boundary_edges) {
    const auto u = edge_unwrapped(mesh, e);
    if (u[0]) found.push_back(e[0]);
    if (u[1]) found.push_back(e[1]);
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  originals_ = std::move(found);
}

std::array<NodeId, 2> SeamNodes::plane_edge(const mesh::Mesh& mesh, const std::array<NodeId, 2>& e) const {
  const auto u = edge_unwrapped(mesh, e);
  return {u[0] ? duplicate_of(e[0]) : e[0], u[1] ? duplicate_of(e[1]) : e[1]};
}

}  // namespace aq::io

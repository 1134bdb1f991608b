// SPDX-License-Identifier: GPL-3.0-or-later
// Merging of pole-row nodes for 3-D writers.
#include "mesh_files/pole_merge.hpp"

namespace aq::io {

PoleMerge::PoleMerge(const mesh::Mesh& mesh) {
  const std::int64_t n = mesh.node_count();
  // Rows 0 and ny of the global lattice (a window lattice's rows are offset by j_origin).
  const std::int64_t ny = mesh.lattice.ny_global, j0 = mesh.lattice.j_origin;
  std::int64_t pole_nodes = 0;
  for (NodeId a = 0; a < n; ++a)
    if (mesh.node_j[a] + j0 == 0 || mesh.node_j[a] + j0 == ny) ++pole_nodes;
  output_count_ = n;
  if (pole_nodes == 0) return;

  node_map_.assign(static_cast<std::size_t>(n), -1);
  sources_.reserve(static_cast<std::size_t>(n));
  NodeId south = -1, north = -1;
  for (NodeId a = 0; a < n; ++a) {
    const std::int64_t j = mesh.node_j[a] + j0;
    NodeId* pole = j == 0 ? &south : (j == ny ? &north : nullptr);
    if (pole != nullptr && *pole >= 0) {
      node_map_[a] = *pole;
      ++merged_;
      continue;
    }
    const auto o = static_cast<NodeId>(sources_.size());
    node_map_[a] = o;
    sources_.push_back(a);
    if (pole != nullptr) *pole = o;
  }
  output_count_ = static_cast<std::int64_t>(sources_.size());
}

int PoleMerge::map_polygon(const NodeId* nodes, int k, NodeId* out) const {
  int m = 0;
  for (int a = 0; a < k; ++a) {
    const NodeId o = map(nodes[a]);
    if (m > 0 && out[m - 1] == o) continue;
    out[m++] = o;
  }
  while (m > 1 && out[m - 1] == out[0]) --m;
  return m;
}

}  // namespace aq::io

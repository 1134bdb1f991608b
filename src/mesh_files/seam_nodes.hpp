// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh drawn on the λ–φ rectangle [λ0, λ0+360] × [-90, 90] (ARCHITECTURE §4.5, §4.8).
// Lattice column I = nx is column 0, so an element east of the last column uses nodes at I = 0
// that must be drawn at I = nx (Mesh::unwrapped_i). Writers in the plane give each such node a
// duplicate at λ0 + 360 and, where the format can, link it to its original (MSH $Periodic).
//
//   I:  nx-1   nx≡0   1                     plane node ids: originals 0..N-1,
//        +------+------+                    duplicates N..N+D-1 in ascending order of the
//        |  e   |      |   e is drawn with  original they copy
//        +------+------+   its east nodes at I = nx (duplicates), not at I = 0
//
// Boundary edges are unwrapped like the element they bound: an edge joining I = 0 to I > nx/2
// uses the duplicate; an edge lying on the seam itself (both ends at I = 0) is drawn at
// λ0 + 360 when it runs north (the wet area, on its left, is west of the seam).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/types.hpp"
#include "mesh/mesh.hpp"
#include "mesh_files/element_kinds.hpp"

namespace aq::io {

class SeamNodes {
 public:
  /// Finds the nodes to duplicate for the elements `kinds` and the boundary edges.
  SeamNodes(const mesh::Mesh& mesh, ElementKinds kinds);

  /// Number of duplicates D.
  [[nodiscard]] std::int64_t count() const { return static_cast<std::int64_t>(originals_.size()); }
  /// Original node of every duplicate, ascending.
  [[nodiscard]] const std::vector<NodeId>& originals() const { return originals_; }
  /// Plane id of the duplicate of node `n` (N + index in originals()); -1 if it has none.
  [[nodiscard]] NodeId duplicate_of(NodeId n) const {
    const auto it = std::lower_bound(originals_.begin(), originals_.end(), n);
    if (it == originals_.end() || *it != n) return -1;
    return node_count_ + (it - originals_.begin());
  }
  /// Plane node of `n` as a node of the element whose nodes are `nodes` (n itself, or its
  /// duplicate when the element is drawn across the seam).
  template <std::size_t K>
  [[nodiscard]] NodeId plane_node(const mesh::Mesh& mesh, const std::array<NodeId, K>& nodes, NodeId n) const {
    if (originals_.empty() || mesh.node_i[n] != 0) return n;
    return mesh.unwrapped_i(nodes, n) == 0 ? n : duplicate_of(n);
  }
  /// Plane nodes of boundary edge a -> b (see the rule at the top of this file).
  [[nodiscard]] std::array<NodeId, 2> plane_edge(const mesh::Mesh& mesh, const std::array<NodeId, 2>& e) const;

  /// Whether boundary edge a -> b is drawn with duplicates.
  static std::array<bool, 2> edge_unwrapped(const mesh::Mesh& mesh, const std::array<NodeId, 2>& e);

 private:
  std::vector<NodeId> originals_;
  NodeId node_count_ = 0;
};

/// λ of lattice column `i` in the plane, with i = nx drawn at exactly λ0 + 360.
inline double plane_lon_deg(const Lattice& lattice, std::int64_t i) {
  return i == lattice.nx && lattice.periodic() ? lattice.lon0_deg + 360.0 : lattice.lon_of(i);
}

}  // namespace aq::io

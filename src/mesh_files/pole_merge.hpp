// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh in 3-D (x, y, z on the sphere): every lattice node on the row J = 0 (or J = ny) is
// the same physical point, the South (North) pole (ARCHITECTURE §4.5). 3-D writers merge each
// pole row into its lowest-numbered node and drop the elements that become degenerate:
//
//   J = ny   p0 ---- p1 ---- p2        all p_k -> p0
//            |  \  b  |  \    |        triangle a = (s0, s1, p1) keeps 3 distinct nodes;
//            | a  \   |     \ |        triangle b = (s0, p1, p0) becomes (s0, p0): dropped;
//   J = ny-1 s0 ---- s1 ---- s2        a square (s0, s1, p1, p0) becomes the triangle (s0, s1, p0)
//
// Output nodes keep the mesh order with the merged nodes removed (ids are compacted).
#pragma once

#include <cstdint>
#include <vector>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace aq::io {

class PoleMerge {
 public:
  explicit PoleMerge(const mesh::Mesh& mesh);

  /// Output node of mesh node `n`.
  [[nodiscard]] NodeId map(NodeId n) const { return node_map_.empty() ? n : node_map_[n]; }
  /// Number of output nodes.
  [[nodiscard]] std::int64_t output_count() const { return output_count_; }
  /// Mesh node of output node `o` (for a merged pole: the lowest-numbered node of its row).
  [[nodiscard]] NodeId source(NodeId o) const { return sources_.empty() ? o : sources_[o]; }
  /// Mesh nodes removed by merging (pole nodes beyond the first of each pole row).
  [[nodiscard]] std::int64_t merged() const { return merged_; }

  /// Maps the k nodes of an element to output nodes, removing cyclically repeated nodes;
  /// writes them to `out` and returns how many remain (< 3: the element is degenerate).
  int map_polygon(const NodeId* nodes, int k, NodeId* out) const;

 private:
  std::vector<NodeId> node_map_;  // empty: identity (no pole rows)
  std::vector<NodeId> sources_;
  std::int64_t output_count_ = 0;
  std::int64_t merged_ = 0;
};

}  // namespace aq::io

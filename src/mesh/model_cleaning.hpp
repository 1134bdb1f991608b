// SPDX-License-Identifier: GPL-3.0-or-later
// Cleaning a triangle mesh for the finite-element ocean models (ARCHITECTURE §1, §4.11): no
// triangle with fewer than two edge neighbours and no pinch vertex.
//
// Both come from the pixel coast. A lattice corner triangle can hang on the rest of the mesh by
// one edge (two of its edges on the coast):
//
//        o                      FESOM2's partitioner stops on it ("find_elem_neighbors_ini:
//       /|                      Insufficient number of neighbors"; FESOM1.4 accepted it).
//      / | t   <- one neighbour
//     o--o
//     |##|
//
// and the wet area can touch itself at one node, the pinch vertex p, where two fans of triangles
// meet that share no edge there:
//
//     \##|  /                   SCHISM stops on it while it builds its boundary tables
//      \#| / fan B              ("Illegal bnd node": every boundary node must start exactly one
//       \|/                     boundary stretch of its element ball).
//        p
//       /|\                                                                               .
//  fan A/ |#\                                                                             .
//
// The cleaning works in rounds, all on integer topology, one thread, in triangle order (the
// result depends on nothing else):
//   1. every triangle with fewer than two neighbours among the kept triangles is removed, all at
//      once; repeated while any is found (each removal can leave a neighbour with one);
//   2. when none is left, every pinch vertex (ascending node id) keeps its largest fan (most
//      triangles; a tie goes to the fan with the smallest triangle id) and the triangles of its
//      other fans that touch it are removed, which can leave triangles with one neighbour (step
//      1 again) or new pinches next to it (step 2 again);
// until neither is found. Nodes no kept triangle uses are dropped; nodes and triangles keep their
// relative order, the boundary loops are traced again (wet area on the left; a loop untouched by
// the cleaning is the same loop, from the same node).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/report.hpp"
#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace aq::mesh {

/// What the cleaning removed.
struct CleaningStats {
  std::int64_t one_neighbour_triangles = 0;  ///< triangles removed for having fewer than two neighbours
  int rounds = 0;                            ///< passes of step 1 that removed some
  std::int64_t pinches = 0;                  ///< pinch vertices resolved (step 2)
  std::int64_t pinch_triangles = 0;          ///< triangles removed at them
  std::int64_t removed_nodes = 0;            ///< nodes no kept triangle uses any more
  double removed_area_km2 = 0.0;             ///< of the removed triangles (geodesic, authalic sphere)
};

/// Defects the models refuse, counted in a triangle mesh.
struct ModelDefects {
  std::int64_t one_neighbour_triangles = 0;  ///< triangles with fewer than two edge neighbours
  std::int64_t pinch_nodes = 0;              ///< nodes whose triangles form more than one fan
  std::int64_t shared_edges = 0;             ///< edges of more than two triangles
  [[nodiscard]] bool none() const { return one_neighbour_triangles == 0 && pinch_nodes == 0 && shared_edges == 0; }
};

/// Counts the defects of `triangles` over nodes 0 .. node_count-1 (throws InternalError when a
/// triangle names a node out of range).
ModelDefects find_model_defects(const std::vector<std::array<NodeId, 3>>& triangles, std::int64_t node_count);

/// The mesh of `input`'s triangles cleaned as described at the top; `input.squares` are not
/// carried over (the model formats write triangles). Throws InternalError when the result still
/// has a defect (an edge of more than two triangles in the input is not repaired), NumericalError
/// when nothing is left.
class ModelMesh {
 public:
  explicit ModelMesh(const Mesh& input);

  /// The cleaned mesh (`input` itself when nothing had to be removed).
  [[nodiscard]] const Mesh& mesh() const { return owned_ ? *owned_ : input_; }
  [[nodiscard]] const CleaningStats& stats() const { return stats_; }
  /// Triangle of `input` each triangle of mesh() is (empty when nothing was removed).
  [[nodiscard]] const std::vector<ElementId>& source_triangle() const { return source_triangle_; }

  /// "n triangles with one neighbour removed in k rounds, p pinches removed (...)".
  [[nodiscard]] std::string describe() const;
  /// The "cleaning" report section.
  [[nodiscard]] Json json() const;

 private:
  const Mesh& input_;
  std::optional<Mesh> owned_;
  CleaningStats stats_;
  std::vector<ElementId> source_triangle_;
};

}  // namespace aq::mesh

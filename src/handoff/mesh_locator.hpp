// SPDX-License-Identifier: GPL-3.0-or-later
// Point location in a global mesh by its integer structure (ARCHITECTURE §3–4): no search over
// elements. A point (λ, φ) is mapped to the lattice system (pole rotation) and to fractional
// pixel coordinates (x, y); its pixel (⌊x⌋ mod nx, ⌊y⌋) lies in one level-0 square, whose leaves
// are contiguous in the mesh's square order (level-0 squares row-major, Morton inside), so the leaf
// holding the pixel is found by a binary search over at most 4^L Morton keys of that square —
// O(L) per point, independent of the mesh size. The leaf's template triangles (2 to 8) are then
// tested with barycentric coordinates in the lattice plane, with the nodes' λ seam-unwrapped
// (Mesh::unwrapped_i), and the triangle whose smallest weight is largest is taken.
//
//   pixel (i, j) -> root = (j >> L)·n0x + (i >> L) -> leaves [start[root], start[root+1])
//               -> last leaf with morton(SW offset) <= morton(i, j offset) -> contains (i, j)?
//               -> triangles [first[leaf], first[leaf+1]) -> barycentric weights
//
// A point on a pixel edge (within 1e-9 pixel) is tried in the pixels on both sides, so points on
// the coast or on a leaf boundary are found in whichever filled leaf touches them. Weights are in
// the lattice plane, where the elements are flat triangles: λ'_p = Σ w_k λ'_k and y_p = Σ w_k y_k
// with y the plane ordinate of a row (Lattice::plane_y: φ' on the lon-lat lattice, the Mercator
// ordinate ln tan(π/4 + φ'/2) on the Mercator one, where φ' itself is not linear inside an
// element) and λ' of the nodes unwrapped as the element is drawn; the tests check this to 1e-9°
// on both lattices. Weights are in [0, 1] and sum to 1: a point
// on an element's edge (within 1e-9 in weight) gets the tiny negative weights of rounding
// clamped to 0 and the rest renormalised.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/rotation.hpp"
#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace aq::handoff {

/// Where a point lies in the mesh.
struct MeshLocation {
  ElementId triangle = -1;                       ///< 0-based triangle, -1 when outside the mesh
  std::array<NodeId, 3> nodes{-1, -1, -1};       ///< the triangle's nodes (anticlockwise)
  std::array<double, 3> weights{0.0, 0.0, 0.0};  ///< barycentric weights of `nodes`, sum 1
  ElementId square = -1;                         ///< the quadtree leaf (mesh square) holding it
  int level = -1;                                ///< its level
  double lattice_lon_deg = 0.0;                  ///< the point in the lattice system, λ' as used for the
  double lattice_lat_deg = 0.0;                  ///<   weights (unwrapped to the element's nodes)
  double lattice_row = 0.0;                      ///< its fractional row (Lattice::lat_of_row gives φ')
  [[nodiscard]] bool inside() const { return triangle >= 0; }
};

class MeshLocator {
 public:
  /// Keeps a reference to `mesh` (must outlive the locator). Throws InternalError when the mesh has
  /// no triangles or its squares are not in the deterministic leaf order.
  explicit MeshLocator(const mesh::Mesh& mesh);

  /// Locates a geographic point (degrees; any longitude, |lat| <= 90).
  [[nodiscard]] MeshLocation locate_geographic(double lon_deg, double lat_deg) const;
  /// Locates a point given in the lattice system (rotated degrees).
  [[nodiscard]] MeshLocation locate_lattice(double rlon_deg, double rlat_deg) const;
  /// The mesh square holding pixel (i mod nx, j), or -1 (j outside [0, ny) or not filled).
  [[nodiscard]] ElementId find_square(std::int64_t i, std::int64_t j) const;

 private:
  const mesh::Mesh& mesh_;
  PoleRotation rotation_;
  std::int64_t n0x_ = 0, root_shift_ = 0;
  std::vector<std::int64_t> root_start_;      ///< first square of each level-0 square (+1 entry)
  std::vector<std::uint64_t> morton_;         ///< Morton key of each square's SW pixel offset
  std::vector<std::int64_t> first_triangle_;  ///< first triangle of each square (+1 entry)
};

}  // namespace aq::handoff

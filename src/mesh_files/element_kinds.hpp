// SPDX-License-Identifier: GPL-3.0-or-later
// Which elements of a Mesh a writer writes (mesh.elements: triangles, squares or both),
// and the polygon view of a square with its hanging (midside) nodes.
//
// A quadtree leaf is a square with corners SW, SE, NE, NW (anticlockwise) and an optional
// midside node on each side (S, E, N, W). As a polygon, the midside nodes are inserted between
// the corners they split, which makes the square mesh conforming:
//
//     NW ---- mN ---- NE
//     |                |        polygon: SW, mS, SE, mE, NE, mN, NW, mW
//     mW              mE        (absent midside nodes are skipped: 4..8 nodes)
//     |                |
//     SW ---- mS ---- SE
#pragma once

#include <array>
#include <string_view>

#include "config/kinds.hpp"
#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace aq::io {

/// mesh.elements (config/kinds.hpp), the one enum the mesh stage and the writers share.
using config::ElementKinds;
using config::has_squares;
using config::has_triangles;
/// Triangles when the mesh has any, squares otherwise.
ElementKinds default_element_kinds(const mesh::Mesh& mesh);
/// Throws InternalError when `kinds` asks for triangles the mesh does not have (the mesh was
/// built with mesh.elements = "squares") or when the per-element arrays have wrong sizes.
void check_elements(const mesh::Mesh& mesh, ElementKinds kinds);

/// Maximum number of nodes of a square polygon (4 corners + 4 midside nodes).
inline constexpr int kMaxSquarePolygon = 8;

/// Writes the polygon of square `s` (corners and midside nodes, anticlockwise from SW) into
/// `out`; returns its node count (4..8; 3..7 for a square of a geographic mesh with a merged pole
/// row, whose repeated pole node is written once).
inline int square_polygon(const mesh::Mesh& mesh, ElementId s, std::array<NodeId, kMaxSquarePolygon>& out) {
  const auto& c = mesh.squares[s];
  const bool has_mid = !mesh.square_midside.empty();
  int k = 0;
  auto add = [&](NodeId n) {
    if (k == 0 || out[k - 1] != n) out[k++] = n;
  };
  for (int side = 0; side < 4; ++side) {
    add(c[side]);
    if (has_mid) {
      const NodeId m = mesh.square_midside[s][side];
      if (m >= 0) add(m);
    }
  }
  while (k > 1 && out[k - 1] == out[0]) --k;
  return k;
}

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// The gradient limit of the size field, |∇h| <= g on the sphere (Persson 2006; OceanMesh2D's and
// JIGSAW's `marche` solve the same Hamilton–Jacobi problem). Its solution is
//
//     h′(x) = min over cells s of ( h(s) + g · dist(s, x) ),    dist: great circle on the sphere
//
// computed here by nearest-source propagation (Danielsson's vector distance transform with
// additive weights): every cell carries the source s that gives its value and hands it to its
// neighbours in raster sweeps (down then up the rows; inside a row, from the row beyond in
// parallel, then left-to-right and right-to-left round the periodic row), repeated until nothing
// changes. Each value is h(s) + g·dist(s, x) for a real source with the exact distance, so
// h′ >= the exact minimum, and it equals it except where a weighted Voronoi region is thinner
// than a cell, where a cell may keep a neighbour's source: measured within 1% of g × the cell size
// (tests against the brute-force minimum on the plane, across the seam, over the pole and in the
// rotated frame). On the lon-lat lattice the first and last rows also see the cell across the
// pole. Deterministic for any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "size/field_grid.hpp"

namespace aq::size {

/// Replaces `h` (km per cell, +inf = no constraint) by min_s(h(s) + g·dist_km(s, x)); g >= 0.
/// When `source` is given it receives, per cell, the index of the cell whose value won (-1 where
/// every value is +inf). `h.size()` must equal grid.cells(). Returns the sweeps made.
int limit_gradient(const FieldGrid& grid, std::vector<double>& h, double g, std::vector<std::int32_t>* source = nullptr);

/// Distance (km) from every cell to the nearest cell with `is_source` set (+inf without any), by
/// the same propagation; `source` as above.
std::vector<double> distance_to(const FieldGrid& grid, const std::vector<std::uint8_t>& is_source,
                                std::vector<std::int32_t>* source = nullptr);

}  // namespace aq::size

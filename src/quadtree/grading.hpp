// SPDX-License-Identifier: GPL-3.0-or-later
// The achieved grading of a leaf set: how fast the element size grows. Along every row and column
// of a level map (the finest leaf level per level-c square), a run of n squares of one level v
// between a finer and a coarser neighbour level spans a distance D = n·(side of a level-c square);
// a size field with |∇h| = g keeps level v (sizes within √2 of h) over D = a/(√2·g), a the level-v
// square's size, so the run's grading is a/(√2·D). The 2:1 balance alone gives runs of one square
// (D = a): 0.71. Runs of levels >= c are below the map's resolution and not measured; the quadtree
// stage uses the finest map of at most 2^25 cells.
#pragma once

#include <cstdint>
#include <vector>

#include "core/lattice.hpp"
#include "quadtree/leaves.hpp"

namespace aq::quadtree {

struct Grading {
  int map_level = 0;
  std::int64_t runs = 0;                 ///< monotone runs measured
  double median = 0.0, p90 = 0.0, max = 0.0;
};

/// The grading of `leaves` on the level-`map_level` map (0 <= map_level <= L).
Grading achieved_grading(const std::vector<Leaf>& leaves, const Lattice& lat, int map_level);

}  // namespace aq::quadtree

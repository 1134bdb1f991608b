// SPDX-License-Identifier: GPL-3.0-or-later
// The quadtree level of every lattice pixel, painted from the leaves a band of rows at a time
// (for the global run file, mask/global_run_file.hpp): leaves are bucketed once by the bands of
// kLevelBandRows rows they touch, so a band costs the leaves that touch it, not all of them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/lattice.hpp"
#include "quadtree/leaves.hpp"

namespace aq::quadtree {

class LeafLevels {
 public:
  static constexpr std::int64_t kLevelBandRows = 256;

  /// Keeps a reference to `leaves` (they must outlive this object).
  LeafLevels(const std::vector<Leaf>& leaves, const Lattice& lattice);

  /// out[(j − j0)·nx + i] = level of the leaf holding pixel (i, j) for j0 <= j < j0 + rows, and
  /// `empty` where no leaf is. Preconditions: 0 <= j0, j0 + rows <= ny.
  void fill(std::int64_t j0, std::int64_t rows, std::uint8_t* out, std::uint8_t empty = 255) const;

 private:
  const std::vector<Leaf>& leaves_;
  Lattice lattice_;
  std::vector<std::int64_t> start_;  ///< leaves of band k: order_[start_[k] .. start_[k+1])
  std::vector<std::int64_t> order_;
};

}  // namespace aq::quadtree

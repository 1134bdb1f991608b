// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel levels from quadtree leaves (see leaf_levels.hpp).
#include "quadtree/leaf_levels.hpp"

#include <algorithm>

namespace aq::quadtree {

LeafLevels::LeafLevels(const std::vector<Leaf>& leaves, const Lattice& lattice) : leaves_(leaves), lattice_(lattice) {
  const std::int64_t bands = (lattice.ny + kLevelBandRows - 1) / kLevelBandRows;
  std::vector<std::int64_t> count(static_cast<std::size_t>(bands) + 1, 0);
  const auto band_range = [&](const Leaf& f) {
    const std::int64_t j0 = leaf_j0(lattice, f), s = leaf_size(lattice, f);
    return std::pair<std::int64_t, std::int64_t>{j0 / kLevelBandRows, (j0 + s - 1) / kLevelBandRows};
  };
  for (const Leaf& f : leaves) {
    const auto [b0, b1] = band_range(f);
    for (std::int64_t b = b0; b <= b1; ++b) ++count[static_cast<std::size_t>(b) + 1];
  }
  start_.assign(count.size(), 0);
  for (std::size_t b = 1; b < count.size(); ++b) start_[b] = start_[b - 1] + count[b];
  order_.assign(static_cast<std::size_t>(start_.back()), 0);
  std::vector<std::int64_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const auto [b0, b1] = band_range(leaves[k]);
    for (std::int64_t b = b0; b <= b1; ++b)
      order_[static_cast<std::size_t>(next[static_cast<std::size_t>(b)]++)] = static_cast<std::int64_t>(k);
  }
}

void LeafLevels::fill(std::int64_t j0, std::int64_t rows, std::uint8_t* out, std::uint8_t empty) const {
  const std::int64_t nx = lattice_.nx;
  std::fill_n(out, rows * nx, empty);
  if (rows <= 0) return;
  const std::int64_t b0 = j0 / kLevelBandRows, b1 = (j0 + rows - 1) / kLevelBandRows;
  for (std::int64_t b = b0; b <= b1; ++b) {
    for (std::int64_t k = start_[static_cast<std::size_t>(b)]; k < start_[static_cast<std::size_t>(b) + 1]; ++k) {
      const Leaf& f = leaves_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])];
      const std::int64_t s = leaf_size(lattice_, f), i0 = leaf_i0(lattice_, f), lj = leaf_j0(lattice_, f);
      const std::int64_t ja = std::max(lj, j0), jb = std::min(lj + s, j0 + rows);
      for (std::int64_t j = ja; j < jb; ++j)
        std::fill_n(out + (j - j0) * nx + i0, s, static_cast<std::uint8_t>(f.level));
    }
  }
}

}  // namespace aq::quadtree

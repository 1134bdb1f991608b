// SPDX-License-Identifier: GPL-3.0-or-later
// 2:1 balance on the bitmap pyramid and its checker (see balance.hpp).
#include "quadtree/balance.hpp"

#include <fmt/format.h>

#include <array>
#include <bit>

#include "core/error.hpp"
#include "quadtree/bits.hpp"
#include "quadtree/parallel.hpp"

namespace aq::quadtree {

namespace {

using Words = std::vector<std::uint64_t>;

/// Row q of the level-k leaves: omega[k] & ~(omega[k-1] expanded); zero outside 0 <= q < rows.
void leaf_row(const Bitmap& fine, const Bitmap& parent, std::int64_t q, std::uint64_t* out) {
  const std::int64_t words = fine.words_per_row();
  if (q < 0 || q >= fine.ny()) {
    std::fill(out, out + words, 0ULL);
    return;
  }
  bits::expand_row(parent.row(q / 2), out, words);
  const std::uint64_t* f = fine.row(q);
  for (std::int64_t w = 0; w < words; ++w) out[w] = f[w] & ~out[w];
}

/// out = in | in rotated by +1 | in rotated by -1 (horizontal dilation by one, periodic).
void hdilate1(const std::uint64_t* in, std::uint64_t* out, std::uint64_t* tmp, std::int64_t n) {
  const std::int64_t words = (n + 63) / 64;
  std::copy(in, in + words, out);
  bits::rotate_row(in, tmp, n, 1);
  for (std::int64_t w = 0; w < words; ++w) out[w] |= tmp[w];
  bits::rotate_row(in, tmp, n, -1);
  for (std::int64_t w = 0; w < words; ++w) out[w] |= tmp[w];
}

void restore_monotone(LevelMasks& m, int from_level) {
  for (int l = from_level; l >= 0; --l) {
    Bitmap& om = m.omega[static_cast<std::size_t>(l)];
    const Bitmap fine = bits::reduce(m.omega[static_cast<std::size_t>(l) + 1], false);
    for (std::size_t k = 0; k < om.words().size(); ++k) om.words()[k] &= fine.words()[k];
  }
}

}  // namespace

BalanceStats balance(LevelMasks& m, BalanceMode mode) {
  BalanceStats stats;
  const int levels = m.levels();
  const bool corner = mode == BalanceMode::kCorner;
  for (int k = levels; k >= 2; --k) {
    const Bitmap& fine = m.omega[static_cast<std::size_t>(k)];
    const Bitmap& parent = m.omega[static_cast<std::size_t>(k) - 1];
    Bitmap& target = m.omega[static_cast<std::size_t>(k) - 2];
    const std::int64_t n = fine.nx();
    const std::int64_t words = fine.words_per_row();
    const std::int64_t words1 = parent.words_per_row();
    const std::int64_t rows2 = target.ny();
    const std::int64_t words2 = target.words_per_row();
    std::int64_t cleared = 0;
#pragma omp parallel default(none) if (quadtree::parallel_worth(rows2 * words * 8)) shared(fine, parent, target, n, words, words1, rows2, words2, corner) \
    reduction(+ : cleared)
    {
      const auto ws = static_cast<std::size_t>(words);
      Words leaf(6 * ws), hor(6 * ws), d(4 * ws), tmp(ws), mid(2 * static_cast<std::size_t>(words1)),
          g(static_cast<std::size_t>(words2));
#pragma omp for schedule(static)
      for (std::int64_t c = 0; c < rows2; ++c) {
        // Level-k rows 4c-1 .. 4c+4 of leaves (index r = 0..5), dilated along the row.
        for (std::int64_t r = 0; r < 6; ++r) {
          leaf_row(fine, parent, 4 * c - 1 + r, &leaf[static_cast<std::size_t>(r) * ws]);
          hdilate1(&leaf[static_cast<std::size_t>(r) * ws], &hor[static_cast<std::size_t>(r) * ws], tmp.data(), n);
        }
        // Stencil image rows 4c .. 4c+3.
        for (std::size_t r = 1; r <= 4; ++r) {
          const Words& side = corner ? hor : leaf;
          for (std::size_t w = 0; w < ws; ++w) {
            d[(r - 1) * ws + w] = side[(r - 1) * ws + w] | hor[r * ws + w] | side[(r + 1) * ws + w];
          }
        }
        bits::reduce_rows(&d[0], &d[ws], words, &mid[0], true);
        bits::reduce_rows(&d[2 * ws], &d[3 * ws], words, &mid[static_cast<std::size_t>(words1)], true);
        bits::reduce_rows(&mid[0], &mid[static_cast<std::size_t>(words1)], words1, g.data(), true);
        std::uint64_t* t = target.row(c);
        for (std::int64_t w = 0; w < words2; ++w) {
          cleared += bits::popcount64(t[w] & g[static_cast<std::size_t>(w)]);
          t[w] &= ~g[static_cast<std::size_t>(w)];
        }
      }
    }
    if (cleared > 0) {
      stats.forced_splits += cleared;
      ++stats.levels_changed;
      restore_monotone(m, k - 3);
    }
  }
  return stats;
}

std::int64_t count_balance_violations(const LevelMasks& m, BalanceMode mode) {
  const int levels = m.levels();
  const bool corner = mode == BalanceMode::kCorner;
  std::int64_t total = 0;
  for (int k = 2; k <= levels; ++k) {
    const Bitmap& fine = m.omega[static_cast<std::size_t>(k)];
    const Bitmap& parent = m.omega[static_cast<std::size_t>(k) - 1];
    const Bitmap& coarse = m.omega[static_cast<std::size_t>(k) - 2];
    const std::int64_t n = fine.nx();
    const std::int64_t rows = fine.ny();
    const std::int64_t words = fine.words_per_row();
    const std::int64_t words1 = parent.words_per_row();
    std::int64_t count = 0;
#pragma omp parallel default(none) if (quadtree::parallel_worth(rows * words * 8)) shared(fine, parent, coarse, n, rows, words, words1, corner) reduction(+ : count)
    {
      const auto ws = static_cast<std::size_t>(words);
      Words leaf(3 * ws), up(ws), up1(static_cast<std::size_t>(words1)), rot(ws);
#pragma omp for schedule(static)
      for (std::int64_t b = 0; b < rows; ++b) {
        // Square N = (a, b) lies inside a leaf of level <= k-2: its grandparent is in omega[k-2].
        bits::expand_row(coarse.row(b / 4), up1.data(), words1);
        bits::expand_row(up1.data(), up.data(), words);
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          leaf_row(fine, parent, b - dy, &leaf[static_cast<std::size_t>(dy + 1) * ws]);
        }
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            if (!corner && dx != 0 && dy != 0) continue;
            // B = N - (dx, dy) is a leaf of level k: row b - dy, column a - dx.
            bits::rotate_row(&leaf[static_cast<std::size_t>(dy + 1) * ws], rot.data(), n, dx);
            for (std::size_t w = 0; w < ws; ++w) count += bits::popcount64(rot[w] & up[w]);
          }
        }
      }
    }
    total += count;
  }
  return total;
}

std::int64_t count_balance_violations(const std::vector<Leaf>& leaves, const Lattice& lat, BalanceMode mode) {
  return count_balance_violations(masks_from_leaves(leaves, lat), mode);
}

std::vector<Leaf> balance_leaves(const std::vector<Leaf>& leaves, const Lattice& lat, BalanceMode mode) {
  LevelMasks m = masks_from_leaves(leaves, lat);
  balance(m, mode);
  return extract_leaves(m, lat);
}

}  // namespace aq::quadtree

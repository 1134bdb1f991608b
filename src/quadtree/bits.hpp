// SPDX-License-Identifier: GPL-3.0-or-later
// Word tricks on bitmap rows for the quadtree stage (seed 002 §"построение покрытия"; ARCHITECTURE
// §4.4: "a level pyramid of bitmaps gives this in O(N)"). In the spirit of p4est's `bits`: small
// branch-free helpers that the level pyramid, the coastal band, the 2:1 balance and the node
// bitmap share, so that each algorithm reads as whole-row operations.
//
// Row layout is the one of aq::Bitmap: bit i of a row of n bits is bit (i & 63) of word i >> 6,
// padding bits past n are kept clear. Rows are periodic in i where a function says so (the λ seam):
//
//     i:   0 1 2 ... n-1 | 0 1 ...      rotate_row(in, out, n, +1):  out[i] = in[(i - 1) mod n]
//
// Two levels of the pyramid relate by halving: square (a, b) of level l has the children
// (2a, 2b) SW, (2a+1, 2b) SE, (2a, 2b+1) NW, (2a+1, 2b+1) NE at level l+1 (Morton / z order,
// the x bit lowest), so a word of a parent row covers two words of each of two child rows.
#pragma once

#include <cstdint>

#include "core/bitmap.hpp"

namespace aq::quadtree::bits {

/// Keeps bits 0, 2, ..., 62 of x, packed into the low 32 bits (bit 2k -> bit k).
constexpr std::uint64_t compact_even(std::uint64_t x) {
  x &= 0x5555555555555555ULL;
  x = (x | (x >> 1)) & 0x3333333333333333ULL;
  x = (x | (x >> 2)) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | (x >> 4)) & 0x00ff00ff00ff00ffULL;
  x = (x | (x >> 8)) & 0x0000ffff0000ffffULL;
  x = (x | (x >> 16)) & 0x00000000ffffffffULL;
  return x;
}

/// Spreads the low 32 bits of x to the even positions (bit k -> bit 2k); inverse of compact_even.
constexpr std::uint64_t spread_even(std::uint64_t x) {
  x &= 0x00000000ffffffffULL;
  x = (x | (x << 16)) & 0x0000ffff0000ffffULL;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffULL;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | (x << 2)) & 0x3333333333333333ULL;
  x = (x | (x << 1)) & 0x5555555555555555ULL;
  return x;
}

/// Number of set bits (core/bitmap.hpp).
using aq::popcount64;

/// Morton (z-order) key of (i, j), i, j < 2^32: bit k of i -> bit 2k, bit k of j -> bit 2k+1.
constexpr std::uint64_t morton(std::uint64_t i, std::uint64_t j) { return spread_even(i) | (spread_even(j) << 1); }

/// Mask of the valid bits of the last word of a row of n >= 1 bits.
constexpr std::uint64_t last_word_mask(std::int64_t n) {
  const int r = static_cast<int>(n & 63);
  return r == 0 ? ~0ULL : ((1ULL << r) - 1ULL);
}

/// 64 consecutive bits of a periodic row of n >= 1 bits, starting at bit p (0 <= p < n):
/// result bit t = row bit (p + t) mod n.
std::uint64_t periodic_window(const std::uint64_t* row, std::int64_t n, std::int64_t p);

/// out = in rotated by s (any sign) on a periodic row of n bits: out[i] = in[(i - s) mod n].
/// `out` must not alias `in`. Padding bits of `out` are cleared.
void rotate_row(const std::uint64_t* in, std::uint64_t* out, std::int64_t n, std::int64_t s);

/// Dilation of a periodic row by radius r >= 0 (out[i] = OR of in[i-r .. i+r], indices mod n),
/// in O(log r) rotations. `tmp` must hold words_per_row words; none of the three may alias.
void dilate_row(const std::uint64_t* in, std::uint64_t* out, std::uint64_t* tmp, std::int64_t n, std::int64_t r);

/// Sets bits [x0, x1) of a row (0 <= x0 <= x1 <= row length; no wrap).
void set_range(std::uint64_t* row, std::int64_t x0, std::int64_t x1);

/// Parent row from two child rows of a pyramid: bit a of `out` = AND (or OR when `use_or`) of the
/// 2×2 children bits (2a, 2a+1) of `lo` and `hi`. `child_words` is the words per child row;
/// `out` gets (child_words + 1) / 2 words.
void reduce_rows(const std::uint64_t* lo, const std::uint64_t* hi, std::int64_t child_words, std::uint64_t* out,
                 bool use_or);

/// Level l-1 bitmap from level l: AND of the 4 children ("all filled") or OR ("any filled").
/// Requires even nx and ny. Parallel over rows.
Bitmap reduce(const Bitmap& fine, bool use_or);

/// Level l+1 row from the parent row: child bit i = parent bit i / 2. `child_words` words written.
void expand_row(const std::uint64_t* parent, std::uint64_t* child, std::int64_t child_words);

/// Number of set bits of `a & ~b` over whole bitmaps of equal shape.
std::int64_t count_and_not(const Bitmap& a, const Bitmap& b);

}  // namespace aq::quadtree::bits

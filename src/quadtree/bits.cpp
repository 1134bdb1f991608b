// SPDX-License-Identifier: GPL-3.0-or-later
// Word tricks on bitmap rows (see bits.hpp).
#include "quadtree/bits.hpp"

#include <algorithm>
#include <bit>
#include <vector>

#include "core/types.hpp"
#include "quadtree/parallel.hpp"

namespace aq::quadtree::bits {

namespace {

/// Bits [p, p + take) of a row, 1 <= take <= 64, p + take <= row length.
std::uint64_t get_bits(const std::uint64_t* row, std::int64_t p, std::int64_t take) {
  const std::int64_t k = p >> 6;
  const int off = static_cast<int>(p & 63);
  std::uint64_t v = row[k] >> off;
  if (off + take > 64) v |= row[k + 1] << (64 - off);
  if (take < 64) v &= (1ULL << take) - 1ULL;
  return v;
}

}  // namespace

std::uint64_t periodic_window(const std::uint64_t* row, std::int64_t n, std::int64_t p) {
  if (p + 64 <= n) {
    const std::int64_t k = p >> 6;
    const int off = static_cast<int>(p & 63);
    if (off == 0) return row[k];
    return (row[k] >> off) | (row[k + 1] << (64 - off));
  }
  std::uint64_t out = 0;
  std::int64_t filled = 0;
  while (filled < 64) {
    const std::int64_t take = std::min<std::int64_t>(64 - filled, n - p);
    out |= get_bits(row, p, take) << filled;
    filled += take;
    p += take;
    if (p == n) p = 0;
  }
  return out;
}

void rotate_row(const std::uint64_t* in, std::uint64_t* out, std::int64_t n, std::int64_t s) {
  const std::int64_t words = (n + 63) / 64;
  std::int64_t start = wrap_index(-s, n);
  for (std::int64_t w = 0; w < words;) {
    // The output words whose 64 bits lie inside the row without wrapping, in one loop of shifts
    // (periodic_window's first case); the one or two that wrap through periodic_window.
    const std::int64_t m = std::min(words - w, (n - start) / 64);
    if (m > 0) {
      const std::int64_t k = start >> 6;
      const int off = static_cast<int>(start & 63);
      if (off == 0) {
        std::copy(in + k, in + k + m, out + w);
      } else {
        for (std::int64_t i = 0; i < m; ++i) out[w + i] = (in[k + i] >> off) | (in[k + i + 1] << (64 - off));
      }
      w += m;
      start += 64 * m;
      if (start >= n) start -= n;
      continue;
    }
    out[w] = periodic_window(in, n, start);
    start = wrap_index(start + 64, n);
    ++w;
  }
  out[words - 1] &= last_word_mask(n);
}

void dilate_row(const std::uint64_t* in, std::uint64_t* out, std::uint64_t* tmp, std::int64_t n, std::int64_t r) {
  const std::int64_t words = (n + 63) / 64;
  std::copy(in, in + words, out);
  // One-sided dilations by doubling: after `c` covered, out[i] = OR in[i-c .. i]; OR-ing the
  // row rotated by c+1 covers 2c+1. Then the same towards the other side.
  for (const std::int64_t sign : {std::int64_t{1}, std::int64_t{-1}}) {
    std::int64_t c = 0;
    while (c < r) {
      const std::int64_t step = std::min(c + 1, r - c);
      rotate_row(out, tmp, n, sign * step);
      for (std::int64_t w = 0; w < words; ++w) out[w] |= tmp[w];
      c += step;
    }
  }
}

void set_range(std::uint64_t* row, std::int64_t x0, std::int64_t x1) {
  if (x0 >= x1) return;
  const std::int64_t w0 = x0 >> 6;
  const std::int64_t w1 = (x1 - 1) >> 6;
  const std::uint64_t m0 = ~0ULL << (x0 & 63);
  const std::uint64_t m1 = last_word_mask(x1);
  if (w0 == w1) {
    row[w0] |= m0 & m1;
    return;
  }
  row[w0] |= m0;
  for (std::int64_t w = w0 + 1; w < w1; ++w) row[w] = ~0ULL;
  row[w1] |= m1;
}

void reduce_rows(const std::uint64_t* lo, const std::uint64_t* hi, std::int64_t child_words, std::uint64_t* out,
                 bool use_or) {
  const std::int64_t out_words = (child_words + 1) / 2;
  for (std::int64_t w = 0; w < out_words; ++w) {
    std::uint64_t half[2] = {0, 0};
    for (int h = 0; h < 2; ++h) {
      const std::int64_t cw = 2 * w + h;
      if (cw >= child_words) break;
      const std::uint64_t x = use_or ? (lo[cw] | hi[cw]) : (lo[cw] & hi[cw]);
      // Words of open sea or land (most of a row) are all 0 or all 1: no compaction needed.
      if (x == 0 || x == ~0ULL) {
        half[h] = x & 0xffffffffULL;
        continue;
      }
      half[h] = compact_even(use_or ? (x | (x >> 1)) : (x & (x >> 1)));
    }
    out[w] = half[0] | (half[1] << 32);
  }
}

Bitmap reduce(const Bitmap& fine, bool use_or) {
  Bitmap coarse(fine.nx() / 2, fine.ny() / 2);
  const std::int64_t rows = coarse.ny();
  const std::int64_t child_words = fine.words_per_row();
#pragma omp parallel for default(none) if (quadtree::parallel_worth(rows * child_words * 2)) \
    shared(fine, coarse, rows, child_words, use_or) schedule(static)
  for (std::int64_t b = 0; b < rows; ++b) {
    reduce_rows(fine.row(2 * b), fine.row(2 * b + 1), child_words, coarse.row(b), use_or);
  }
  return coarse;
}

void expand_row(const std::uint64_t* parent, std::uint64_t* child, std::int64_t child_words) {
  for (std::int64_t w = 0; w < child_words; ++w) {
    const std::uint64_t half = (parent[w >> 1] >> (32 * (w & 1))) & 0xffffffffULL;
    // Half-words of open sea or land (most of a row) are all 0 or all 1: no spreading needed.
    if (half == 0 || half == 0xffffffffULL) {
      child[w] = half == 0 ? 0 : ~0ULL;
      continue;
    }
    const std::uint64_t s = spread_even(half);
    child[w] = s | (s << 1);
  }
}

std::int64_t count_and_not(const Bitmap& a, const Bitmap& b) {
  const std::vector<std::uint64_t>& wa = a.words();
  const std::vector<std::uint64_t>& wb = b.words();
  const auto n = static_cast<std::int64_t>(wa.size());
  std::int64_t total = 0;
#pragma omp parallel for default(none) if (quadtree::parallel_worth(n)) shared(wa, wb, n) reduction(+ : total) schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    total += popcount64(wa[static_cast<std::size_t>(k)] & ~wb[static_cast<std::size_t>(k)]);
  }
  return total;
}

}  // namespace aq::quadtree::bits

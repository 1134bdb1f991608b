// SPDX-License-Identifier: GPL-3.0-or-later
// Word-parallel primitives on one bitmap row (aq::Bitmap layout: bit i of the row is bit (i & 63)
// of word i >> 6; bits at and beyond the row length n are padding and stay clear). They serve
// the K-cursor fill of seed 002 (§4.3 of ARCHITECTURE.md): periodic window AND/OR along λ,
// run search for the span flood fill, range set/clear/count.
//
// Ranges are half-open [a, b) with 0 <= a <= b <= n. "Rotations" are periodic in the row length
// n (the λ seam): rotate(src, s)(i) = src((i + s) mod n).
//
//   word:      0                     1
//   bit i:     0 1 2 ... 63 | 64 65 ... 127 | ...        (bit 0 = westernmost pixel of the row)
#pragma once

#include <cstdint>

namespace aq::mask::bits {

/// Mask with the `n` low bits set, 0 <= n <= 64.
[[nodiscard]] constexpr std::uint64_t low_mask(int n) {
  return n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
}

/// The `n` bits (1 <= n <= 64) starting at bit `pos`, in the low bits of the result. Reads only
/// the words that hold them.
[[nodiscard]] std::uint64_t read_bits(const std::uint64_t* row, std::int64_t pos, int n);

/// Overwrites the `n` bits (1 <= n <= 64) starting at bit `pos` with the low bits of `v`.
void write_bits(std::uint64_t* row, std::int64_t pos, std::uint64_t v, int n);

/// First set bit in [a, b), or b if none.
[[nodiscard]] std::int64_t find_first_set(const std::uint64_t* row, std::int64_t a, std::int64_t b);
/// First clear bit in [a, b), or b if none.
[[nodiscard]] std::int64_t find_first_clear(const std::uint64_t* row, std::int64_t a, std::int64_t b);
/// Last clear bit in [a, b), or a - 1 if none.
[[nodiscard]] std::int64_t find_last_clear(const std::uint64_t* row, std::int64_t a, std::int64_t b);

/// Sets / clears all bits in [a, b).
void set_range(std::uint64_t* row, std::int64_t a, std::int64_t b);
void clear_range(std::uint64_t* row, std::int64_t a, std::int64_t b);
/// Number of set bits in [a, b).
[[nodiscard]] std::int64_t count_range(const std::uint64_t* row, std::int64_t a, std::int64_t b);
/// Number of bits in [a, b) set in both rows.
[[nodiscard]] std::int64_t count_range_and(const std::uint64_t* x, const std::uint64_t* y, std::int64_t a,
                                           std::int64_t b);

enum class Combine { kCopy, kAnd, kOr };

/// dst(i) = src((i + shift) mod n)  combined into dst by `op` (copy, AND or OR), for 0 <= i < n.
/// `shift` may be any integer (reduced mod n). src and dst must not overlap. Padding stays clear.
void rotate_row(const std::uint64_t* src, std::uint64_t* dst, std::int64_t n, std::int64_t shift, Combine op);

/// out bit k = (values[k] <= threshold, compared as doubles) for 0 <= k < n; NaN compares false
/// (clear). Writes words_for(n) words; padding bits are cleared. The float version compares in
/// float against float_threshold(threshold), four values at a time (SSE2): the same bits.
void threshold_row(const float* values, std::int64_t n, double threshold, std::uint64_t* out);
void threshold_row(const double* values, std::int64_t n, double threshold, std::uint64_t* out);

/// The largest float f with (double)f <= t (-inf when none is finite, NaN for NaN t): for every
/// float x, x <= f exactly when (double)x <= t.
[[nodiscard]] float float_threshold(double t);

/// Bitmaps smaller than this many words are processed by one thread: starting a parallel region
/// costs more than the work (and much more when the cores are shared).
inline constexpr std::int64_t kParallelMinWords = std::int64_t{1} << 14;

/// Number of 64-bit words of a row of n bits.
[[nodiscard]] constexpr std::int64_t words_for(std::int64_t n) { return (n + 63) >> 6; }

}  // namespace aq::mask::bits

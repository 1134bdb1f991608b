// SPDX-License-Identifier: GPL-3.0-or-later
// Word-parallel bitmap row primitives (see bit_rows.hpp).
#include "mask/bit_rows.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/bitmap.hpp"

namespace aq::mask::bits {

namespace {
constexpr std::int64_t word_of(std::int64_t i) { return i >> 6; }
constexpr int bit_of(std::int64_t i) { return static_cast<int>(i & 63); }
// Bits [lo, 64) of a word, lo in [0, 64).
constexpr std::uint64_t from_bit(int lo) { return ~std::uint64_t{0} << lo; }
}  // namespace

std::uint64_t read_bits(const std::uint64_t* row, std::int64_t pos, int n) {
  const std::int64_t w = word_of(pos);
  const int o = bit_of(pos);
  std::uint64_t v = row[w] >> o;
  if (o + n > 64) v |= row[w + 1] << (64 - o);
  return v & low_mask(n);
}

void write_bits(std::uint64_t* row, std::int64_t pos, std::uint64_t v, int n) {
  const std::int64_t w = word_of(pos);
  const int o = bit_of(pos);
  const std::uint64_t m = low_mask(n);
  v &= m;
  row[w] = (row[w] & ~(m << o)) | (v << o);
  if (o + n > 64) {
    const int hi = o + n - 64;  // bits that spill into the next word
    const std::uint64_t mh = low_mask(hi);
    row[w + 1] = (row[w + 1] & ~mh) | (v >> (64 - o));
  }
}

std::int64_t find_first_set(const std::uint64_t* row, std::int64_t a, std::int64_t b) {
  if (a >= b) return b;
  std::int64_t w = word_of(a);
  const std::int64_t wl = word_of(b - 1);
  std::uint64_t x = row[w] & from_bit(bit_of(a));
  while (true) {
    if (x != 0) {
      const std::int64_t p = (w << 6) + std::countr_zero(x);
      return p < b ? p : b;
    }
    if (++w > wl) return b;
    x = row[w];
  }
}

std::int64_t find_first_clear(const std::uint64_t* row, std::int64_t a, std::int64_t b) {
  if (a >= b) return b;
  std::int64_t w = word_of(a);
  const std::int64_t wl = word_of(b - 1);
  std::uint64_t x = ~row[w] & from_bit(bit_of(a));
  while (true) {
    if (x != 0) {
      const std::int64_t p = (w << 6) + std::countr_zero(x);
      return p < b ? p : b;
    }
    if (++w > wl) return b;
    x = ~row[w];
  }
}

std::int64_t find_last_clear(const std::uint64_t* row, std::int64_t a, std::int64_t b) {
  if (a >= b) return a - 1;
  std::int64_t w = word_of(b - 1);
  const std::int64_t wf = word_of(a);
  std::uint64_t x = ~row[w] & low_mask(bit_of(b - 1) + 1);
  while (true) {
    if (x != 0) {
      const std::int64_t p = (w << 6) + 63 - std::countl_zero(x);
      return p >= a ? p : a - 1;
    }
    if (--w < wf) return a - 1;
    x = ~row[w];
  }
}

void set_range(std::uint64_t* row, std::int64_t a, std::int64_t b) {
  if (a >= b) return;
  const std::int64_t wa = word_of(a), wb = word_of(b - 1);
  const std::uint64_t ma = from_bit(bit_of(a));
  const std::uint64_t mb = low_mask(bit_of(b - 1) + 1);
  if (wa == wb) {
    row[wa] |= ma & mb;
    return;
  }
  row[wa] |= ma;
  for (std::int64_t w = wa + 1; w < wb; ++w) row[w] = ~std::uint64_t{0};
  row[wb] |= mb;
}

void clear_range(std::uint64_t* row, std::int64_t a, std::int64_t b) {
  if (a >= b) return;
  const std::int64_t wa = word_of(a), wb = word_of(b - 1);
  const std::uint64_t ma = from_bit(bit_of(a));
  const std::uint64_t mb = low_mask(bit_of(b - 1) + 1);
  if (wa == wb) {
    row[wa] &= ~(ma & mb);
    return;
  }
  row[wa] &= ~ma;
  for (std::int64_t w = wa + 1; w < wb; ++w) row[w] = 0;
  row[wb] &= ~mb;
}

std::int64_t count_range(const std::uint64_t* row, std::int64_t a, std::int64_t b) {
  if (a >= b) return 0;
  const std::int64_t wa = word_of(a), wb = word_of(b - 1);
  const std::uint64_t ma = from_bit(bit_of(a));
  const std::uint64_t mb = low_mask(bit_of(b - 1) + 1);
  if (wa == wb) return popcount64(row[wa] & ma & mb);
  std::int64_t n = popcount64(row[wa] & ma);
  for (std::int64_t w = wa + 1; w < wb; ++w) n += popcount64(row[w]);
  return n + popcount64(row[wb] & mb);
}

std::int64_t count_range_and(const std::uint64_t* x, const std::uint64_t* y, std::int64_t a, std::int64_t b) {
  if (a >= b) return 0;
  const std::int64_t wa = word_of(a), wb = word_of(b - 1);
  const std::uint64_t ma = from_bit(bit_of(a));
  const std::uint64_t mb = low_mask(bit_of(b - 1) + 1);
  if (wa == wb) return popcount64(x[wa] & y[wa] & ma & mb);
  std::int64_t n = popcount64(x[wa] & y[wa] & ma);
  for (std::int64_t w = wa + 1; w < wb; ++w) n += popcount64(x[w] & y[w]);
  return n + popcount64(x[wb] & y[wb] & mb);
}

void rotate_row(const std::uint64_t* src, std::uint64_t* dst, std::int64_t n, std::int64_t shift, Combine op) {
  if (n <= 0) return;
  std::int64_t s = shift % n;
  if (s < 0) s += n;
  const std::int64_t nw = words_for(n);
  // The whole words whose source bits [i0 + s, i0 + s + 64) lie inside the row: one loop of
  // shifts (what read_bits gives for them); the rest, near the seam and the row's end, below.
  const std::int64_t fast = std::min(nw, (n - s) / 64);
  if (fast > 0) {
    const std::int64_t k = s >> 6;
    const int off = bit_of(s);
    const auto combine = [&](auto f) {
      for (std::int64_t w = 0; w < fast; ++w)
        f(dst[w], off == 0 ? src[k + w] : (src[k + w] >> off) | (src[k + w + 1] << (64 - off)));
    };
    switch (op) {
      case Combine::kCopy:
        combine([](std::uint64_t& d, std::uint64_t v) { d = v; });
        break;
      case Combine::kAnd:
        combine([](std::uint64_t& d, std::uint64_t v) { d &= v; });
        break;
      case Combine::kOr:
        combine([](std::uint64_t& d, std::uint64_t v) { d |= v; });
        break;
    }
  }
  for (std::int64_t w = std::max<std::int64_t>(fast, 0); w < nw; ++w) {
    const std::int64_t i0 = w << 6;
    const int len = static_cast<int>(n - i0 < 64 ? n - i0 : 64);
    std::int64_t start = i0 + s;
    if (start >= n) start -= n;
    std::uint64_t v = 0;
    if (start + len <= n) {
      v = read_bits(src, start, len);
    } else {  // the 64 bits wrap over the seam: [start, n) then [0, rest)
      const int first = static_cast<int>(n - start);
      v = read_bits(src, start, first) | (read_bits(src, 0, len - first) << first);
    }
    switch (op) {
      case Combine::kCopy:
        dst[w] = v;
        break;
      case Combine::kAnd:
        dst[w] &= v;
        break;
      case Combine::kOr:
        dst[w] |= v;
        break;
    }
  }
}

float float_threshold(double t) {
  constexpr float kMax = std::numeric_limits<float>::max(), kInf = std::numeric_limits<float>::infinity();
  if (std::isnan(t)) return std::numeric_limits<float>::quiet_NaN();
  if (t >= static_cast<double>(kMax)) return t == std::numeric_limits<double>::infinity() ? kInf : kMax;
  if (t < -static_cast<double>(kMax)) return -kInf;
  auto f = static_cast<float>(t);  // the nearest float: one step down when it rounded up
  if (static_cast<double>(f) > t) f = std::nextafter(f, -kInf);
  return f;
}

void threshold_row(const float* values, std::int64_t n, double threshold, std::uint64_t* out) {
  const float f = float_threshold(threshold);
  const std::int64_t nw = words_for(n);
  for (std::int64_t w = 0; w < nw; ++w) {
    const float* x = values + (w << 6);
    const int len = static_cast<int>(std::min<std::int64_t>(64, n - (w << 6)));
    std::uint64_t word = 0;
    int b = 0;
#if defined(__SSE2__)
    const __m128 f4 = _mm_set1_ps(f);
    for (; b + 4 <= len; b += 4)
      word |= static_cast<std::uint64_t>(_mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(x + b), f4))) << b;
#endif
    for (; b < len; ++b) word |= static_cast<std::uint64_t>(x[b] <= f) << b;
    out[w] = word;
  }
}

void threshold_row(const double* values, std::int64_t n, double threshold, std::uint64_t* out) {
  const std::int64_t nw = words_for(n);
  for (std::int64_t w = 0; w < nw; ++w) {
    const double* x = values + (w << 6);
    const int len = static_cast<int>(std::min<std::int64_t>(64, n - (w << 6)));
    std::uint64_t word = 0;
    for (int b = 0; b < len; ++b) word |= static_cast<std::uint64_t>(x[b] <= threshold) << b;
    out[w] = word;
  }
}

}  // namespace aq::mask::bits

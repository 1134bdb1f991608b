// SPDX-License-Identifier: GPL-3.0-or-later
// Counting the set bits of bitmaps (see bitmap.hpp).
#include "core/bitmap.hpp"

#include <algorithm>

namespace aq {

namespace {

constexpr std::int64_t kBlock = std::int64_t{1} << 16;  // words per block (512 KB)

// One block of words: compiled twice, with and without POPCNT, the one to run chosen when the
// program is loaded (GCC's target_clones); the same count either way.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("popcnt", "default")))
#endif
std::int64_t
count_block(const std::uint64_t* w, std::int64_t n) {
  std::int64_t c = 0;
  for (std::int64_t k = 0; k < n; ++k) c += __builtin_popcountll(w[k]);
  return c;
}

}  // namespace

std::int64_t count_bits(const std::uint64_t* words, std::int64_t n) {
  const std::int64_t blocks = (n + kBlock - 1) / kBlock;
  std::int64_t total = 0;
#pragma omp parallel for schedule(static) default(none) shared(words, n, blocks) reduction(+ : total) if (blocks > 8)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::int64_t first = b * kBlock;
    total += count_block(words + first, n - first < kBlock ? n - first : kBlock);
  }
  return total;
}

}  // namespace aq

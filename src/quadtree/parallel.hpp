// SPDX-License-Identifier: GPL-3.0-or-later
// Deterministic OpenMP work splitting for the quadtree and mesh stages (STYLE.md "OpenMP"):
// a range [0, n) is cut into contiguous blocks (one per thread, or one when the work is small).
// Per-block outputs concatenated by block index, or placed by prefix sums of per-block counts,
// give the serial order, so results are bit-identical for any thread count. Exceptions thrown
// inside a block are caught and the first one (lowest block) is rethrown after the region.
#pragma once

#include <cstdint>
#include <exception>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace aq::quadtree {

/// Threads an OpenMP region would use (1 without OpenMP).
inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// Below this much work (in 64-bit word operations or cheap items) a loop runs on one thread:
/// starting a parallel region costs more than the work, and much more when the cores are shared.
inline constexpr std::int64_t kParallelMinWork = std::int64_t{1} << 18;

/// Whether a loop of about `work` word operations is worth a parallel region (the `if` clause).
constexpr bool parallel_worth(std::int64_t work) { return work >= kParallelMinWork; }

/// Number of contiguous blocks to cut n items of about `work_per_item` word operations into:
/// max_threads(), or 1 when the work is too small for a parallel region.
inline int block_count(std::int64_t n, std::int64_t work_per_item = 1) {
  return parallel_worth(n * work_per_item) ? max_threads() : 1;
}

/// Calls body(block, begin, end) for the contiguous blocks 0..blocks-1 of [0, n) (block b is
/// [n·b/blocks, n·(b+1)/blocks)), in parallel. The partition depends only on n and `blocks`, so a
/// count pass and a fill pass with the same arguments see the same blocks. Rethrows the first
/// exception of the lowest block after the region.
template <class Body>
void for_each_block(std::int64_t n, int blocks, const Body& body) {
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(blocks));
#pragma omp parallel for default(none) if (blocks > 1) shared(n, blocks, body, errors) schedule(static, 1)
  for (int b = 0; b < blocks; ++b) {
    try {
      body(b, n * b / blocks, n * (b + 1) / blocks);
    } catch (...) {
      errors[static_cast<std::size_t>(b)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

/// Exclusive prefix sums of `counts` in place; returns the total.
inline std::int64_t exclusive_scan_in_place(std::vector<std::int64_t>& counts) {
  std::int64_t total = 0;
  for (std::int64_t& c : counts) {
    const std::int64_t v = c;
    c = total;
    total += v;
  }
  return total;
}

}  // namespace aq::quadtree

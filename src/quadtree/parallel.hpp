// Deterministic OpenMP work splitting for the quadtree and mesh stages (STYLE.md "OpenMP"):
// a range [0, n) is cut into contiguous blocks, one per thread, in thread order. Per-block
// outputs concatenated by block index (or placed by prefix sums of per-block counts) give the
// serial order, so results are bit-identical for any thread count. Exceptions thrown inside a
// block are caught and the first one (lowest block) is rethrown after the parallel region.
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

/// Calls body(block, begin, end) for contiguous blocks of [0, n), one per thread of a team of at
/// most max_threads(), blocks in thread order. Returns the number of blocks (<= max_threads()).
/// Rethrows the first exception of the lowest block after the region.
template <class Body>
int parallel_blocks(std::int64_t n, const Body& body) {
  const int nt = max_threads();
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(nt));
  int blocks = 1;
#ifdef _OPENMP
#pragma omp parallel num_threads(nt) default(none) shared(n, body, blocks, errors)
  {
    const int team = omp_get_num_threads();
    const int t = omp_get_thread_num();
#pragma omp single
    blocks = team;
    try {
      body(t, n * t / team, n * (t + 1) / team);
    } catch (...) {
      errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
  }
#else
  try {
    body(0, std::int64_t{0}, n);
  } catch (...) {
    errors[0] = std::current_exception();
  }
#endif
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return blocks;
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

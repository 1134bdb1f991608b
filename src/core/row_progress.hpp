// SPDX-License-Identifier: GPL-3.0-or-later
// Progress of an OpenMP loop over rows, reported from the calling thread only (ProgressFn is
// not thread-safe and draws on the terminal).
#pragma once

#include <algorithm>
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/log.hpp"

namespace aq {

// Progress of a parallel loop over rows with schedule(static) and no barriers: thread 0 (the
// calling thread) reports the fraction of its own contiguous chunk done, which tracks the whole
// loop; the owner calls finish() after the loop. One parallel region per pass keeps the cost of
// barriers out of the loop (they are expensive when the cores are shared).
class RowProgress {
 public:
  RowProgress(const ProgressFn& fn, std::int64_t rows, const char* label) : fn_(fn), rows_(rows), label_(label) {}
  // Call once per row from inside the loop.
  void row_done() {
    if (!fn_) return;
#ifdef _OPENMP
    if (omp_get_thread_num() != 0) return;
    const std::int64_t t = omp_get_num_threads();
#else
    const std::int64_t t = 1;
#endif
    const std::int64_t chunk = rows_ / t + (rows_ % t != 0 ? 1 : 0);  // thread 0's static chunk
    ++done_;
    const std::int64_t pct = 100 * done_ / std::max<std::int64_t>(chunk, 1);
    if (pct != last_pct_ && pct < 100) {
      last_pct_ = pct;
      fn_(static_cast<double>(pct) / 100.0, label_);
    }
  }
  void finish() const {
    if (fn_) fn_(1.0, label_);
  }

 private:
  const ProgressFn& fn_;
  std::int64_t rows_;
  const char* label_;
  std::int64_t done_ = 0;
  std::int64_t last_pct_ = -1;
};

}  // namespace aq

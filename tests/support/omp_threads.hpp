// SPDX-License-Identifier: GPL-3.0-or-later
// OpenMP thread count for a scope (1 vs 2 threads must give the same bits): set on construction,
// the previous count restored on destruction; nothing without OpenMP.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace aq::testing {

class ThreadCount {
 public:
  explicit ThreadCount(int n) {
#ifdef _OPENMP
    saved_ = omp_get_max_threads();
    omp_set_num_threads(n);
#else
    (void)n;
#endif
  }
  ~ThreadCount() {
#ifdef _OPENMP
    omp_set_num_threads(saved_);
#endif
  }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int saved_ = 1;
};

}  // namespace aq::testing

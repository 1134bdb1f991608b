// SPDX-License-Identifier: GPL-3.0-or-later
// Wall-clock and process CPU timers, and peak resident memory (getrusage).
#pragma once

#include <chrono>
#include <cstdint>

namespace aq {

/// Seconds of process CPU time (all threads) since process start.
double process_cpu_seconds();
/// Peak resident set size of the process so far, in bytes.
std::int64_t peak_rss_bytes();
/// Resident set size of the process now, in bytes (/proc/self/statm; 0 if unknown).
std::int64_t current_rss_bytes();
/// Total physical memory of the machine, in bytes (0 if unknown).
std::int64_t physical_memory_bytes();

/// Measures wall and CPU time from construction.
class Timer {
 public:
  Timer() : wall0_(std::chrono::steady_clock::now()), cpu0_(process_cpu_seconds()) {}
  [[nodiscard]] double wall_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  }
  [[nodiscard]] double cpu_s() const { return process_cpu_seconds() - cpu0_; }

 private:
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_;
};

}  // namespace aq

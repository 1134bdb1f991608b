// SPDX-License-Identifier: GPL-3.0-or-later
// Checks that fail on non-finite values. Any comparison with NaN is false, so a check written
// `if (error > tolerance) fail` or `if (area > 0) use it` lets a NaN through: a mesh whose wet area
// is NaN used to pass "all checks". Every pass/fail decision on a computed number goes through
// these helpers, and a non-finite value is reported with the quantity and where it first became
// non-finite (index order, so the message is the same for any thread count).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aq {

/// `value` <= `limit` with both finite: false for NaN and ±∞ (use it for "error within tolerance").
[[nodiscard]] inline bool finite_at_most(double value, double limit) {
  return std::isfinite(value) && std::isfinite(limit) && value <= limit;
}

/// max(a, b) that keeps a NaN (std::max(a, NaN) returns a, so a running maximum of errors would
/// silently drop it).
[[nodiscard]] inline double nan_max(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? NAN : (a < b ? b : a);
}

/// Index of the first non-finite value of `values`, or -1.
[[nodiscard]] std::int64_t first_non_finite(std::span<const double> values);

/// Collects the first non-finite value of each checked quantity as one failure message each:
/// "<quantity> is <value> at <where(index)>" plus how many values of that quantity are non-finite.
class FiniteChecks {
 public:
  /// Checks one scalar (`where` says what it is computed from).
  void scalar(std::string_view quantity, double value, std::string_view where = {});
  /// Checks a sequence; `where(i)` describes position i (e.g. "triangle 12 at (…)"), called only
  /// for the first non-finite value.
  template <class Where>
  void values(std::string_view quantity, std::span<const double> v, Where&& where) {
    const std::int64_t first = first_non_finite(v);
    if (first >= 0) add(quantity, v[static_cast<std::size_t>(first)], where(first), count_non_finite(v));
  }
  /// Checks n values given by `get(i)` (return any finite number where the quantity is undefined
  /// by design, e.g. on a boundary); `where(i)` as above.
  template <class Get, class Where>
  void indexed(std::string_view quantity, std::int64_t n, Get&& get, Where&& where) {
    std::int64_t first = -1, count = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      if (std::isfinite(get(i))) continue;
      if (first < 0) first = i;
      ++count;
    }
    if (first >= 0) add(quantity, get(first), where(first), count);
  }
  [[nodiscard]] const std::vector<std::string>& failures() const { return failures_; }
  [[nodiscard]] bool ok() const { return failures_.empty(); }

 private:
  static std::int64_t count_non_finite(std::span<const double> v);
  void add(std::string_view quantity, double value, const std::string& where, std::int64_t count);
  std::vector<std::string> failures_;
};

}  // namespace aq

// SPDX-License-Identifier: GPL-3.0-or-later
// Non-finite checks (see finite.hpp).
#include "core/finite.hpp"

#include <fmt/format.h>

namespace aq {

std::int64_t first_non_finite(std::span<const double> values) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k])) return static_cast<std::int64_t>(k);
  return -1;
}

std::int64_t FiniteChecks::count_non_finite(std::span<const double> v) {
  std::int64_t n = 0;
  for (const double x : v) n += std::isfinite(x) ? 0 : 1;
  return n;
}

void FiniteChecks::scalar(std::string_view quantity, double value, std::string_view where) {
  if (!std::isfinite(value)) add(quantity, value, std::string(where), 1);
}

void FiniteChecks::add(std::string_view quantity, double value, const std::string& where, std::int64_t count) {
  std::string m = fmt::format("{} is {}", quantity, value);
  if (!where.empty()) m += " at " + where;
  if (count > 1) m += fmt::format(" (first of {} non-finite values)", count);
  failures_.push_back(std::move(m));
}

}  // namespace aq

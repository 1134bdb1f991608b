// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/edit_distance.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

namespace aq {

std::size_t edit_distance(const std::string& a, const std::string& b, bool ignore_case) {
  const auto same = [ignore_case](char x, char y) {
    if (!ignore_case) return x == y;
    return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
  };
  std::vector<std::size_t> d(b.size() + 1);  // one row of the distance table
  for (std::size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t prev = d[0];
    d[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cur = d[j];
      d[j] = std::min({d[j] + 1, d[j - 1] + 1, prev + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      prev = cur;
    }
  }
  return d[b.size()];
}

}  // namespace aq

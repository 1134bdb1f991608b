// SPDX-License-Identifier: GPL-3.0-or-later
// The edit distance the "did you mean" suggestions rank known names by (an unknown configuration
// key or section, a misspelt passage name).
#pragma once

#include <cstddef>
#include <string>

namespace aq {

/// The Levenshtein distance between `a` and `b`: the fewest insertions, deletions and
/// substitutions of one byte that turn one into the other; with `ignore_case`, ASCII letters of
/// either case are the same.
[[nodiscard]] std::size_t edit_distance(const std::string& a, const std::string& b, bool ignore_case = false);

}  // namespace aq

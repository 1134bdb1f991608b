// SPDX-License-Identifier: GPL-3.0-or-later
// Seed 004's automatic best-grid choice (digest B.6); see grid_selection.hpp.
#include "curvilinear/elliptic/grid_selection.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"

namespace aq::curvilinear {

namespace {

std::string names(const std::vector<Candidate>& c, const std::vector<int>& set) {
  std::string s;
  for (const int k : set) s += (s.empty() ? "" : ", ") + c[static_cast<std::size_t>(k)].name;
  return "{" + s + "}";
}

// S ← argmax f(k) over the set; the set ← {S} ∪ {f(k)_o > f(k)_o(S)}.
void filter(const std::vector<Candidate>& c, std::vector<int>& set, std::size_t k, Selection& out) {
  int best = set.front();
  for (const int g : set)
    if (c[static_cast<std::size_t>(g)].criteria.worst[k] > c[static_cast<std::size_t>(best)].criteria.worst[k])
      best = g;
  const double avg = c[static_cast<std::size_t>(best)].criteria.average[k];
  std::vector<int> next;
  for (const int g : set)
    if (g == best || c[static_cast<std::size_t>(g)].criteria.average[k] > avg) next.push_back(g);
  out.steps.push_back(fmt::format("f{}: best worst cell {} ({:.4g}); kept those with a higher f{}_o than {:.4g}: {}",
                                  k + 1, c[static_cast<std::size_t>(best)].name,
                                  c[static_cast<std::size_t>(best)].criteria.worst[k], k + 1, avg, names(c, next)));
  set.swap(next);
}

// Lexicographic max over `keys` (indices into worst (< 4) or average (4 + k)).
int lexicographic(const std::vector<Candidate>& c, const std::vector<int>& set, const std::vector<int>& keys) {
  const auto value = [&](int g, int key) {
    const Criteria& q = c[static_cast<std::size_t>(g)].criteria;
    return key < 4 ? q.worst[static_cast<std::size_t>(key)] : q.average[static_cast<std::size_t>(key - 4)];
  };
  int best = set.front();
  for (const int g : set) {
    for (const int key : keys) {
      const double a = value(g, key), b = value(best, key);
      if (a > b) {
        best = g;
        break;
      }
      if (a < b) break;
    }
  }
  return best;
}

}  // namespace

Selection select_best_grid(const std::vector<Candidate>& c) {
  if (c.empty()) throw InternalError("select_best_grid: no candidates");
  Selection out;
  std::vector<int> set;
  for (int g = 0; g < static_cast<int>(c.size()); ++g)
    if (c[static_cast<std::size_t>(g)].criteria.worst[0] > 0.0) set.push_back(g);
  if (!set.empty()) {
    out.steps.push_back(fmt::format("all cells convex (f1 > 0): {}", names(c, set)));
    for (std::size_t k = 1; k < 4; ++k) filter(c, set, k, out);
  } else {
    for (int g = 0; g < static_cast<int>(c.size()); ++g)
      if (c[static_cast<std::size_t>(g)].self_intersecting_cells == 0 &&
          c[static_cast<std::size_t>(g)].boundary_crossings == 0)
        set.push_back(g);
    if (!set.empty()) {
      out.steps.push_back(
          fmt::format("no candidate has all cells convex; without self-intersecting cells and boundary "
                      "crossings: {}",
                      names(c, set)));
      for (std::size_t k = 0; k < 4; ++k) filter(c, set, k, out);
    } else {
      for (int g = 0; g < static_cast<int>(c.size()); ++g) set.push_back(g);
      out.chosen = lexicographic(c, set, {4, 5, 6, 7});
      out.steps.push_back(
          fmt::format("every candidate folds or crosses the boundary: the best (f1_o, f2_o, f3_o, "
                      "f4_o) is {}",
                      c[static_cast<std::size_t>(out.chosen)].name));
      return out;
    }
  }
  out.chosen = set.size() == 1 ? set.front() : lexicographic(c, set, {1, 2, 3});
  if (set.size() > 1)
    out.steps.push_back(fmt::format("{} remain: the best (f2, f3, f4) is {}", names(c, set),
                                    c[static_cast<std::size_t>(out.chosen)].name));
  else
    out.steps.push_back(fmt::format("chosen: {}", c[static_cast<std::size_t>(out.chosen)].name));
  return out;
}

}  // namespace aq::curvilinear

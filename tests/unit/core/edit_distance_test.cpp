// SPDX-License-Identifier: GPL-3.0-or-later
// The edit distance of the "did you mean" suggestions (core/edit_distance.hpp): the configuration's
// unknown keys (case matters) and mask.passages_open's names (case does not).
#include "core/edit_distance.hpp"

#include <gtest/gtest.h>

#include <string>

namespace aq::unit_core_edit_distance_test {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("", ""), 0U);
  EXPECT_EQ(edit_distance("", "abc"), 3U);
  EXPECT_EQ(edit_distance("abc", ""), 3U);
  EXPECT_EQ(edit_distance("min_depth_m", "min_depth_m"), 0U);
  EXPECT_EQ(edit_distance("min_depth", "min_depth_m"), 2U);  // two insertions
  EXPECT_EQ(edit_distance("cursr", "cursor"), 1U);           // one insertion
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3U);         // the textbook case
  EXPECT_EQ(edit_distance("Gibraltar", "Gibraltra"), 2U);    // a transposition is two steps
  EXPECT_EQ(edit_distance("flaw", "lawn"), edit_distance("lawn", "flaw"));
}

TEST(EditDistance, IgnoresTheCaseOfLettersOnlyWhenAsked) {
  EXPECT_EQ(edit_distance("gibraltar", "Gibraltar"), 1U);
  EXPECT_EQ(edit_distance("gibraltar", "Gibraltar", true), 0U);
  EXPECT_EQ(edit_distance("BAB-EL-MANDEB", "Bab-el-Mandeb", true), 0U);
  EXPECT_EQ(edit_distance("hormuz", "Hormoz", true), 1U);
}

}  // namespace aq::unit_core_edit_distance_test

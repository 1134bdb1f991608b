// SPDX-License-Identifier: GPL-3.0-or-later
// The 16 triangle templates (templates.hpp): one parameterised case per 4-bit code (and both
// diagonals of code 0), each checked geometrically and drawn in ASCII.
#include "mesh/templates.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace aq::mesh::unit_mesh_templates_test {
namespace {

struct Code {
  unsigned code;
  bool nw;
};

std::string PrintToString(const Code& c) { return std::to_string(c.code) + (c.nw ? "_nw" : ""); }

/// Draws a template on a 9×9 character grid ('*' vertices, '-' '|' '/' '\' edges), north up.
std::vector<std::string> draw(const Template& t) {
  std::vector<std::string> g(9, std::string(9, ' '));
  const auto cell = [](unsigned v) {
    const std::array<int, 2> p = local_position(v);
    return std::array<int, 2>{4 * p[0], 8 - 4 * p[1]};  // column, row
  };
  for (unsigned k = 0; k < t.count; ++k) {
    for (unsigned e = 0; e < 3; ++e) {
      const auto a = cell(t.tri[k][e]), b = cell(t.tri[k][(e + 1) % 3]);
      const int dx = (b[0] > a[0]) - (b[0] < a[0]), dy = (b[1] > a[1]) - (b[1] < a[1]);
      const char c = dy == 0 ? '-' : dx == 0 ? '|' : (dx == dy ? '\\' : '/');
      for (int x = a[0] + dx, y = a[1] + dy; x != b[0] || y != b[1]; x += dx, y += dy) {
        g[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] = c;
      }
    }
    for (unsigned v = 0; v < 3; ++v) {
      const auto p = cell(t.tri[k][v]);
      g[static_cast<std::size_t>(p[1])][static_cast<std::size_t>(p[0])] = '*';
    }
  }
  return g;
}

class TemplateCode : public ::testing::TestWithParam<Code> {};

TEST_P(TemplateCode, RightIsoscelesAnticlockwiseConformingAndTilingTheSquare) {
  const Code c = GetParam();
  const Template& t = template_for(c.code, c.nw);
  const int k = std::popcount(c.code);
  ASSERT_EQ(t.count, c.code == 0 ? 2 : 4 + k);
  ASSERT_EQ(triangle_count(c.code), t.count);
  for (const std::string& row : draw(t)) std::printf("    %s\n", row.c_str());

  // Vertices allowed: the corners, the midside nodes of the code's sides, the centre if k > 0.
  std::set<unsigned> allowed{kSW, kSE, kNE, kNW};
  for (unsigned s = 0; s < 4; ++s)
    if ((c.code >> s) & 1U) allowed.insert(4 + s);
  if (c.code != 0) allowed.insert(kCentre);
  std::set<unsigned> used;
  long twice_area = 0;
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (unsigned q = 0; q < t.count; ++q) {
    std::array<std::array<int, 2>, 3> p{};
    for (unsigned v = 0; v < 3; ++v) {
      ASSERT_TRUE(allowed.count(t.tri[q][v])) << "vertex " << int(t.tri[q][v]) << " in triangle " << q;
      used.insert(t.tri[q][v]);
      p[v] = local_position(t.tri[q][v]);
      ++directed[{t.tri[q][v], t.tri[q][(v + 1) % 3]}];
    }
    const int cross = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    EXPECT_GT(cross, 0) << "triangle " << q << " is not anticlockwise";
    twice_area += cross;
    std::array<int, 3> d2{};
    for (unsigned e = 0; e < 3; ++e) {
      const auto& a = p[e];
      const auto& b = p[(e + 1) % 3];
      d2[e] = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
    }
    std::sort(d2.begin(), d2.end());
    EXPECT_EQ(d2[0], d2[1]) << "triangle " << q << " is not isosceles";
    EXPECT_EQ(d2[2], 2 * d2[0]) << "triangle " << q << " has no right angle";
    // The right angle sits at the midside node when the triangle has one.
    for (unsigned v = 0; v < 3; ++v) {
      if (t.tri[q][v] < kMidS || t.tri[q][v] > kMidW) continue;
      const auto& a = p[(v + 1) % 3];
      const auto& b = p[(v + 2) % 3];
      EXPECT_EQ((a[0] - p[v][0]) * (b[0] - p[v][0]) + (a[1] - p[v][1]) * (b[1] - p[v][1]), 0);
    }
  }
  EXPECT_EQ(used, allowed) << "every midside node of the code is used";
  EXPECT_EQ(twice_area, 8) << "the triangles' areas add up to the square (side 2)";
  // No vertex lies inside another triangle's edge (no hanging node inside the template).
  for (unsigned q = 0; q < t.count; ++q) {
    for (unsigned e = 0; e < 3; ++e) {
      const auto a = local_position(t.tri[q][e]), b = local_position(t.tri[q][(e + 1) % 3]);
      for (const unsigned v : used) {
        const auto x = local_position(v);
        const int cross = (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]);
        const int dot1 = (x[0] - a[0]) * (b[0] - a[0]) + (x[1] - a[1]) * (b[1] - a[1]);
        const int dot2 = (x[0] - b[0]) * (a[0] - b[0]) + (x[1] - b[1]) * (a[1] - b[1]);
        EXPECT_FALSE(cross == 0 && dot1 > 0 && dot2 > 0) << "vertex " << v << " inside edge of triangle " << q;
      }
    }
  }
  // Interior edges appear once in each direction; boundary edges (on the square's sides) once.
  for (const auto& [edge, n] : directed) {
    EXPECT_EQ(n, 1);
    const auto a = local_position(edge.first), b = local_position(edge.second);
    const bool on_side = (a[0] == b[0] && (a[0] == 0 || a[0] == 2)) || (a[1] == b[1] && (a[1] == 0 || a[1] == 2));
    EXPECT_EQ(directed.count({edge.second, edge.first}), on_side ? 0u : 1u);
  }
}

std::vector<Code> all_codes() {
  std::vector<Code> v{{0, true}};
  for (unsigned c = 0; c < 16; ++c) v.push_back({c, false});
  return v;
}

INSTANTIATE_TEST_SUITE_P(AllCodes, TemplateCode, ::testing::ValuesIn(all_codes()),
                         [](const ::testing::TestParamInfo<Code>& i) { return PrintToString(i.param); });

TEST(Templates, DrawingsMatchTheHeaderComment) {
  // clang-format off
  const std::vector<std::string> ne{"*-------*",
                                    "|      /|",
                                    "|     / |",
                                    "|    /  |",
                                    "|   /   |",
                                    "|  /    |",
                                    "| /     |",
                                    "|/      |",
                                    "*-------*"};
  // clang-format on
  EXPECT_EQ(draw(template_for(0, false)), ne);
  // clang-format off
  const std::vector<std::string> nw{"*-------*",
                                    "|\\      |",
                                    "| \\     |",
                                    "|  \\    |",
                                    "|   \\   |",
                                    "|    \\  |",
                                    "|     \\ |",
                                    "|      \\|",
                                    "*-------*"};
  // clang-format on
  EXPECT_EQ(draw(template_for(0, true)), nw);
  // clang-format off
  const std::vector<std::string> s{"*-------*",
                                   "|\\     /|",
                                   "| \\   / |",
                                   "|  \\ /  |",
                                   "|   *   |",
                                   "|  /|\\  |",
                                   "| / | \\ |",
                                   "|/  |  \\|",
                                   "*---*---*"};
  // clang-format on
  EXPECT_EQ(draw(template_for(1, false)), s);
  // clang-format off
  const std::vector<std::string> all{"*---*---*",
                                     "|\\  |  /|",
                                     "| \\ | / |",
                                     "|  \\|/  |",
                                     "*---*---*",
                                     "|  /|\\  |",
                                     "| / | \\ |",
                                     "|/  |  \\|",
                                     "*---*---*"};
  // clang-format on
  EXPECT_EQ(draw(template_for(15, false)), all);
}

TEST(Templates, DiagonalChoice) {
  EXPECT_FALSE(uses_nw_diagonal(Diagonal::kNE, 1, 0));
  EXPECT_TRUE(uses_nw_diagonal(Diagonal::kNW, 0, 0));
  EXPECT_FALSE(uses_nw_diagonal(Diagonal::kAlternate, 3, 5));
  EXPECT_TRUE(uses_nw_diagonal(Diagonal::kAlternate, 3, 4));
  EXPECT_EQ(parse_name<Diagonal>("alternate"), Diagonal::kAlternate);
  EXPECT_FALSE(parse_name<Diagonal>("sw").has_value());
}

}  // namespace
}  // namespace aq::mesh::unit_mesh_templates_test

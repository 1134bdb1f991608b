// SPDX-License-Identifier: GPL-3.0-or-later
// Triangle templates of a quadtree square (seed 002, Fig. 4 "шаблоны разбиения квадрата на
// треугольники"; ARCHITECTURE §4.6). A square is split into right isosceles triangles according
// to which of its sides carry a midside (hanging) node — a 4-bit code, one bit per side:
//
//     bit 0 (1) S,  bit 1 (2) E,  bit 2 (4) N,  bit 3 (8) W
//
// Local vertices of a square (the same conventions as quadtree/nodes.hpp):
//
//     3 NW ---- 6 N ---- 2 NE
//      |                  |
//     7 W       8 C      5 E           corners 0..3, midside nodes 4..7, centre 8
//      |                  |
//     0 SW ---- 4 S ---- 1 SE
//
// Code 0 (no midside node): two triangles split by a diagonal, "ne" (SW–NE) or "nw" (SE–NW):
//
//     code 0, "ne"         code 0, "nw"
//     3---------2          3---------2
//     |  1    / |          | \    1  |
//     |     /   |          |   \     |
//     |   /     |          |     \   |
//     | /    0  |          |  0    \ |
//     0---------1          0---------1
//
// Code with k >= 1 bits: a centre node and 4 + k triangles, going anticlockwise round the sides
// S, E, N, W; a side with a midside node gives (corner, midside, C) and (midside, next corner, C)
// with the right angle at the midside node, a side without gives (corner, next corner, C) with
// the right angle at C. All triangles are anticlockwise. For example:
//
//     code 1 (S)           code 5 (S, N)        code 15 (S, E, N, W)
//     3---------2          3----6----2          3----6----2
//     | \  3  / |          | \ 4| 3/ |          | \ 5| 4/ |
//     |   \ /   |          |   \|/   |          | 6 \|/ 3 |
//     | 4  8  2 |          | 5  8  2 |          7----8----5
//     |   /|\   |          |   /|\   |          | 7 /|\ 2 |
//     | / 0|1 \ |          | / 0|1 \ |          | / 0|1 \ |
//     0----4----1          0----4----1          0----4----1
//
// (numbers inside are the triangle order in the template). Codes 1..15 all occur in practice
// (ARCHITECTURE §4.9), so the table covers all 16.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "config/kinds.hpp"

namespace aq::mesh {

/// Local vertex numbers of a square (see the file comment).
enum LocalVertex : std::uint8_t {
  kSW = 0,
  kSE = 1,
  kNE = 2,
  kNW = 3,
  kMidS = 4,
  kMidE = 5,
  kMidN = 6,
  kMidW = 7,
  kCentre = 8
};

/// Choice of the diagonal of squares without midside nodes (`mesh.diagonal`, config/kinds.hpp):
/// SW–NE, SE–NW, or alternating as a chequerboard ("ne" when a + b of the square is even).
using config::Diagonal;

/// Triangles of one template as local vertex triples, anticlockwise.
struct Template {
  std::uint8_t count = 0;
  std::array<std::array<std::uint8_t, 3>, 8> tri{};
};

namespace detail {
constexpr Template make_template(unsigned code, bool nw) {
  Template t;
  if (code == 0) {
    if (nw) {
      t.tri[0] = {kSW, kSE, kNW};
      t.tri[1] = {kSE, kNE, kNW};
    } else {
      t.tri[0] = {kSW, kSE, kNE};
      t.tri[1] = {kSW, kNE, kNW};
    }
    t.count = 2;
    return t;
  }
  for (unsigned side = 0; side < 4; ++side) {
    const auto a = static_cast<std::uint8_t>(side);
    const auto b = static_cast<std::uint8_t>((side + 1) % 4);
    const auto m = static_cast<std::uint8_t>(4 + side);
    if ((code >> side) & 1U) {
      t.tri[t.count++] = {a, m, kCentre};
      t.tri[t.count++] = {m, b, kCentre};
    } else {
      t.tri[t.count++] = {a, b, kCentre};
    }
  }
  return t;
}
constexpr std::array<Template, 16> make_table() {
  std::array<Template, 16> table{};
  for (unsigned c = 0; c < 16; ++c) table[c] = make_template(c, false);
  return table;
}
}  // namespace detail

/// Templates by midside code; entry 0 is the "ne" diagonal.
inline constexpr std::array<Template, 16> kTemplates = detail::make_table();
/// Code 0 with the "nw" diagonal.
inline constexpr Template kTemplateNW = detail::make_template(0, true);

/// Number of triangles of a code: 2 for code 0, else 4 + (bits set).
constexpr int triangle_count(unsigned code) { return kTemplates[code & 15U].count; }

/// Whether square (a, b) (indices at its level) uses the "nw" diagonal when it has code 0.
constexpr bool uses_nw_diagonal(Diagonal d, std::int64_t a, std::int64_t b) {
  return d == Diagonal::kNW || (d == Diagonal::kAlternate && ((a + b) & 1) != 0);
}

/// The template of a square: `code` 0..15 and its diagonal choice.
constexpr const Template& template_for(unsigned code, bool nw_diagonal) {
  return (code == 0 && nw_diagonal) ? kTemplateNW : kTemplates[code & 15U];
}

/// Position of a local vertex in units of half a side: (0..2, 0..2), SW corner at (0, 0).
constexpr std::array<int, 2> local_position(unsigned v) {
  constexpr std::array<std::array<int, 2>, 9> p{
      {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}, {1, 1}}};
  return p[v];
}

static_assert(triangle_count(0) == 2 && triangle_count(1) == 5 && triangle_count(15) == 8);

}  // namespace aq::mesh

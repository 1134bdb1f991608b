// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the revised IZ89 straightening (seed 000 Sec. 2.3–2.4; digest izogrid.md §5–6) on
// polygons whose conformal modulus is known exactly from symmetry:
//
//  * Half-square triangle. The square Q = [−1,1]² with its four corners at the edge midpoints
//    (0,−1), (1,0), (0,1), (−1,0) has modulus 1: the 90° rotation maps Q onto itself and each
//    side onto the next, so W/H = H/W. The reflection in y = x maps Q onto itself, swaps the
//    south and north sides and maps east and west onto themselves; it is the reflection of the
//    unit-square image in its horizontal midline, so the diagonal y = x maps to that midline.
//    The lower half, the right isosceles triangle (−1,−1), (1,−1), (1,1) with corners SW (0,−1),
//    SE (1,0), NE (1,1), NW (−1,−1), therefore maps onto a 1 × ½ rectangle: W/H = 2 exactly.
//    (Symmetry argument as in Henrici, Applied and Computational Complex Analysis vol. 3,
//    §16.11, for moduli of symmetric quadrilaterals.)
//  * Symmetric L-shape 0, 2, 2+i, 1+i, 1+2i, 2i with corners 0 (SW), 2 (SE), 1+i (NE, reflex
//    3π/2 -> π/2) and 2i (NW): the reflection in y = x swaps S with W and E with N, so W/H = 1.
//
// IZ89 maps the polygon through its vertices (chords), so the discrete W/H approaches the exact
// value as the sides are subdivided; the tests check the value and that the error shrinks.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/error.hpp"
#include "curvilinear/conformal/inverse_problem.hpp"
#include "curvilinear/conformal/iz89.hpp"

namespace aq::curvilinear::unit_curvilinear_iz89_test {
namespace {

struct Polygon {
  std::vector<double> x, y;
  std::array<int, 4> corners{};
};

// Polygon through the given vertices (counter-clockwise), each edge split into pieces of
// length ≈ h; `corner_vertex` lists which input vertices are the SW, SE, NE, NW corners (the
// first must be vertex 0).
Polygon subdivide(const std::vector<std::pair<double, double>>& v, const std::array<int, 4>& corner_vertex, double h) {
  Polygon p;
  const int n = static_cast<int>(v.size());
  int c = 0;
  for (int i = 0; i < n; ++i) {
    if (c < 4 && corner_vertex[static_cast<std::size_t>(c)] == i)
      p.corners[static_cast<std::size_t>(c++)] = static_cast<int>(p.x.size());
    const auto [x0, y0] = v[static_cast<std::size_t>(i)];
    const auto [x1, y1] = v[static_cast<std::size_t>((i + 1) % n)];
    const int m = std::max(1, static_cast<int>(std::lround(std::hypot(x1 - x0, y1 - y0) / h)));
    for (int k = 0; k < m; ++k) {
      p.x.push_back(x0 + (x1 - x0) * k / m);
      p.y.push_back(y0 + (y1 - y0) * k / m);
    }
  }
  return p;
}

// W/H = (|S| + |N|)/(|E| + |W|) of a straightened polygon.
double aspect(const Polygon& p) {
  const int nb = static_cast<int>(p.x.size());
  double len[4] = {0, 0, 0, 0};
  for (int s = 0; s < 4; ++s) {
    const int a = p.corners[static_cast<std::size_t>(s)], b = s == 3 ? nb : p.corners[static_cast<std::size_t>(s) + 1];
    for (int i = a; i < b; ++i) {
      const auto j = static_cast<std::size_t>((i + 1) % nb), k = static_cast<std::size_t>(i);
      len[s] += std::hypot(p.x[j] - p.x[k], p.y[j] - p.y[k]);
    }
  }
  return (len[0] + len[2]) / (len[1] + len[3]);
}

// Largest |cos| of the rectangle's corner angles and largest deviation of a side from its chord.
double max_corner_cos(const Polygon& p) {
  const int nb = static_cast<int>(p.x.size());
  double worst = 0.0;
  for (int c : p.corners) {
    const auto k = static_cast<std::size_t>(c), km = static_cast<std::size_t>((c + nb - 1) % nb),
               kp = static_cast<std::size_t>((c + 1) % nb);
    const double ax = p.x[k] - p.x[km], ay = p.y[k] - p.y[km], bx = p.x[kp] - p.x[k], by = p.y[kp] - p.y[k];
    worst = std::max(worst, std::fabs(ax * bx + ay * by) / (std::hypot(ax, ay) * std::hypot(bx, by)));
  }
  return worst;
}

Polygon half_square_triangle(double h) {
  // SW (0,−1), B (1,−1), SE (1,0), NE (1,1), NW (−1,−1)
  return subdivide({{0, -1}, {1, -1}, {1, 0}, {1, 1}, {-1, -1}}, {0, 2, 3, 4}, h);
}

Polygon symmetric_l(double h) { return subdivide({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {0, 1, 3, 5}, h); }

TEST(Iz89Test, HalfSquareTriangleHasModulusTwo) {
  double prev_err = 1.0;
  for (double h : {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64}) {
    Polygon p = half_square_triangle(h);
    const Iz89Result r = iz89_straighten(p.x, p.y, p.corners);
    ASSERT_TRUE(r.converged) << "h = " << h;
    EXPECT_EQ(r.clamped_maps, 0);
    // Right angles to the round-off floor, which grows like Nb² (iz89.hpp).
    EXPECT_LT(max_corner_cos(p), 2e-16 * static_cast<double>(p.x.size() * p.x.size()));
    const double err = std::fabs(aspect(p) - 2.0);
    std::printf("[ info ] half-square triangle, h = 1/%d (%zu vertices): W/H = %.10f, %d passes\n",
                static_cast<int>(1 / h), p.x.size(), aspect(p), r.passes);
    EXPECT_LT(err, 0.6 * prev_err) << "h = " << h;  // the chord error shrinks with h
    prev_err = err;
  }
  EXPECT_LT(prev_err, 1e-4);
}

TEST(Iz89Test, SymmetricLShapeHasModulusOne) {
  // The reflex corner (interior 3π/2, P = 1/3) makes the chord error larger and the order lower
  // (measured ≈ h^1.25) than for the triangle; the pass order breaks the discrete symmetry.
  double prev_err = 1.0;
  for (double h : {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64}) {
    Polygon p = symmetric_l(h);
    const Iz89Result r = iz89_straighten(p.x, p.y, p.corners);
    ASSERT_TRUE(r.converged);
    EXPECT_LT(max_corner_cos(p), 2e-16 * static_cast<double>(p.x.size() * p.x.size()));
    const double err = std::fabs(aspect(p) - 1.0);
    std::printf("[ info ] symmetric L, h = 1/%d: W/H = %.10f, %d passes\n", static_cast<int>(1 / h), aspect(p),
                r.passes);
    EXPECT_LT(err, 0.55 * prev_err) << "h = " << h;
    prev_err = err;
  }
  EXPECT_LT(prev_err, 4e-4);
}

TEST(Iz89Test, RectangleIsAFixedPoint) {
  Polygon p = subdivide({{0, 0}, {3, 0}, {3, 2}, {0, 2}}, {0, 1, 2, 3}, 0.25);
  const std::vector<double> x0 = p.x, y0 = p.y;
  const Iz89Result r = iz89_straighten(p.x, p.y, p.corners);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.passes, 1);
  EXPECT_EQ(p.x, x0);
  EXPECT_EQ(p.y, y0);
  EXPECT_DOUBLE_EQ(aspect(p), 1.5);
}

TEST(Iz89Test, ConvergesAboutADecadePerPass) {
  Polygon p = half_square_triangle(1.0 / 32);
  const Iz89Result r = iz89_straighten(p.x, p.y, p.corners);
  ASSERT_GE(r.max_angle.size(), 6u);
  // From the first pass to the round-off floor the largest turning angle falls geometrically.
  int falls = 0;
  for (std::size_t i = 1; i < r.max_angle.size() && r.max_angle[i] > 1e-11; ++i)
    if (r.max_angle[i] < 0.5 * r.max_angle[i - 1]) ++falls;
  EXPECT_GE(falls, 6);
  EXPECT_LT(r.max_angle.back(), 1e-10);
}

TEST(Iz89Test, BitIdenticalForOneAndTwoThreads) {
  for (double h : {1.0 / 16, 1.0 / 40}) {
    Polygon a = symmetric_l(h), b = a;
    Iz89Options one, two;
    one.max_passes = two.max_passes = 3;  // each vertex map costs two barriers: keep it short
    one.threads = 1;
    two.threads = 2;
    two.min_parallel_vertices = 0;  // force the parallel path even for a small polygon
    const Iz89Result ra = iz89_straighten(a.x, a.y, a.corners, one);
    const Iz89Result rb = iz89_straighten(b.x, b.y, b.corners, two);
    EXPECT_EQ(ra.passes, rb.passes);
    EXPECT_EQ(ra.max_angle, rb.max_angle);
    EXPECT_EQ(a.x, b.x);  // bit for bit
    EXPECT_EQ(a.y, b.y);
    // The default: the thread count chosen per chunk by timing.
    Polygon c = symmetric_l(h);
    Iz89Options chosen;
    chosen.max_passes = 3;
    chosen.min_parallel_vertices = 0;
    (void)iz89_straighten(c.x, c.y, c.corners, chosen);
    EXPECT_EQ(a.x, c.x);
    EXPECT_EQ(a.y, c.y);
  }
}

// Three threads (unequal shares of blocks, three parties at each barrier), an odd vertex count
// and sweeps of 128 maps that start anywhere must all give the one-thread bits.
TEST(Iz89Test, BitIdenticalForThreeThreadsAndOddPolygons) {
  Polygon base = half_square_triangle(1.0 / 45);
  if (base.x.size() % 2 == 0) {  // make the vertex count odd: split the first edge once more
    base.x.insert(base.x.begin() + 1, 0.5 * (base.x[0] + base.x[1]));
    base.y.insert(base.y.begin() + 1, 0.5 * (base.y[0] + base.y[1]));
    for (int c = 1; c < 4; ++c) ++base.corners[static_cast<std::size_t>(c)];
  }
  ASSERT_EQ(base.x.size() % 2, 1U);
  ASSERT_GT(base.x.size(), 3U * 64);  // more blocks of 64 walk positions than threads
  Polygon a = base, b = base, c = base;
  Iz89Options one, three, chosen;
  one.max_passes = three.max_passes = chosen.max_passes = 2;
  one.threads = 1;
  three.threads = 3;
  three.min_parallel_vertices = chosen.min_parallel_vertices = 0;
  const Iz89Result ra = iz89_straighten(a.x, a.y, a.corners, one);
  const Iz89Result rb = iz89_straighten(b.x, b.y, b.corners, three);
  (void)iz89_straighten(c.x, c.y, c.corners, chosen);  // sweeps of 128 maps, 1 or N threads each
  EXPECT_EQ(ra.max_angle, rb.max_angle);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.x, c.x);
  EXPECT_EQ(a.y, c.y);
  EXPECT_NE(a.x, base.x);  // the maps did move the vertices
}

TEST(Iz89Test, RefusesDegeneratePolygons) {
  Polygon p = subdivide({{0, 0}, {3, 0}, {3, 2}, {0, 2}}, {0, 1, 2, 3}, 0.5);
  p.x[3] = p.x[2];
  p.y[3] = p.y[2];
  p.x[1] += 0.1;  // not a rectangle any more, so vertex maps run and meet the zero edge
  EXPECT_THROW(iz89_straighten(p.x, p.y, p.corners), NumericalError);
  std::vector<double> x{0, 1, 1}, y{0, 0, 1};
  EXPECT_THROW(iz89_straighten(x, y, {0, 1, 2, 2}), InternalError);
}

TEST(Iz89Test, InnerPassSchedules) {
  // 2^((m+5)/2) and sqrt(2m+5), rounded up (digest §7.2 table).
  const std::vector<int> exp_counts{8, 12, 16, 23, 32, 46, 64, 91};
  const std::vector<int> sqrt_counts{3, 3, 4, 4, 4, 5, 5, 5};
  for (int m = 1; m <= 8; ++m) {
    EXPECT_EQ(inner_pass_count(InnerSchedule::kExponential, m), exp_counts[static_cast<std::size_t>(m - 1)]) << m;
    EXPECT_EQ(inner_pass_count(InnerSchedule::kSqrt, m), sqrt_counts[static_cast<std::size_t>(m - 1)]) << m;
  }
  EXPECT_EQ(parse_name<InnerSchedule>("sqrt"), InnerSchedule::kSqrt);
  EXPECT_FALSE(parse_name<InnerSchedule>("linear").has_value());
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_iz89_test

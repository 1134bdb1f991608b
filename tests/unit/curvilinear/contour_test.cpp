// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the corner-exact spline contour (seed 000 eqs. (8)–(15), (55)–(73), (85)–(87); digest
// izogrid.md §4) and of its periodic sweep solvers (seed 001 §10, digest splines.md §7):
// exact 90° corners on random star-shaped contours, straight sides for four corners, the C²/C⁴
// continuity that the corrected equations (72)/(73) must give, iterated arc length, the refused
// inputs (corner counts, self-intersection, clockwise order), and mode-2 uniform nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "core/error.hpp"
#include "curvilinear/common/boundary_nodes.hpp"
#include "curvilinear/common/periodic_spline.hpp"
#include "curvilinear/common/spline_contour.hpp"

namespace aq::curvilinear::unit_curvilinear_contour_test {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Points {
  std::vector<double> x, y;
  std::vector<bool> corner;
};

Points black_sea() {
  Points p;
  p.x = {-97, -77, -44, -9, 25, 75, 104, 89.2, 55, 38, 57.5, 3, -40, -74, -84};
  p.y = {-26, -39.5, -46, -31.5, -44, -47, -33, -14, 10, 29, 63.5, 47, 60, 12, -6.2};
  p.corner.assign(15, false);
  p.corner[0] = p.corner[6] = p.corner[10] = p.corner[12] = true;
  return p;
}

// A random star-shaped contour: n points at increasing angles with random radii, four of them
// corners, one per quadrant.
Points random_star(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> radius(60.0, 140.0), jitter(-0.3, 0.3);
  Points p;
  const double start = 1.25 * kPi;  // SW
  for (int k = 0; k < n; ++k) {
    const double a = start + 2.0 * kPi * (k + 0.5 * jitter(rng)) / n;
    const double r = radius(rng);
    p.x.push_back(r * std::cos(a));
    p.y.push_back(r * std::sin(a));
    p.corner.push_back(false);
  }
  p.corner[0] = true;
  p.corner[static_cast<std::size_t>(n / 4)] = true;
  p.corner[static_cast<std::size_t>(n / 2)] = true;
  p.corner[static_cast<std::size_t>(3 * n / 4)] = true;
  return p;
}

double corner_cos(const SplineContour& c, int corner) {
  const Side out = static_cast<Side>(corner);
  const Side in = static_cast<Side>((corner + 3) % 4);
  const double s = c.side_begin(out);
  const PlanePoint a = c.side_derivative(in, corner == 0 ? c.period() : s);
  const PlanePoint b = c.side_derivative(out, s);
  return (a.x * b.x + a.y * b.y) / (std::hypot(a.x, a.y) * std::hypot(b.x, b.y));
}

TEST(ContourTest, CornersAreExactlyRightAnglesOnRandomStarShapes) {
  std::mt19937 rng(12345);
  int built = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Points p = random_star(rng, 8 + trial % 17);
    for (int degree : {3, 5}) {
      for (Parametrisation par : {Parametrisation::kIndex, Parametrisation::kArcLength}) {
        ContourOptions o;
        o.degree = degree;
        o.parametrisation = par;
        std::unique_ptr<SplineContour> c;
        try {
          c = std::make_unique<SplineContour>(p.x, p.y, p.corner, o);
        } catch (const InputError&) {
          continue;  // a random star whose quintic loops is refused, as it should be
        }
        ++built;
        for (int k = 0; k < 4; ++k) {
          ASSERT_LT(std::fabs(corner_cos(*c, k)), 1e-13)
              << "trial " << trial << " degree " << degree << " corner " << k;
          // The same from positions alone: chords a small step before and after the corner.
          const double s = c->side_begin(static_cast<Side>(k));
          const double d = 1e-5;
          const PlanePoint m = c->point(s), a = c->point(s - d), b = c->point(s + d);
          const double ax = m.x - a.x, ay = m.y - a.y, bx = b.x - m.x, by = b.y - m.y;
          EXPECT_LT(std::fabs(ax * bx + ay * by) / (std::hypot(ax, ay) * std::hypot(bx, by)), 1e-3);
        }
      }
    }
  }
  EXPECT_GT(built, 500);  // most random contours are fine (800 tried)
}

TEST(ContourTest, FourCornersGiveTheRectangleWithStraightSides) {
  const std::vector<double> x{-30, 50, 50, -30}, y{-10, -10, 25, 25};
  for (int degree : {3, 5}) {
    ContourOptions o;
    o.degree = degree;
    const SplineContour c(x, y, {true, true, true, true}, o);
    for (int seg = 0; seg < 4; ++seg)
      for (double p = 0.0; p <= 1.0; p += 0.0625) {
        const PlanePoint q = c.segment_eval(seg, p);
        if (seg == 0) {
          EXPECT_NEAR(q.y, -10.0, 1e-13);
        }
        if (seg == 1) {
          EXPECT_NEAR(q.x, 50.0, 1e-13);
        }
        if (seg == 2) {
          EXPECT_NEAR(q.y, 25.0, 1e-13);
        }
        if (seg == 3) {
          EXPECT_NEAR(q.x, -30.0, 1e-13);
        }
      }
    EXPECT_NEAR(c.side_length(Side::kSouth), 80.0, 1e-11);
    EXPECT_NEAR(c.side_length(Side::kEast), 35.0, 1e-11);
    // Side fractions in the grid's positive directions: t = 0 at the west/south end.
    const PlanePoint n0 = c.point(c.side_parameter(Side::kNorth, 0.0));
    const PlanePoint w1 = c.point(c.side_parameter(Side::kWest, 1.0));
    const PlanePoint e0 = c.point(c.side_parameter(Side::kEast, 0.0));
    EXPECT_NEAR(n0.x, -30.0, 1e-13);
    EXPECT_NEAR(n0.y, 25.0, 1e-13);
    EXPECT_NEAR(w1.x, -30.0, 1e-13);
    EXPECT_NEAR(w1.y, 25.0, 1e-13);
    EXPECT_NEAR(e0.x, 50.0, 1e-13);
    EXPECT_NEAR(e0.y, -10.0, 1e-13);
    // Arc length across a corner adds the two pieces.
    EXPECT_NEAR(c.arc_length(c.side_begin(Side::kSouth), c.side_end(Side::kEast)), 115.0, 1e-11);
  }
}

TEST(ContourTest, QuinticIsC4AndCubicIsC2AcrossKnots) {
  // Equation (72) as printed (+1/10, swapped A⁴/B⁴) would break C⁴ on unequal spacings; the
  // arc-length parametrisation makes the spacings unequal, so check derivative jumps there.
  const Points p = black_sea();
  for (int degree : {3, 5}) {
    ContourOptions o;
    o.degree = degree;
    o.parametrisation = Parametrisation::kArcLength;
    const SplineContour c(p.x, p.y, p.corner, o);
    const int n = c.num_points();
    for (int k = 1; k < n; ++k) {
      if (c.side_of_segment(k) != c.side_of_segment(k - 1)) continue;  // corners: rotated frames
      for (int order = 1; order <= degree - 1; ++order) {
        const PlanePoint l = c.segment_eval(k - 1, 1.0, order), r = c.segment_eval(k, 0.0, order);
        const double scale = std::hypot(l.x, l.y) + std::hypot(r.x, r.y) + 1e-300;
        EXPECT_LT(std::hypot(l.x - r.x, l.y - r.y) / scale, 1e-10)
            << "degree " << degree << " knot " << k << " derivative " << order;
      }
      // ... and the next derivative really jumps (the test can tell).
      const PlanePoint l = c.segment_eval(k - 1, 1.0, degree), r = c.segment_eval(k, 0.0, degree);
      EXPECT_GT(std::hypot(l.x - r.x, l.y - r.y), 1e-9);
    }
  }
}

TEST(ContourTest, CyclicSweepsMatchDenseSolves) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  const int n = 9;
  std::vector<double> h(n), df(n);
  for (int i = 0; i < n; ++i) {
    h[static_cast<std::size_t>(i)] = u(rng);
    df[static_cast<std::size_t>(i)] = u(rng) - 1.2;
  }
  std::vector<double> d(n), dd(n);
  periodic_quintic_derivatives(h, df, d, dd);
  // Residuals of (70) and corrected (72) with the solution.
  for (int k = 0; k < n; ++k) {
    const auto km = static_cast<std::size_t>((k + n - 1) % n), kk = static_cast<std::size_t>(k),
               kp = static_cast<std::size_t>((k + 1) % n);
    const double A = h[km], B = h[kk];
    const double r1 = 7.0 / 15 * d[km] / (A * A * A) + 8.0 / 15 * (1 / (A * A * A) + 1 / (B * B * B)) * d[kk] +
                      7.0 / 15 * d[kp] / (B * B * B) + 1.0 / 15 * dd[km] / (A * A) -
                      1.0 / 10 * (1 / (A * A) - 1 / (B * B)) * dd[kk] - 1.0 / 15 * dd[kp] / (B * B) -
                      (df[kk] / std::pow(B, 4) + df[km] / std::pow(A, 4));
    const double r2 = -2.0 / 5 * d[km] / (A * A) - 3.0 / 5 * (1 / (A * A) - 1 / (B * B)) * d[kk] +
                      2.0 / 5 * d[kp] / (B * B) - 1.0 / 20 * dd[km] / A + 3.0 / 20 * (1 / A + 1 / B) * dd[kk] -
                      1.0 / 20 * dd[kp] / B - (df[kk] / (B * B * B) - df[km] / (A * A * A));
    EXPECT_NEAR(r1, 0.0, 1e-13);
    EXPECT_NEAR(r2, 0.0, 1e-13);
  }
  std::vector<double> dc(n);
  periodic_cubic_slopes(h, df, dc);
  for (int k = 0; k < n; ++k) {
    const auto km = static_cast<std::size_t>((k + n - 1) % n), kk = static_cast<std::size_t>(k),
               kp = static_cast<std::size_t>((k + 1) % n);
    const double A = h[km], B = h[kk];
    EXPECT_NEAR(dc[km] / A + 2 * (1 / A + 1 / B) * dc[kk] + dc[kp] / B - 3 * (df[km] / (A * A) + df[kk] / (B * B)), 0.0,
                1e-13);
  }
}

TEST(ContourTest, HermiteBasesInterpolate) {
  for (int degree : {3, 5}) {
    const HermiteBasis& b = hermite_basis(degree);
    EXPECT_DOUBLE_EQ(poly_derivative(b.fl, 0.0, 0), 1.0);
    EXPECT_DOUBLE_EQ(poly_derivative(b.fr, 1.0, 0), 1.0);
    EXPECT_DOUBLE_EQ(poly_derivative(b.dl, 0.0, 1), 1.0);
    EXPECT_DOUBLE_EQ(poly_derivative(b.dr, 1.0, 1), 1.0);
    EXPECT_DOUBLE_EQ(poly_derivative(b.dl, 1.0, 1), 0.0);
    EXPECT_DOUBLE_EQ(poly_derivative(b.fl, 1.0, 0), 0.0);
    if (degree == 5) {
      EXPECT_DOUBLE_EQ(poly_derivative(b.ddl, 0.0, 2), 1.0);
      EXPECT_DOUBLE_EQ(poly_derivative(b.ddr, 1.0, 2), 1.0);
      EXPECT_DOUBLE_EQ(poly_derivative(b.ddr, 0.0, 2), 0.0);
      EXPECT_DOUBLE_EQ(poly_derivative(b.fr, 1.0, 2), 0.0);
      // Third derivatives at the ends, digest §4.3 table (in p, which is ξ + 1/2).
      EXPECT_DOUBLE_EQ(poly_derivative(b.dl, 0.0, 3), -36.0);
      EXPECT_DOUBLE_EQ(poly_derivative(b.dl, 1.0, 3), -24.0);
      EXPECT_DOUBLE_EQ(poly_derivative(b.ddr, 1.0, 4), 36.0);
    }
  }
}

TEST(ContourTest, BlackSeaCubicAndQuinticNearlyCoincide) {
  // Seed Fig. 3 shows both; the digest's prototype found max |quintic − cubic| = 1.36 units.
  const Points p = black_sea();
  ContourOptions o5, o3;
  o3.degree = 3;
  const SplineContour q(p.x, p.y, p.corner, o5), c(p.x, p.y, p.corner, o3);
  double worst = 0.0;
  for (int k = 0; k < q.num_points(); ++k)
    for (double t = 0.0; t < 1.0; t += 1.0 / 64) {
      const PlanePoint a = q.segment_eval(k, t), b = c.segment_eval(k, t);
      worst = std::max(worst, std::hypot(a.x - b.x, a.y - b.y));
    }
  EXPECT_GT(worst, 0.5);
  EXPECT_LT(worst, 2.0);
  std::printf("[ info ] Black Sea: max |quintic - cubic| at equal parameter = %.3f units\n", worst);
}

TEST(ContourTest, ArcLengthParametrisationConverges) {
  const Points p = black_sea();
  ContourOptions o;
  o.parametrisation = Parametrisation::kArcLength;
  o.degree = 3;
  const SplineContour cubic(p.x, p.y, p.corner, o);
  EXPECT_GT(cubic.arc_length_iterations(), 2);
  EXPECT_LT(cubic.arc_length_iterations(), 60);
  // The fixed point: every knot spacing is the arc length of its segment.
  for (int k = 0; k < cubic.num_points(); ++k)
    EXPECT_NEAR(cubic.arc_length(cubic.knot(k), cubic.knot(k + 1)) / (cubic.knot(k + 1) - cubic.knot(k)), 1.0, 1e-13);
  // The quintic is built on the cubic's spacings (the paper's advice, §4.6): close, not equal.
  o.degree = 5;
  const SplineContour c(p.x, p.y, p.corner, o);
  EXPECT_DOUBLE_EQ(c.period(), cubic.period());
  EXPECT_NEAR(c.period() / c.arc_length(0.0, c.period()), 1.0, 1e-2);
  // Speed ~ 1 everywhere (an arc-length parameter), unlike the index parameter.
  for (double s = 0.0; s < c.period(); s += c.period() / 200) {
    const PlanePoint d = c.derivative(s);
    EXPECT_NEAR(std::hypot(d.x, d.y), 1.0, 0.25) << s;
  }
}

TEST(ContourTest, RefusesThreeOrFiveCorners) {
  Points p = black_sea();
  p.corner[10] = false;
  try {
    SplineContour c(p.x, p.y, p.corner);
    FAIL() << "3 corners accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("found 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("points 1, 7, 13"), std::string::npos) << e.what();
  }
  p.corner[10] = true;
  p.corner[4] = true;
  try {
    SplineContour c(p.x, p.y, p.corner);
    FAIL() << "5 corners accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("found 5"), std::string::npos) << e.what();
  }
}

TEST(ContourTest, RefusesASelfIntersectingContourAndSaysWhere) {
  Points p = black_sea();
  // Pull the north-east corner down across the south side.
  p.x[10] = 20.0;
  p.y[10] = -80.0;
  try {
    SplineContour c(p.x, p.y, p.corner);
    FAIL() << "self-intersecting contour accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("intersects itself"), std::string::npos) << m;
    EXPECT_NE(m.find("between points"), std::string::npos) << m;
    EXPECT_NE(m.find("near ("), std::string::npos) << m;
  }
  // A figure-eight with the corners in place.
  const std::vector<double> x{0, 100, 0, 100, 0, 50}, y{0, 0, 100, 100, 50, 40};
  EXPECT_THROW(SplineContour(x, y, {true, true, false, true, true, false}), InputError);
}

TEST(ContourTest, RefusesClockwiseAndRepeatedPoints) {
  const std::vector<double> x{0, 0, 100, 100}, y{0, 50, 50, 0};  // clockwise rectangle
  try {
    SplineContour c(x, y, {true, true, true, true});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("clockwise"), std::string::npos) << e.what();
  }
  const std::vector<double> x2{0, 100, 100, 100, 0}, y2{0, 0, 50, 50, 50};
  EXPECT_THROW(SplineContour(x2, y2, {true, true, false, true, true}), InputError);
}

TEST(ContourTest, UniformNodesHaveEqualChordsToRoundOff) {
  const Points p = black_sea();
  const SplineContour c(p.x, p.y, p.corner);
  UniformStats st;
  const BoundaryNodes n = uniform_boundary_nodes(c, 131, 101, {}, &st);
  ASSERT_EQ(n.count(), 2 * 130 + 2 * 100);
  for (int s = 0; s < 4; ++s) {
    const Side side = static_cast<Side>(s);
    const std::vector<double> par = side_parameters(c, n, side);
    EXPECT_DOUBLE_EQ(par.front(), c.side_begin(side));
    EXPECT_DOUBLE_EQ(par.back(), c.side_end(side));
    double lo = 1e300, hi = 0.0;
    for (std::size_t k = 1; k < par.size(); ++k) {
      const PlanePoint a = c.point(par[k - 1]), b = c.point(par[k]);
      const double d = std::hypot(b.x - a.x, b.y - a.y);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    EXPECT_LT((hi - lo) / hi, 5e-12) << side_name(side);  // round-off: ~4 ulp of s per node
    EXPECT_LE(st.iterations[static_cast<std::size_t>(s)], 25) << side_name(side);
    std::printf("[ info ] mode 2, %s side: %d step corrections, chord spread %.1e\n", side_name(side),
                st.iterations[static_cast<std::size_t>(s)], (hi - lo) / hi);
  }
}

}  // namespace
}  // namespace aq::curvilinear::unit_curvilinear_contour_test

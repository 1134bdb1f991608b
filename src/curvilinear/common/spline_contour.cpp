// SPDX-License-Identifier: GPL-3.0-or-later
// Spline contour with exact right-angle corners; see spline_contour.hpp (seed 000 eqs. (5)–(15),
// (55)–(91); digest izogrid.md §4).
#include "curvilinear/common/spline_contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "curvilinear/common/periodic_spline.hpp"

namespace aq::curvilinear {

namespace {

// Rotation of a side into the unfolded frame (eq. (9)): primed = R_side * original.
PlanePoint rotate_to_unfolded(int side, double vx, double vy) {
  switch (side) {
    case 0:
      return {vx, vy};  // south: unrotated
    case 1:
      return {vy, -vx};  // east: 90° clockwise
    case 2:
      return {-vx, -vy};  // north: 180°
    default:
      return {-vy, vx};  // west: 270° clockwise
  }
}
// Inverse rotation (eqs. (11)–(15) before re-orienting north and west).
PlanePoint rotate_back(int side, double vx, double vy) {
  switch (side) {
    case 0:
      return {vx, vy};
    case 1:
      return {-vy, vx};
    case 2:
      return {-vx, -vy};
    default:
      return {vy, -vx};
  }
}

// 20-point Gauss–Legendre nodes on [0, 1] and weights (computed once, Newton on P_20).
struct GaussLegendre {
  static constexpr int kN = 20;
  std::array<double, kN> x{}, w{};
  GaussLegendre() {
    const int n = kN;
    for (int i = 0; i < (n + 1) / 2; ++i) {
      double z = std::cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5));
      double pp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p1 = 1.0, p2 = 0.0;
        for (int j = 0; j < n; ++j) {
          const double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * j + 1.0) * z * p2 - j * p3) / (j + 1.0);
        }
        pp = n * (z * p1 - p2) / (z * z - 1.0);
        const double dz = p1 / pp;
        z -= dz;
        if (std::fabs(dz) < 1e-16) break;
      }
      const double wi = 2.0 / ((1.0 - z * z) * pp * pp);
      x[static_cast<std::size_t>(i)] = 0.5 * (1.0 - z);
      x[static_cast<std::size_t>(n - 1 - i)] = 0.5 * (1.0 + z);
      w[static_cast<std::size_t>(i)] = 0.5 * wi;
      w[static_cast<std::size_t>(n - 1 - i)] = 0.5 * wi;
    }
  }
};
const GaussLegendre& gauss_legendre() {
  static const GaussLegendre gl;
  return gl;
}

double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Do closed segments p1-p2 and q1-q2 intersect (including touching and collinear overlap)?
bool segments_intersect(const PlanePoint& p1, const PlanePoint& p2, const PlanePoint& q1, const PlanePoint& q2) {
  const double d1 = cross2(q2.x - q1.x, q2.y - q1.y, p1.x - q1.x, p1.y - q1.y);
  const double d2 = cross2(q2.x - q1.x, q2.y - q1.y, p2.x - q1.x, p2.y - q1.y);
  const double d3 = cross2(p2.x - p1.x, p2.y - p1.y, q1.x - p1.x, q1.y - p1.y);
  const double d4 = cross2(p2.x - p1.x, p2.y - p1.y, q2.x - p1.x, q2.y - p1.y);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  auto on_segment = [](const PlanePoint& a, const PlanePoint& b, const PlanePoint& c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
  };
  if (d1 == 0 && on_segment(q1, q2, p1)) return true;
  if (d2 == 0 && on_segment(q1, q2, p2)) return true;
  if (d3 == 0 && on_segment(p1, p2, q1)) return true;
  if (d4 == 0 && on_segment(p1, p2, q2)) return true;
  return false;
}

}  // namespace

const char* side_name(Side side) {
  switch (side) {
    case Side::kSouth:
      return "south";
    case Side::kEast:
      return "east";
    case Side::kNorth:
      return "north";
    case Side::kWest:
      return "west";
  }
  return "?";
}

SplineContour::SplineContour(std::vector<double> x, std::vector<double> y, const std::vector<bool>& corner,
                             const ContourOptions& options)
    : x_(std::move(x)),
      y_(std::move(y)),
      degree_(options.degree),
      param_(options.parametrisation),
      source_(options.source) {
  if (degree_ != 3 && degree_ != 5)
    throw InternalError(
        fmt::format("{}: spline degree {} is not supported (3 = cubic, 5 = quintic)", source_, degree_));
  const int n = static_cast<int>(x_.size());
  if (y_.size() != x_.size() || corner.size() != x_.size())
    throw InternalError("SplineContour: x, y and corner flags differ in length");
  // Corners: point 0 is SW by definition; then exactly three more.
  std::vector<int> found{0};
  for (int k = 1; k < n; ++k)
    if (corner[static_cast<std::size_t>(k)]) found.push_back(k);
  if (found.size() != 4) {
    std::string list;
    for (std::size_t i = 0; i < found.size(); ++i) list += fmt::format("{}{}", i ? ", " : "", found[i] + 1);
    throw InputError(
        fmt::format("{}: the contour needs exactly 4 corners (the first point is the south-west corner, then the "
                    "south-east, north-east and north-west corners are marked); found {} (points {})",
                    source_, found.size(), list));
  }
  if (n < 4) throw InputError(fmt::format("{}: a contour needs at least 4 points, got {}", source_, n));
  for (int i = 0; i < 4; ++i) corners_[static_cast<std::size_t>(i)] = found[static_cast<std::size_t>(i)];
  for (int k = 0; k < n; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    if (!std::isfinite(x_[ku]) || !std::isfinite(y_[ku]))
      throw InputError(fmt::format("{}: point {} ({}, {}) is not finite", source_, k + 1, x_[ku], y_[ku]));
    const auto k1 = static_cast<std::size_t>((k + 1) % n);
    if (x_[ku] == x_[k1] && y_[ku] == y_[k1])
      throw InputError(fmt::format("{}: points {} and {} coincide at ({}, {})", source_, k + 1,
                                   static_cast<int>(k1) + 1, x_[ku], y_[ku]));
  }
  // Orientation of the control polygon first: a clockwise list unfolds into loops.
  {
    double area2 = 0.0;
    for (int k = 0; k < n; ++k) {
      const auto ku = static_cast<std::size_t>(k), k1 = static_cast<std::size_t>((k + 1) % n);
      area2 += x_[ku] * y_[k1] - y_[ku] * x_[k1];
    }
    if (!(area2 > 0.0))
      throw InputError(fmt::format(
          "{}: the control points run clockwise (signed area {:.4g}); list them counter-clockwise starting at "
          "the south-west corner",
          source_, 0.5 * area2));
  }
  side_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    int s = 0;
    while (s < 3 && k >= corners_[static_cast<std::size_t>(s + 1)]) ++s;
    side_[static_cast<std::size_t>(k)] = s;
  }

  // Knot spacings: 1 (index) or iterated arc length with the cubic spline (§4.6b).
  std::vector<double> h(static_cast<std::size_t>(n), 1.0);
  if (param_ == Parametrisation::kArcLength) {
    for (int k = 0; k < n; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      const auto k1 = static_cast<std::size_t>((k + 1) % n);
      h[ku] = std::hypot(x_[k1] - x_[ku], y_[k1] - y_[ku]);  // chord lengths (7)
    }
    const int wanted_degree = degree_;
    degree_ = 3;
    const auto& gl = gauss_legendre();
    bool converged = false;
    double change = 0.0;
    for (int it = 1; it <= options.arc_length_max_iterations; ++it) {
      fit(h);
      change = 0.0;
      std::vector<double> hn(h.size());
      for (int k = 0; k < n; ++k) {
        double len = 0.0;
        for (int q = 0; q < GaussLegendre::kN; ++q) {
          const PlanePoint d = segment_eval(k, gl.x[static_cast<std::size_t>(q)], 1);
          len += gl.w[static_cast<std::size_t>(q)] * std::hypot(d.x, d.y);
        }
        len *= h[static_cast<std::size_t>(k)];  // |dC/ds| ds over the segment
        hn[static_cast<std::size_t>(k)] = len;
        change = std::max(change, std::fabs(len / h[static_cast<std::size_t>(k)] - 1.0));
      }
      h = hn;
      arc_iterations_ = it;
      if (change < options.arc_length_tolerance) {
        converged = true;
        break;
      }
    }
    if (!converged)
      throw NumericalError(fmt::format(
          "{}: the arc-length parametrisation did not converge in {} iterations (last relative change {:.3g}); "
          "use the index parametrisation or smooth the control points",
          source_, options.arc_length_max_iterations, change));
    degree_ = wanted_degree;
  }
  fit(h);
  check_geometry(options);
}

void SplineContour::fit(const std::vector<double>& h) {
  const int n = num_points();
  const auto nu = static_cast<std::size_t>(n);
  h_ = h;
  knots_.assign(nu + 1, 0.0);
  for (std::size_t k = 0; k < nu; ++k) knots_[k + 1] = knots_[k] + h_[k];
  // Unfolded differences (8)–(9).
  std::vector<double> dfx(nu), dfy(nu);
  for (int k = 0; k < n; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const auto k1 = static_cast<std::size_t>((k + 1) % n);
    const PlanePoint d = rotate_to_unfolded(side_[ku], x_[k1] - x_[ku], y_[k1] - y_[ku]);
    dfx[ku] = d.x;
    dfy[ku] = d.y;
  }
  dxu_.assign(nu, 0.0);
  dyu_.assign(nu, 0.0);
  ddxu_.assign(nu, 0.0);
  ddyu_.assign(nu, 0.0);
  if (degree_ == 3) {
    periodic_cubic_slopes(h_, dfx, dxu_);
    periodic_cubic_slopes(h_, dfy, dyu_);
  } else {
    periodic_quintic_derivatives(h_, dfx, dxu_, ddxu_);
    periodic_quintic_derivatives(h_, dfy, dyu_, ddyu_);
  }
  // Back-rotation per segment (11)–(15): both ends of segment k use the frame of its side.
  seg_.resize(nu);
  for (int k = 0; k < n; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const auto k1 = static_cast<std::size_t>((k + 1) % n);
    const int s = side_[ku];
    const PlanePoint dl = rotate_back(s, dxu_[ku], dyu_[ku]);
    const PlanePoint dr = rotate_back(s, dxu_[k1], dyu_[k1]);
    const PlanePoint ddl = rotate_back(s, ddxu_[ku], ddyu_[ku]);
    const PlanePoint ddr = rotate_back(s, ddxu_[k1], ddyu_[k1]);
    seg_[ku] = {dl.x, dl.y, dr.x, dr.y, ddl.x, ddl.y, ddr.x, ddr.y};
  }
}

double SplineContour::side_begin(Side side) const {
  return knots_[static_cast<std::size_t>(corners_[static_cast<std::size_t>(side)])];
}

double SplineContour::side_end(Side side) const {
  if (side == Side::kWest) return knots_.back();
  return knots_[static_cast<std::size_t>(corners_[static_cast<std::size_t>(side) + 1])];
}

double SplineContour::side_parameter(Side side, double t) const {
  const double a = side_begin(side), b = side_end(side);
  if (side == Side::kSouth || side == Side::kEast) return a + t * (b - a);
  return b - t * (b - a);  // the contour runs north and west backwards
}

Side SplineContour::side_of_segment(int segment) const {
  return static_cast<Side>(side_[static_cast<std::size_t>(segment)]);
}

int SplineContour::segment_of(double s) const {
  const double per = period();
  double t = std::fmod(s, per);
  if (t < 0.0) t += per;
  auto it = std::upper_bound(knots_.begin(), knots_.end(), t);
  int k = static_cast<int>(it - knots_.begin()) - 1;
  return std::clamp(k, 0, num_points() - 1);
}

PlanePoint SplineContour::segment_eval(int segment, double p, int order) const {
  const int n = num_points();
  const auto k = static_cast<std::size_t>(segment);
  const auto k1 = static_cast<std::size_t>((segment + 1) % n);
  const HermiteBasis& b = hermite_basis(degree_);
  const SegmentData& sd = seg_[k];
  const double h = h_[k];
  const double bfl = poly_derivative(b.fl, p, order), bfr = poly_derivative(b.fr, p, order);
  const double bdl = h * poly_derivative(b.dl, p, order), bdr = h * poly_derivative(b.dr, p, order);
  double x = x_[k] * bfl + x_[k1] * bfr + sd.dlx * bdl + sd.drx * bdr;
  double y = y_[k] * bfl + y_[k1] * bfr + sd.dly * bdl + sd.dry * bdr;
  if (degree_ == 5) {
    const double bddl = h * h * poly_derivative(b.ddl, p, order), bddr = h * h * poly_derivative(b.ddr, p, order);
    x += sd.ddlx * bddl + sd.ddrx * bddr;
    y += sd.ddly * bddl + sd.ddry * bddr;
  }
  if (order > 0) {
    const double scale = std::pow(h, -order);
    x *= scale;
    y *= scale;
  }
  return {x, y};
}

PlanePoint SplineContour::point(double s) const {
  const int k = segment_of(s);
  const double per = period();
  double t = std::fmod(s, per);
  if (t < 0.0) t += per;
  const auto ku = static_cast<std::size_t>(k);
  return segment_eval(k, (t - knots_[ku]) / h_[ku], 0);
}

PlanePoint SplineContour::derivative(double s, int order) const {
  const int k = segment_of(s);
  const double per = period();
  double t = std::fmod(s, per);
  if (t < 0.0) t += per;
  const auto ku = static_cast<std::size_t>(k);
  return segment_eval(k, (t - knots_[ku]) / h_[ku], order);
}

PlanePoint SplineContour::side_derivative(Side side, double s, int order) const {
  const double a = side_begin(side), b = side_end(side);
  const double t = std::clamp(s, a, b);
  const int first = corners_[static_cast<std::size_t>(side)];
  const int last = (side == Side::kWest ? num_points() : corners_[static_cast<std::size_t>(side) + 1]) - 1;
  auto it = std::upper_bound(knots_.begin(), knots_.end(), t);
  const int k = std::clamp(static_cast<int>(it - knots_.begin()) - 1, first, last);
  const auto ku = static_cast<std::size_t>(k);
  return segment_eval(k, (t - knots_[ku]) / h_[ku], order);
}

double SplineContour::arc_length(double s0, double s1) const {
  if (s1 < s0) throw InternalError("SplineContour::arc_length: s1 < s0");
  const auto& gl = gauss_legendre();
  const double per = period();
  const int n = num_points();
  // Shift s0 into [0, per) and walk segments, allowing one wrap.
  double shift = std::floor(s0 / per) * per;
  double a = s0 - shift, b = s1 - shift;
  double total = 0.0;
  int k = segment_of(a);
  double base = 0.0;  // added to knots when wrapping
  while (a < b) {
    const auto ku = static_cast<std::size_t>(k);
    const double ks = knots_[ku] + base, ke = knots_[ku + 1] + base;
    const double e = std::min(b, ke);
    if (e > a) {
      const double p0 = (a - ks) / h_[ku], p1 = (e - ks) / h_[ku];
      double sum = 0.0;
      for (int q = 0; q < GaussLegendre::kN; ++q) {
        const double p = p0 + (p1 - p0) * gl.x[static_cast<std::size_t>(q)];
        const PlanePoint d = segment_eval(k, p, 1);
        sum += gl.w[static_cast<std::size_t>(q)] * std::hypot(d.x, d.y);
      }
      total += sum * (e - a);
    }
    a = e;
    ++k;
    if (k == n) {
      k = 0;
      base += per;
    }
  }
  return total;
}

double SplineContour::curvature(double s) const {
  const PlanePoint d1 = derivative(s, 1), d2 = derivative(s, 2);
  const double sp = std::hypot(d1.x, d1.y);
  return (d1.x * d2.y - d1.y * d2.x) / (sp * sp * sp);
}

std::vector<PlanePoint> SplineContour::sample(int per_segment) const {
  const int n = num_points();
  std::vector<PlanePoint> out;
  out.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(per_segment));
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < per_segment; ++i) out.push_back(segment_eval(k, static_cast<double>(i) / per_segment, 0));
  return out;
}

void SplineContour::check_geometry(const ContourOptions& options) const {
  const int m = std::max(8, options.check_samples_per_segment);
  const std::vector<PlanePoint> pts = sample(m);
  const std::size_t ns = pts.size();
  // Orientation: the shoelace area must be positive (counter-clockwise).
  double area2 = 0.0;
  for (std::size_t i = 0; i < ns; ++i) {
    const PlanePoint& a = pts[i];
    const PlanePoint& b = pts[(i + 1) % ns];
    area2 += a.x * b.y - a.y * b.x;
  }
  // Self-intersection: sweep the polyline pieces by their minimum x.
  std::vector<std::size_t> order(ns);
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto xmin = [&](std::size_t i) { return std::min(pts[i].x, pts[(i + 1) % ns].x); };
  auto xmax = [&](std::size_t i) { return std::max(pts[i].x, pts[(i + 1) % ns].x); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return xmin(a) < xmin(b); });
  for (std::size_t oi = 0; oi < ns; ++oi) {
    const std::size_t i = order[oi];
    const double xi1 = xmax(i);
    const double yi0 = std::min(pts[i].y, pts[(i + 1) % ns].y), yi1 = std::max(pts[i].y, pts[(i + 1) % ns].y);
    for (std::size_t oj = oi + 1; oj < ns && xmin(order[oj]) <= xi1; ++oj) {
      const std::size_t j = order[oj];
      const std::size_t gap = i > j ? i - j : j - i;
      if (gap <= 1 || gap == ns - 1) continue;  // neighbours share an end point
      const double yj0 = std::min(pts[j].y, pts[(j + 1) % ns].y), yj1 = std::max(pts[j].y, pts[(j + 1) % ns].y);
      if (yj1 < yi0 || yj0 > yi1) continue;
      if (!segments_intersect(pts[i], pts[(i + 1) % ns], pts[j], pts[(j + 1) % ns])) continue;
      const int si = static_cast<int>(std::min(i, j) / static_cast<std::size_t>(m));
      const int sj = static_cast<int>(std::max(i, j) / static_cast<std::size_t>(m));
      const int n = num_points();
      const PlanePoint& at = pts[std::min(i, j)];
      if (si == sj)
        throw InputError(fmt::format(
            "{}: the contour loops on itself on the {} side between points {} and {} near ({:.4g}, {:.4g}); move "
            "these points apart or add a point between them",
            source_, side_name(side_of_segment(si)), si + 1, (si + 1) % n + 1, at.x, at.y));
      throw InputError(fmt::format(
          "{}: the contour intersects itself: the {} side between points {} and {} crosses the {} side between "
          "points {} and {} near ({:.4g}, {:.4g}); move the control points so the contour is a simple closed "
          "curve",
          source_, side_name(side_of_segment(si)), si + 1, (si + 1) % n + 1, side_name(side_of_segment(sj)), sj + 1,
          (sj + 1) % n + 1, at.x, at.y));
    }
  }
  if (!(area2 > 0.0))
    throw InputError(fmt::format(
        "{}: the contour runs clockwise (signed area {:.4g}); list the points counter-clockwise starting at "
        "the south-west corner",
        source_, 0.5 * area2));
}

}  // namespace aq::curvilinear

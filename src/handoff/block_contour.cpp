// SPDX-License-Identifier: GPL-3.0-or-later
// A block's projection and contour (see block_contour.hpp).
#include "handoff/block_contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::handoff {

namespace {

constexpr double kStereographicBeyondDeg = 75.0;  // |φ| beyond which the projection is ST
constexpr double kSlope = 0.5;                    // steepest inset change per unit along a side
constexpr int kOutlineSamples = 16;               // per side, for the projection choice

// Initial bearing (degrees clockwise from north) from a to b on the sphere.
double bearing_deg(const curvilinear::GeoPoint& a, const curvilinear::GeoPoint& b) {
  const double p1 = a.lat_deg * kDegToRad, p2 = b.lat_deg * kDegToRad;
  const double dl = (b.lon_deg - a.lon_deg) * kDegToRad;
  return std::atan2(std::sin(dl) * std::cos(p2),
                    std::cos(p1) * std::sin(p2) - std::sin(p1) * std::cos(p2) * std::cos(dl)) *
         kRadToDeg;
}

// Smallest 1, 2 or 5 × 10^k >= q (q > 0).
double nice_up(double q) {
  const double e = std::pow(10.0, std::floor(std::log10(q)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * e >= q * (1.0 - 1e-12)) return m * e;
  return 10.0 * e;
}

// (s, t) of a point `x` along side `side` at inset `e` (see the file comment's sides).
std::array<double, 2> side_point(int side, double x, double e) {
  switch (side) {
    case 0:
      return {x, e};
    case 1:
      return {1.0 - e, x};
    case 2:
      return {x, 1.0 - e};
    default:
      return {e, x};
  }
}

// Outline points (s, t), counter-clockwise from SW, `per_side` per side.
std::vector<std::array<double, 2>> outline(int per_side) {
  std::vector<std::array<double, 2>> p;
  for (int k = 0; k < per_side; ++k) p.push_back({static_cast<double>(k) / per_side, 0.0});
  for (int k = 0; k < per_side; ++k) p.push_back({1.0, static_cast<double>(k) / per_side});
  for (int k = 0; k < per_side; ++k) p.push_back({1.0 - static_cast<double>(k) / per_side, 1.0});
  for (int k = 0; k < per_side; ++k) p.push_back({0.0, 1.0 - static_cast<double>(k) / per_side});
  return p;
}

}  // namespace

BoxFrame::BoxFrame(const BlockBox& box, const PoleRotation& rotation)
    : box_(box), rotation_(rotation), rotate_(box.lattice_system && !rotation.identity()) {
  const double h = box_.lat_max_deg - box_.lat_min_deg;
  const double off = std::min(1.0, 0.25 * h);
  if (box_.lat_max_deg >= 90.0 - 1e-9) {
    box_.lat_max_deg = 90.0 - off;
    trimmed_ = true;
  }
  if (box_.lat_min_deg <= -90.0 + 1e-9) {
    box_.lat_min_deg = -90.0 + off;
    trimmed_ = true;
  }
  if (box_.mercator_rows) {
    y_min_deg_ = mercator_y_deg(box_.lat_min_deg);
    y_max_deg_ = mercator_y_deg(box_.lat_max_deg);
  }
}

curvilinear::GeoPoint BoxFrame::system(double s, double t) const {
  const double lon = box_.lon_min_deg + s * (box_.lon_max_deg - box_.lon_min_deg);
  if (box_.mercator_rows) return {lon, mercator_lat_deg(y_min_deg_ + t * (y_max_deg_ - y_min_deg_))};
  return {lon, box_.lat_min_deg + t * (box_.lat_max_deg - box_.lat_min_deg)};
}

curvilinear::GeoPoint BoxFrame::geographic(double s, double t) const {
  const curvilinear::GeoPoint p = system(s, t);
  if (!rotate_) return p;
  curvilinear::GeoPoint g;
  rotation_.to_geographic(p.lon_deg, p.lat_deg, g.lon_deg, g.lat_deg);
  return g;
}

double SideInsets::at(int side, double x) const {
  if (n <= 0) return 0.0;
  const auto& v = e[static_cast<std::size_t>(side)];
  const double p = x * n - 0.5;
  if (p <= 0.0) return v.front();
  if (p >= n - 1) return v.back();
  const auto k = static_cast<std::size_t>(p);
  const double f = p - static_cast<double>(k);
  return v[k] + f * (v[k + 1] - v[k]);
}

double SideInsets::min_over(int side, double a, double b) const {
  if (n <= 0) return 0.0;
  if (b < a) std::swap(a, b);
  double m = std::min(at(side, a), at(side, b));
  const auto& v = e[static_cast<std::size_t>(side)];
  for (int k = 0; k < n; ++k) {
    const double x = (k + 0.5) / n;
    if (x > a && x < b) m = std::min(m, v[static_cast<std::size_t>(k)]);
  }
  return m;
}

double SideInsets::max(int side) const {
  const auto& v = e[static_cast<std::size_t>(side)];
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

SideInsets shrink_to_wet(const BoxFrame& frame, const Bitmap& filled, const Lattice& lat, const PoleRotation& rotation,
                         double max_inset) {
  if (filled.nx() != lat.nx || filled.ny() != lat.ny) throw InternalError("shrink_to_wet: bitmap and lattice differ");
  const double cap = std::clamp(max_inset, 0.0, 0.45);
  const BlockBox& b = frame.box();
  const std::array<double, 2> extent_px = box_extent_px(b, lat, rotation);
  SideInsets out;
  out.max_inset = cap;
  out.n = static_cast<int>(std::clamp(2.0 * std::ceil(std::max(extent_px[0], extent_px[1])), 32.0, 1024.0));
  const int n = out.n;
  const auto wet = [&](double s, double t) {
    const curvilinear::GeoPoint p = frame.system(s, t);
    const mask::LonLat q = b.lattice_system ? mask::LonLat{p.lon_deg, p.lat_deg}
                                            : mask::geographic_to_lattice(rotation, {p.lon_deg, p.lat_deg});
    const auto px = pixel_holding(lat, q);
    return px && filled.get(px->i, px->j);
  };
  const int m_max = static_cast<int>(std::floor(cap * n));
  const double step = 1.0 / n;
  for (int side = 0; side < 4; ++side) {
    auto& e = out.e[static_cast<std::size_t>(side)];
    e.assign(static_cast<std::size_t>(n), 0.0);
    // 1. Raw insets: consecutive dry cells from the side inward.
    for (int k = 0; k < n; ++k) {
      int m = 0;
      while (m < m_max) {
        const auto st = side_point(side, (k + 0.5) * step, (m + 0.5) * step);
        if (wet(st[0], st[1])) break;
        ++m;
      }
      e[static_cast<std::size_t>(k)] = std::min(m * step, cap);
    }
    // 2-3. Corner zones and the slope-limited lower envelope, until nothing changes.
    const double zone = cap + step;
    for (int pass = 0; pass < 4 * n + 4; ++pass) {
      const std::vector<double> before = e;
      double lo = 1.0, hi = 1.0;
      for (int k = 0; k < n; ++k) {
        const double x = (k + 0.5) * step;
        if (x < zone) lo = std::min(lo, e[static_cast<std::size_t>(k)]);
        if (x > 1.0 - zone) hi = std::min(hi, e[static_cast<std::size_t>(k)]);
      }
      for (int k = 0; k < n; ++k) {
        const double x = (k + 0.5) * step;
        auto& v = e[static_cast<std::size_t>(k)];
        if (x < zone) v = std::min(v, lo);
        if (x > 1.0 - zone) v = std::min(v, hi);
      }
      for (std::size_t k = 1; k < e.size(); ++k) e[k] = std::min(e[k], e[k - 1] + kSlope * step);
      for (std::size_t k = e.size() - 1; k-- > 0;) e[k] = std::min(e[k], e[k + 1] + kSlope * step);
      if (e == before) break;
    }
  }
  return out;
}

curvilinear::ProjectionParams choose_projection(const BoxFrame& frame) {
  curvilinear::ProjectionParams p;
  const curvilinear::GeoPoint c = frame.geographic(0.5, 0.5);
  p.rlat_deg = c.lat_deg;
  p.rlon_deg = c.lon_deg;
  p.rota_deg = 0.0;
  if (frame.rotated()) {  // the box's meridian is not the geographic one: stand the box upright
    // The box's central meridian is a great circle through c: aim at its far end for accuracy.
    const double r = bearing_deg(c, frame.geographic(0.5, 1.0));
    p.rota_deg = std::round(r * 1e9) / 1e9 + 0.0;
  }
  double max_lat = 0.0;
  for (const auto& st : outline(kOutlineSamples))
    max_lat = std::max(max_lat, std::abs(frame.geographic(st[0], st[1]).lat_deg));
  p.kind = max_lat > kStereographicBeyondDeg ? curvilinear::ProjectionKind::kStereographic
                                             : curvilinear::ProjectionKind::kMercator;
  p.uscale = 1.0;
  const curvilinear::Projection unit(p);
  double m = 0.0;
  for (const auto& st : outline(kOutlineSamples)) {
    const auto g = frame.geographic(st[0], st[1]);
    const auto q = unit.forward(g.lon_deg, g.lat_deg);
    m = std::max({m, std::abs(q.x), std::abs(q.y)});
  }
  if (!std::isfinite(m) || m <= 0.0) {
    throw InputError(fmt::format("block [{}, {}] x [{}, {}]: the block's outline cannot be projected",
                                 frame.box().lon_min_deg, frame.box().lon_max_deg, frame.box().lat_min_deg,
                                 frame.box().lat_max_deg));
  }
  p.uscale = nice_up(m / 100.0);
  return p;
}

BlockContour block_contour(const BoxFrame& frame, const SideInsets& insets, int points_per_side) {
  if (points_per_side < 2)  // blocks.points_per_side is validated at load
    throw InternalError(fmt::format("block contour: {} points per side (>= 2)", points_per_side));
  BlockContour c;
  c.projection = choose_projection(frame);
  c.insets = insets;
  c.trimmed = frame.trimmed();
  const curvilinear::Projection proj(c.projection);
  const int P = points_per_side;
  // Corners (s, t) from the insets at the ends of the sides: the minimum over the end's reach
  // (max_inset + 1/P covers the first control interval whatever the neighbouring side's inset).
  const double reach = insets.max_inset + 1.0 / P;
  const auto end = [&](int side, int at_end) {
    return at_end == 0 ? insets.min_over(side, 0.0, reach) : insets.min_over(side, 1.0 - reach, 1.0);
  };
  const std::array<std::array<double, 2>, 4> corner{{{end(3, 0), end(0, 0)},
                                                     {1.0 - end(1, 0), end(0, 1)},
                                                     {1.0 - end(1, 1), 1.0 - end(2, 1)},
                                                     {end(3, 1), 1.0 - end(2, 0)}}};
  for (int side = 0; side < 4; ++side) {
    const auto& a = corner[static_cast<std::size_t>(side)];
    const auto& b = corner[static_cast<std::size_t>((side + 1) % 4)];
    c.corners[static_cast<std::size_t>(side)] = side * P;
    // The coordinate running along the side: s for S/N, t for E/W.
    const int along = (side == 0 || side == 2) ? 0 : 1;
    const double x0 = a[static_cast<std::size_t>(along)], x1 = b[static_cast<std::size_t>(along)];
    const double h = (x1 - x0) / P;
    for (int k = 0; k < P; ++k) {
      const double x = x0 + (static_cast<double>(k) / P) * (x1 - x0);
      // The corner keeps its inset; the others the profile's minimum over both neighbouring
      // intervals (step 4 of the file comment).
      const std::array<double, 4> corner_inset{a[1], 1.0 - a[0], 1.0 - a[1], a[0]};
      const double inset =
          k == 0 ? corner_inset[static_cast<std::size_t>(side)] : insets.min_over(side, x - h, x + h);
      const auto st = side_point(side, x, inset);
      const auto g = frame.geographic(st[0], st[1]);
      const auto q = proj.forward(g.lon_deg, g.lat_deg);
      if (!std::isfinite(q.x) || !std::isfinite(q.y)) {
        throw InputError(fmt::format("block contour point ({}, {}) is at a singularity of the {} projection", g.lon_deg,
                                     g.lat_deg, std::string(name_of(c.projection.kind))));
      }
      c.x.push_back(q.x);
      c.y.push_back(q.y);
    }
  }
  return c;
}

}  // namespace aq::handoff

// SPDX-License-Identifier: GPL-3.0-or-later
// Corridor edits of the sampled elevation (see elevation_edits.hpp).
#include "raster/elevation_edits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/sphere_vectors.hpp"
#include "core/types.hpp"

namespace aq::raster {

namespace {

using V3 = sphere::Vec3;

using sphere::cross;
using sphere::dot;
using sphere::norm;
V3 unit(double lon_deg, double lat_deg) { return sphere::unit_deg(lon_deg, lat_deg); }

// Longitude, latitude (degrees) of a unit vector.
void lonlat(const V3& v, double& lon, double& lat) {
  lon = std::atan2(v[1], v[0]) * kRadToDeg;
  lat = std::asin(std::clamp(v[2], -1.0, 1.0)) * kRadToDeg;
}

// The longest arc indexed in one piece (degrees): longer arcs are split, so that the bulge of a
// great circle beyond its end points' latitudes stays below kBulgeDeg (L²/8·tan φ for L = 1°: 0.12° at 89°).
constexpr double kMaxArcDeg = 1.0;
constexpr double kBulgeDeg = 0.2;

constexpr std::uint64_t kFnvOffset = 1469598103934665603ULL, kFnvPrime = 1099511628211ULL;
void fnv(std::uint64_t& h, const void* p, std::size_t n) {
  const auto* b = static_cast<const unsigned char*>(p);
  for (std::size_t k = 0; k < n; ++k) {
    h ^= b[k];
    h *= kFnvPrime;
  }
}

}  // namespace

ElevationEdits::ElevationEdits(std::vector<Corridor> corridors) : corridors_(std::move(corridors)) {
  struct Piece {
    V3 a, b;
    double r_deg;
    std::int32_t corridor;
  };
  std::vector<Piece> pieces[2];  // channels, blockages
  for (std::size_t c = 0; c < corridors_.size(); ++c) {
    const Corridor& k = corridors_[c];
    const std::size_t nv = k.lon_deg.size();
    const auto fail = [&](const std::string& why) {
      throw InputError(fmt::format("edit corridor {} \"{}\": {}", c, k.name, why));
    };
    if (nv == 0 || k.lat_deg.size() != nv) fail("needs at least one vertex (as many latitudes as longitudes)");
    const std::size_t arcs = nv == 1 ? 1 : nv - 1;
    if (k.half_width_deg.size() != arcs) fail(fmt::format("{} half-widths for {} arcs", k.half_width_deg.size(), arcs));
    if (!std::isfinite(k.elevation_m)) fail("elevation is not a finite number");
    if (std::isinf(k.keep_at_or_below_m)) fail("keep_at_or_below_m is infinite");
    for (std::size_t v = 0; v < nv; ++v)
      if (!std::isfinite(k.lon_deg[v]) || !std::isfinite(k.lat_deg[v]) || std::abs(k.lat_deg[v]) > 90.0)
        fail(fmt::format("vertex {} ({}, {}) is not a lon/lat point", v, k.lon_deg[v], k.lat_deg[v]));
    for (const double r : k.half_width_deg)
      if (!(r > 0.0 && r <= 30.0)) fail(fmt::format("half-width {}° is outside (0, 30]", r));
    auto& out = pieces[k.kind == EditKind::kChannel ? 0 : 1];
    if (nv == 1) {
      const V3 a = unit(k.lon_deg[0], k.lat_deg[0]);
      out.push_back({a, a, k.half_width_deg[0], static_cast<std::int32_t>(c)});
      continue;
    }
    for (std::size_t v = 0; v + 1 < nv; ++v) {
      const V3 a = unit(k.lon_deg[v], k.lat_deg[v]), b = unit(k.lon_deg[v + 1], k.lat_deg[v + 1]);
      const double ang = std::atan2(norm(cross(a, b)), dot(a, b)) * kRadToDeg;
      if (ang > 179.0) fail(fmt::format("arc {} joins two (nearly) antipodal points", v));
      const int parts = std::max(1, static_cast<int>(std::ceil(ang / kMaxArcDeg)));
      const double w = ang * kDegToRad;
      V3 prev = a;
      for (int s = 1; s <= parts; ++s) {
        V3 q = b;
        if (s < parts && w > 0.0) {  // spherical linear interpolation
          const double t = static_cast<double>(s) / parts, sw = std::sin(w);
          const double fa = std::sin((1.0 - t) * w) / sw, fb = std::sin(t * w) / sw;
          q = {fa * a[0] + fb * b[0], fa * a[1] + fb * b[1], fa * a[2] + fb * b[2]};
          const double l = norm(q);
          q = {q[0] / l, q[1] / l, q[2] / l};
        }
        out.push_back({prev, q, k.half_width_deg[v], static_cast<std::int32_t>(c)});
        prev = q;
      }
    }
  }
  struct Box {
    double lat_lo, lat_hi, lon_lo, lon_hi;  // lon_hi - lon_lo >= 360: all longitudes
  };
  std::vector<Box> boxes;
  for (const auto& list : pieces)
    for (const Piece& p : list) {
      Arc arc;
      arc.a = p.a;
      arc.b = p.b;
      arc.corridor = p.corridor;
      const Corridor& kc = corridors_[static_cast<std::size_t>(p.corridor)];
      arc.keep = std::isnan(kc.keep_at_or_below_m) ? kc.elevation_m : kc.keep_at_or_below_m;
      arc.sin_r = std::sin(p.r_deg * kDegToRad);
      arc.cos_r = std::cos(p.r_deg * kDegToRad);
      const V3 n = cross(p.a, p.b);
      const double ln = norm(n);
      arc.point = ln < 1e-15;
      if (!arc.point) arc.n = {n[0] / ln, n[1] / ln, n[2] / ln};
      double lon_a = 0, lat_a = 0, lon_b = 0, lat_b = 0;
      lonlat(p.a, lon_a, lat_a);
      lonlat(p.b, lon_b, lat_b);
      double dl = lon_b - lon_a;
      if (dl > 180.0) dl -= 360.0;
      if (dl < -180.0) dl += 360.0;
      const double margin = p.r_deg + kBulgeDeg;
      Box bx{std::min(lat_a, lat_b) - margin, std::max(lat_a, lat_b) + margin, 0.0, 0.0};
      const double top = std::max(std::abs(bx.lat_lo), std::abs(bx.lat_hi));
      if (top >= 88.0) {
        bx.lon_lo = -180.0;
        bx.lon_hi = 180.0 + 360.0;
      } else {
        const double m = margin / std::cos(top * kDegToRad);
        bx.lon_lo = std::min(lon_a, lon_a + dl) - m;
        bx.lon_hi = std::max(lon_a, lon_a + dl) + m;
      }
      arcs_.push_back(arc);
      boxes.push_back(bx);
    }
  // The index (CSR over cells), and per cell the reach (lowest channel, highest blockage).
  const std::int64_t ncell = kCols * kRows;
  std::vector<std::int32_t> count(static_cast<std::size_t>(ncell + 1), 0);
  row_used_.assign(static_cast<std::size_t>(kRows), 0);
  const auto for_cells = [&](const Box& bx, auto&& f) {
    const auto r0 =
        std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((bx.lat_lo + 90.0) / kCellDeg)), 0, kRows - 1);
    const auto r1 =
        std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((bx.lat_hi + 90.0) / kCellDeg)), 0, kRows - 1);
    std::int64_t c0 = static_cast<std::int64_t>(std::floor((bx.lon_lo + 180.0) / kCellDeg));
    std::int64_t c1 = static_cast<std::int64_t>(std::floor((bx.lon_hi + 180.0) / kCellDeg));
    if (c1 - c0 >= kCols - 1) {
      c0 = 0;
      c1 = kCols - 1;
    }
    for (std::int64_t r = r0; r <= r1; ++r)
      for (std::int64_t c = c0; c <= c1; ++c) f(r * kCols + wrap_index(c, kCols), r);
  };
  for (std::size_t k = 0; k < arcs_.size(); ++k)
    for_cells(boxes[k], [&](std::int64_t cell, std::int64_t r) {
      ++count[static_cast<std::size_t>(cell) + 1];
      row_used_[static_cast<std::size_t>(r)] = 1;
    });
  for (std::int64_t c = 0; c < ncell; ++c) count[static_cast<std::size_t>(c + 1)] += count[static_cast<std::size_t>(c)];
  cell_start_ = count;
  cell_arcs_.assign(static_cast<std::size_t>(count.back()), 0);
  for (std::size_t k = 0; k < arcs_.size(); ++k)  // arcs in order within each cell: deterministic
    for_cells(boxes[k], [&](std::int64_t cell, std::int64_t) {
      cell_arcs_[static_cast<std::size_t>(count[static_cast<std::size_t>(cell)]++)] = static_cast<std::int32_t>(k);
    });
}

bool ElevationEdits::inside(const Arc& arc, const V3& p) const {
  if (dot(arc.a, p) >= arc.cos_r) return true;
  if (arc.point) return false;
  if (dot(arc.b, p) >= arc.cos_r) return true;
  if (std::abs(dot(arc.n, p)) > arc.sin_r) return false;
  // Between the ends: p's projection on the great circle lies on the arc from a to b.
  return dot(cross(arc.a, p), arc.n) >= 0.0 && dot(cross(p, arc.b), arc.n) >= 0.0;
}

std::int64_t ElevationEdits::cell_of(double lon_deg, double lat_deg) const {
  const auto r =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((lat_deg + 90.0) / kCellDeg)), 0, kRows - 1);
  const double x = wrap_lon_deg(lon_deg, -180.0) + 180.0;
  const auto c = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(x / kCellDeg)), 0, kCols - 1);
  return r * kCols + c;
}

double ElevationEdits::apply(double lon_deg, double lat_deg, double z) const {
  if (arcs_.empty() || !std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return z;
  const std::int64_t cell = cell_of(lon_deg, lat_deg);
  const std::int32_t b = cell_start_[static_cast<std::size_t>(cell)],
                     e = cell_start_[static_cast<std::size_t>(cell) + 1];
  if (b == e) return z;
  const V3 p = unit(lon_deg, lat_deg);
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  for (std::int32_t q = b; q < e; ++q) {
    const Arc& arc = arcs_[static_cast<std::size_t>(cell_arcs_[static_cast<std::size_t>(q)])];
    const Corridor& c = corridors_[static_cast<std::size_t>(arc.corridor)];
    const bool channel = c.kind == EditKind::kChannel;
    if ((channel && c.elevation_m >= lo) || (!channel && c.elevation_m <= hi)) continue;  // changes nothing
    if (channel && !std::isnan(z) && z <= arc.keep) continue;  // the raster's own water stays
    if (!inside(arc, p)) continue;
    if (channel)
      lo = c.elevation_m;
    else
      hi = c.elevation_m;
  }
  if (lo < std::numeric_limits<double>::infinity()) z = std::isnan(z) ? lo : std::min(z, lo);
  if (hi > -std::numeric_limits<double>::infinity() && !std::isnan(z)) z = std::max(z, hi);
  return z;
}

int ElevationEdits::corridor_at(double lon_deg, double lat_deg) const {
  if (arcs_.empty() || !std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return -1;
  const std::int64_t cell = cell_of(lon_deg, lat_deg);
  const V3 p = unit(lon_deg, lat_deg);
  int best = -1;
  for (std::int32_t q = cell_start_[static_cast<std::size_t>(cell)];
       q < cell_start_[static_cast<std::size_t>(cell) + 1]; ++q) {
    const Arc& arc = arcs_[static_cast<std::size_t>(cell_arcs_[static_cast<std::size_t>(q)])];
    if ((best < 0 || arc.corridor < best) && inside(arc, p)) best = arc.corridor;
  }
  return best;
}

void ElevationEdits::apply_row(const double* lon_deg, double lat_deg, float* out, std::int64_t n) const {
  if (!touches_lat(lat_deg)) return;
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t cell = cell_of(lon_deg[k], lat_deg);
    if (cell_start_[static_cast<std::size_t>(cell)] == cell_start_[static_cast<std::size_t>(cell) + 1]) continue;
    out[k] = static_cast<float>(apply(lon_deg[k], lat_deg, static_cast<double>(out[k])));
  }
}

bool ElevationEdits::touches_lat(double lat_deg) const {
  if (arcs_.empty() || !std::isfinite(lat_deg)) return false;
  const auto r =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((lat_deg + 90.0) / kCellDeg)), 0, kRows - 1);
  return row_used_[static_cast<std::size_t>(r)] != 0;
}

ElevationEdits::Reach ElevationEdits::reach_in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const {
  Reach out;
  out.channel_min_m = std::numeric_limits<double>::infinity();
  out.blockage_max_m = -std::numeric_limits<double>::infinity();
  if (arcs_.empty()) return out;
  const auto r0 =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((lat_lo + 90.0) / kCellDeg)), 0, kRows - 1);
  const auto r1 =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((lat_hi + 90.0) / kCellDeg)), 0, kRows - 1);
  std::int64_t c0 = static_cast<std::int64_t>(std::floor((lon_lo + 180.0) / kCellDeg));
  std::int64_t c1 = static_cast<std::int64_t>(std::floor((lon_hi + 180.0) / kCellDeg));
  if (c1 - c0 >= kCols - 1) {
    c0 = 0;
    c1 = kCols - 1;
  }
  const auto add = [&](const Corridor& c) {
    if (c.kind == EditKind::kChannel) {
      out.channel = true;
      out.channel_min_m = std::min(out.channel_min_m, c.elevation_m);
    } else {
      out.blockage = true;
      out.blockage_max_m = std::max(out.blockage_max_m, c.elevation_m);
    }
  };
  if ((r1 - r0 + 1) * (c1 - c0 + 1) > 4096) {  // a large box: every corridor may reach it
    for (const Corridor& c : corridors_) add(c);
    return out;
  }
  for (std::int64_t r = r0; r <= r1; ++r) {
    if (row_used_[static_cast<std::size_t>(r)] == 0) continue;
    for (std::int64_t c = c0; c <= c1; ++c) {
      const auto cell = static_cast<std::size_t>(r * kCols + wrap_index(c, kCols));
      for (std::int32_t q = cell_start_[cell]; q < cell_start_[cell + 1]; ++q)
        add(corridors_[static_cast<std::size_t>(
            arcs_[static_cast<std::size_t>(cell_arcs_[static_cast<std::size_t>(q)])].corridor)]);
    }
  }
  return out;
}

std::string ElevationEdits::fingerprint() const {
  std::uint64_t h = kFnvOffset;
  for (const Corridor& c : corridors_) {
    const auto kind = static_cast<std::uint8_t>(c.kind);
    fnv(h, &kind, 1);
    fnv(h, &c.elevation_m, sizeof(double));
    fnv(h, &c.keep_at_or_below_m, sizeof(double));
    const std::uint64_t nv = c.lon_deg.size();
    fnv(h, &nv, sizeof nv);
    fnv(h, c.lon_deg.data(), nv * sizeof(double));
    fnv(h, c.lat_deg.data(), nv * sizeof(double));
    fnv(h, c.half_width_deg.data(), c.half_width_deg.size() * sizeof(double));
  }
  return fmt::format("{:016x}", h);
}

}  // namespace aq::raster

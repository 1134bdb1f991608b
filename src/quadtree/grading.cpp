// SPDX-License-Identifier: GPL-3.0-or-later
// The achieved grading of a leaf set (see grading.hpp).
#include "quadtree/grading.hpp"

#include <algorithm>
#include <cmath>

namespace aq::quadtree {

Grading achieved_grading(const std::vector<Leaf>& leaves, const Lattice& lat, int map_level) {
  Grading out;
  out.map_level = map_level;
  const int c = map_level;
  const std::int64_t nx = lat.nx >> (lat.levels - c), ny = lat.ny >> (lat.levels - c);
  std::vector<std::uint8_t> level(static_cast<std::size_t>(nx * ny), 255);
  for (const Leaf& f : leaves) {
    if (f.level >= c) {
      std::uint8_t& v = level[static_cast<std::size_t>((f.b >> (f.level - c)) * nx + (f.a >> (f.level - c)))];
      v = v == 255 ? static_cast<std::uint8_t>(f.level) : std::max(v, static_cast<std::uint8_t>(f.level));
    } else {
      const std::int64_t s = std::int64_t{1} << (c - f.level);
      for (std::int64_t b = f.b * s; b < (f.b + 1) * s; ++b)
        std::fill_n(level.begin() + b * nx + f.a * s, s, static_cast<std::uint8_t>(f.level));
    }
  }
  std::vector<double> g;
  // One line of the map: cells at(t), t = 0..n-1, of side side_km(t) along the line; row_of(t) the
  // pixel row of the cell's centre (for the level-v square size there).
  const auto scan = [&](std::int64_t n, auto at, auto side_km, auto centre_row) {
    std::int64_t t = 0;
    while (t < n) {
      const std::uint8_t v = at(t);
      std::int64_t e = t;
      double d = 0.0;
      while (e < n && at(e) == v) d += side_km(e++);
      if (v < c && t > 0 && e < n) {
        const std::uint8_t before = at(t - 1), after = at(e);
        const bool up = before == v + 1 && after + 1 == v, down = before + 1 == v && after == v + 1;
        if (up || down) g.push_back(square_size_km(lat, v, centre_row((t + e) / 2)) / (std::sqrt(2.0) * d));
      }
      t = e;
    }
  };
  const double step_rad = lat.step0_deg / static_cast<double>(std::int64_t{1} << c) * 3.14159265358979323846 / 180.0;
  const auto row_pixel = [&](std::int64_t b) { return (static_cast<double>(b) + 0.5) * static_cast<double>(lat.pixels_per_square(c)); };
  const double r_km = kEarthRadiusKm;
  for (std::int64_t b = 0; b < ny; ++b) {
    const double lat_deg = lat.lat_of_row(row_pixel(b));
    const double dx = r_km * step_rad * std::cos(lat_deg * 3.14159265358979323846 / 180.0);
    scan(
        nx, [&](std::int64_t t) { return level[static_cast<std::size_t>(b * nx + t)]; },
        [&](std::int64_t) { return dx; }, [&](std::int64_t) { return row_pixel(b); });
  }
  for (std::int64_t a = 0; a < nx; ++a) {
    scan(
        ny, [&](std::int64_t t) { return level[static_cast<std::size_t>(t * nx + a)]; },
        [&](std::int64_t t) {
          const double la = lat.lat_of_row(row_pixel(t));
          return lat.mercator() ? r_km * step_rad * std::cos(la * 3.14159265358979323846 / 180.0) : r_km * step_rad;
        },
        [&](std::int64_t t) { return row_pixel(t); });
  }
  out.runs = static_cast<std::int64_t>(g.size());
  if (!g.empty()) {
    std::sort(g.begin(), g.end());
    out.median = g[(g.size() - 1) / 2];
    out.p90 = g[static_cast<std::size_t>(0.9 * static_cast<double>(g.size() - 1))];
    out.max = g.back();
  }
  return out;
}

}  // namespace aq::quadtree

// SPDX-License-Identifier: GPL-3.0-or-later
// Candidate coastal blocks and their ranking (see coastal_blocks.hpp).
#include "handoff/coastal_blocks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/lattice_coords.hpp"
#include "quadtree/leaves.hpp"

namespace aq::handoff {

namespace {

// Set bits of a row in [x0, x1), 0 <= x0 <= x1 <= row length.
std::int64_t count_range(const std::uint64_t* row, std::int64_t x0, std::int64_t x1) {
  std::int64_t n = 0;
  while (x0 < x1) {
    const std::int64_t w = x0 >> 6;
    const int b0 = static_cast<int>(x0 & 63);
    const std::int64_t end = std::min(x1, (w + 1) << 6);
    const int b1 = static_cast<int>(end - (w << 6));  // 1..64
    std::uint64_t word = row[w] >> b0;
    if (b1 - b0 < 64) word &= (1ULL << (b1 - b0)) - 1ULL;
    n += std::popcount(word);
    x0 = end;
  }
  return n;
}

// Level-0 squares with coast, exact counts.
std::vector<BlockCandidate> square_candidates(const Bitmap& filled, const Bitmap& coast, const Lattice& lat) {
  const std::int64_t s = lat.pixels_per_square(0);
  const std::int64_t n0x = lat.nx / s, n0y = lat.ny / s;
  std::vector<std::int64_t> nf(static_cast<std::size_t>(n0x * n0y), 0), nc(nf.size(), 0);
  for (std::int64_t j = 0; j < lat.ny; ++j) {
    const std::int64_t b = j / s;
    const std::uint64_t* fr = filled.row(j);
    const std::uint64_t* cr = coast.row(j);
    for (std::int64_t a = 0; a < n0x; ++a) {
      const auto k = static_cast<std::size_t>(b * n0x + a);
      nf[k] += count_range(fr, a * s, (a + 1) * s);
      nc[k] += count_range(cr, a * s, (a + 1) * s);
    }
  }
  std::vector<BlockCandidate> out;
  for (std::int64_t b = 0; b < n0y; ++b) {
    for (std::int64_t a = 0; a < n0x; ++a) {
      const auto k = static_cast<std::size_t>(b * n0x + a);
      if (nc[k] == 0) continue;
      BlockCandidate c;
      c.square_a = a;
      c.square_b = b;
      c.box = {lat.lon_of(a * s), lat.lon_of((a + 1) * s), lat.lat_of(b * s), lat.lat_of((b + 1) * s), true,
               lat.mercator()};
      c.coastal_pixels = nc[k];
      c.filled_pixels = nf[k];
      c.wet_fraction = static_cast<double>(nf[k]) / static_cast<double>(s * s);
      out.push_back(c);
    }
  }
  return out;
}

// A user box sampled at the lattice resolution (see the file comment of coastal_blocks.hpp).
BlockCandidate box_candidate(const Bitmap& filled, const Bitmap& coast, const Lattice& lat, const PoleRotation& rot,
                             const std::array<double, 4>& b, int index) {
  BlockCandidate c;
  c.box = {b[0], b[1], b[2], b[3], false};
  c.box_index = index;
  const auto ns = [](double extent_px) {
    return static_cast<std::int64_t>(std::clamp(std::ceil(extent_px), 1.0, 2048.0));
  };
  const std::array<double, 2> px = box_extent_px(c.box, lat, rot);
  const std::int64_t nu = ns(px[0]), nv = ns(px[1]);
  const double du = (b[1] - b[0]) / static_cast<double>(nu), dv = (b[3] - b[2]) / static_cast<double>(nv);
  double wet_w = 0.0, all_w = 0.0;
  for (std::int64_t v = 0; v < nv; ++v) {
    const double lat_deg = b[2] + (static_cast<double>(v) + 0.5) * dv;
    const double w = std::cos(lat_deg * kDegToRad);
    for (std::int64_t u = 0; u < nu; ++u) {
      const double lon_deg = b[0] + (static_cast<double>(u) + 0.5) * du;
      const auto p = pixel_holding(lat, mask::geographic_to_lattice(rot, {lon_deg, lat_deg}));
      all_w += w;
      if (p && filled.get(p->i, p->j)) {
        ++c.filled_pixels;
        wet_w += w;
        if (coast.get(p->i, p->j)) ++c.coastal_pixels;
      }
    }
  }
  c.wet_fraction = all_w > 0.0 ? wet_w / all_w : 0.0;
  return c;
}

}  // namespace

std::optional<mask::PixelIJ> pixel_holding(const Lattice& lat, mask::LonLat q) {
  double x = 0.0, y = 0.0;
  mask::deg_to_lattice_xy(lat, q, x, y);
  if (!mask::on_lattice_rows(lat, y)) return std::nullopt;
  return mask::PixelIJ{std::clamp(static_cast<std::int64_t>(x), std::int64_t{0}, lat.nx - 1),
                       std::clamp(static_cast<std::int64_t>(y), std::int64_t{0}, lat.ny - 1)};
}

std::string BlockCandidate::describe() const {
  if (box_index >= 0) return fmt::format("blocks.boxes[{}]", box_index);
  return fmt::format("level-0 square ({}, {})", square_a, square_b);
}

std::array<double, 2> box_extent_px(const BlockBox& box, const Lattice& lat, const PoleRotation& rotation) {
  const double d = lat.pixel_deg();
  const double w = box.lon_max_deg - box.lon_min_deg, h = box.lat_max_deg - box.lat_min_deg;
  if (!lat.mercator()) return {w / d, h / d};
  if (box.lattice_system) return {w / d, (mercator_y_deg(box.lat_max_deg) - mercator_y_deg(box.lat_min_deg)) / d};
  const double lon_c = box.lon_min_deg + 0.5 * w, lat_c = box.lat_min_deg + 0.5 * h;
  const double scale = std::cos(mask::geographic_to_lattice(rotation, {lon_c, lat_c}).lat_deg * kDegToRad);
  return {w * std::cos(lat_c * kDegToRad) / (d * scale), h / (d * scale)};
}

int suggest_ny(const BlockBox& box, const Lattice& lat, const PoleRotation& rotation, int refinement, int fixed_ny) {
  if (fixed_ny > 0) return fixed_ny;
  const double n = std::ceil(box_extent_px(box, lat, rotation)[1] * std::max(1, refinement) - 1e-9);
  auto ny = static_cast<int>(std::clamp(n, 8.0, 100000.0));
  return ny + (ny & 1);
}

Bitmap coastal_pixels(const Bitmap& filled) { return quadtree::coastal_band(filled, 1); }

std::vector<BlockCandidate> rank_blocks(const Bitmap& filled, const Lattice& lat, const PoleRotation& rotation,
                                        const config::BlocksOptions& options) {
  if (filled.nx() != lat.nx || filled.ny() != lat.ny) {
    throw InternalError(
        fmt::format("rank_blocks: a {} x {} bitmap for a {} x {} lattice", filled.nx(), filled.ny(), lat.nx, lat.ny));
  }
  const Bitmap coast = coastal_pixels(filled);
  std::vector<BlockCandidate> c;
  if (options.boxes.empty()) {
    c = square_candidates(filled, coast, lat);
    if (c.empty()) {
      throw InputError(
          "blocks: no level-0 square of the global run holds coast (the filled ocean has no land "
          "boundary); give user boxes in blocks.boxes");
    }
  } else {
    for (std::size_t k = 0; k < options.boxes.size(); ++k) {
      const auto& b = options.boxes[k];
      BlockCandidate bc = box_candidate(filled, coast, lat, rotation, b, static_cast<int>(k));
      if (bc.filled_pixels == 0) {
        throw ConfigError(fmt::format(
            "blocks.boxes[{}] = [{}, {}, {}, {}]: the block holds no water of the global run (no pixel of the "
            "filled ocean Ω_L inside: land, or a lake/sea the K-cursor fill does not reach); move the box over "
            "the ocean",
            k, b[0], b[1], b[2], b[3]));
      }
      c.push_back(bc);
    }
  }
  for (auto& x : c) x.suggested_ny = suggest_ny(x.box, lat, rotation, options.refinement, options.ny);
  std::stable_sort(c.begin(), c.end(), [](const BlockCandidate& a, const BlockCandidate& b) {
    if (a.coastal_pixels != b.coastal_pixels) return a.coastal_pixels > b.coastal_pixels;
    return a.wet_fraction > b.wet_fraction;
  });
  return c;
}

}  // namespace aq::handoff

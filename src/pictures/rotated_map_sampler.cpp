// SPDX-License-Identifier: GPL-3.0-or-later
// The raster under the pixels of a rotated map, by cells and tiles (see rotated_map_sampler.hpp).
#include "pictures/rotated_map_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/types.hpp"

namespace aq::io {

namespace {

constexpr int kCellsPerTile = RotatedMapSampler::kTile / RotatedMapSampler::kCell;
constexpr int kCorners = kCellsPerTile + 1;  // corner points per tile side

// Raster position (column, row) of a cell corner or centre; column unwrapped on a global raster.
struct RasterPoint {
  double c, r;
};

}  // namespace

RotatedMapSampler::RotatedMapSampler(const raster::Bathymetry& bathy, const PoleRotation& rotation, int width,
                                     int height, const std::function<double(double)>& rlon,
                                     const std::function<double(double)>& rlat)
    : bathy_(bathy), info_(bathy.info()), width_(width), height_(height) {
  // Corridor edits (Bathymetry::set_edits) are applied per sample: the exact path.
  fast_ = !info_.streamed && bathy.samples_bilinear() && bathy.edits() == nullptr && info_.ncols > 1 && info_.nrows > 1;
  // The rotated x, y, z axes (λ', φ') = (0, 0), (90, 0), (0, 90) in geographic coordinates,
  // taken from PoleRotation itself so that the map agrees with the mesh.
  const double axes[3][2] = {{0.0, 0.0}, {90.0, 0.0}, {0.0, 90.0}};
  for (std::size_t k = 0; k < 3; ++k) {
    double lon = 0, lat = 0;
    rotation.to_geographic(axes[k][0], axes[k][1], lon, lat);
    const double lo = lon * kDegToRad, la = lat * kDegToRad;
    axes_[k] = {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
  }
  // Corners up to the end of the last tile (beyond the map's edge when it is not a whole tile).
  const auto end = [](int n) { return (n + kTile - 1) / kTile * kTile; };
  for (int x = 0; x <= end(width); ++x) {
    const double a = rlon(x) * kDegToRad;
    cos_lon_.push_back(std::cos(a));
    sin_lon_.push_back(std::sin(a));
  }
  for (int y = 0; y <= end(height); ++y) {
    const double a = rlat(y) * kDegToRad;
    cos_lat_.push_back(std::cos(a));
    sin_lat_.push_back(std::sin(a));
  }
}

RotatedMapSampler::Position RotatedMapSampler::position(int x, int y) const {
  const auto i = static_cast<std::size_t>(x), j = static_cast<std::size_t>(y);
  double g[3];
  for (std::size_t k = 0; k < 3; ++k)
    g[k] = cos_lat_[j] * (cos_lon_[i] * axes_[0][k] + sin_lon_[i] * axes_[1][k]) + sin_lat_[j] * axes_[2][k];
  return {std::atan2(g[1], g[0]) * kRadToDeg, std::asin(std::clamp(g[2], -1.0, 1.0)) * kRadToDeg};
}

void RotatedMapSampler::sample_rows_exact(int y0, int rows, float* out) const {
  sample_cell_exact(0, y0, width_, y0 + rows, y0, out);
}

void RotatedMapSampler::sample_cell_exact(int x0, int y0, int x1, int y1, int out_y0, float* out) const {
  for (int y = y0; y < y1; ++y) {
    float* row = out + static_cast<std::ptrdiff_t>(y - out_y0) * width_;
    for (int x = x0; x < x1; ++x) {
      const Position p = position(x, y);
      row[x] = static_cast<float>(bathy_.sample(p.lon_deg, p.lat_deg));
    }
  }
}

void RotatedMapSampler::sample_rows(int y0, int rows, float* out) const {
  if (!fast_) {
    sample_rows_exact(y0, rows, out);
    return;
  }
  std::vector<float> block;
  for (int ty = y0 / kTile; ty * kTile < y0 + rows; ++ty)
    for (int tx = 0; tx * kTile < width_; ++tx) sample_tile(tx, ty, y0, rows, out, block);
}

// One tile's pixels within rows [y0, y0 + rows): the cells' corners, side midpoints and centres
// exact, the cells checked, the raster block under the good cells read once, then every pixel.
void RotatedMapSampler::sample_tile(int tx, int ty, int y0, int rows, float* out, std::vector<float>& block) const {
  const double nc = static_cast<double>(info_.ncols), nr = static_cast<double>(info_.nrows);
  auto raster_point = [&](int x, int y) {
    const Position p = position(x, y);
    double c = (p.lon_deg - info_.lon_first) / info_.dlon;
    if (info_.global_lon) c -= nc * std::floor(c / nc);
    return RasterPoint{c, (p.lat_deg - info_.lat_first) / info_.dlat};
  };
  const int px0 = tx * kTile, py0 = ty * kTile;
  // Columns continuous across the tile: each within half the raster of the tile's first corner.
  const double c_ref = raster_point(px0, py0).c;
  auto point = [&](int x, int y) {
    RasterPoint p = raster_point(px0 + x, py0 + y);
    if (info_.global_lon) p.c += nc * std::round((c_ref - p.c) / nc);
    return p;
  };
  RasterPoint corner[kCorners][kCorners];
  constexpr int h = kCell / 2;
  for (int j = 0; j < kCorners; ++j)
    for (int i = 0; i < kCorners; ++i) corner[j][i] = point(i * kCell, j * kCell);
  // Midpoints of the cells' horizontal and vertical sides.
  RasterPoint side_h[kCorners][kCellsPerTile], side_v[kCellsPerTile][kCorners];
  for (int j = 0; j < kCorners; ++j)
    for (int i = 0; i < kCellsPerTile; ++i) side_h[j][i] = point(i * kCell + h, j * kCell);
  for (int j = 0; j < kCellsPerTile; ++j)
    for (int i = 0; i < kCorners; ++i) side_v[j][i] = point(i * kCell, j * kCell + h);

  // The blend's error as a distance on the ground, in the raster's row spacing: a column is
  // dlon cos φ wide there. Within kMaxError / 2 at every side's midpoint bounds a quadratic error
  // within kMaxError over the cell (e(s, t) = A s(s-1) + B t(t-1): each side measures A or B
  // alone; the centre alone would not: the column is a harmonic function of the pixel on a
  // conformal map, A = -B); the centre is checked too.
  const double col_width = info_.dlon / info_.dlat;
  auto off = [&](const RasterPoint& exact, const RasterPoint& p, const RasterPoint& q, double tol) {
    const double cos_lat = std::cos((info_.lat_first + exact.r * info_.dlat) * kDegToRad);
    return !(std::abs(exact.c - 0.5 * (p.c + q.c)) * col_width * cos_lat <= tol &&
             std::abs(exact.r - 0.5 * (p.r + q.r)) <= tol);
  };
  // A cell is good when those checks pass and its block (corners' bounding box, one cell of
  // margin) lies in the raster.
  bool good[kCellsPerTile][kCellsPerTile];
  double c_lo = std::numeric_limits<double>::infinity(), c_hi = -c_lo, r_lo = c_lo, r_hi = -c_lo;
  for (int j = 0; j < kCellsPerTile; ++j)
    for (int i = 0; i < kCellsPerTile; ++i) {
      const RasterPoint& a = corner[j][i];
      const RasterPoint& b = corner[j][i + 1];
      const RasterPoint& c = corner[j + 1][i];
      const RasterPoint& d = corner[j + 1][i + 1];
      const RasterPoint m = point(i * kCell + h, j * kCell + h);
      const RasterPoint ad{0.5 * (a.c + d.c), 0.5 * (a.r + d.r)}, bc{0.5 * (b.c + c.c), 0.5 * (b.r + c.r)};
      const double lo_c = std::min({a.c, b.c, c.c, d.c}) - 1.0, hi_c = std::max({a.c, b.c, c.c, d.c}) + 1.0;
      const double lo_r = std::min({a.r, b.r, c.r, d.r}) - 1.0, hi_r = std::max({a.r, b.r, c.r, d.r}) + 1.0;
      const bool inside = lo_r >= 0.0 && hi_r <= nr - 1.0 && (info_.global_lon || (lo_c >= 0.0 && hi_c <= nc - 1.0));
      const double side_tol = 0.5 * kMaxError;
      // NaN fails every check.
      good[j][i] = inside && !off(side_h[j][i], a, b, side_tol) && !off(side_h[j + 1][i], c, d, side_tol) &&
                   !off(side_v[j][i], a, c, side_tol) && !off(side_v[j][i + 1], b, d, side_tol) &&
                   !off(m, ad, bc, kMaxError);
      if (!good[j][i]) continue;
      c_lo = std::min(c_lo, lo_c);
      c_hi = std::max(c_hi, hi_c);
      r_lo = std::min(r_lo, lo_r);
      r_hi = std::max(r_hi, hi_r);
    }
  std::int64_t bc0 = 0, br0 = 0, bnc = 0, bnr = 0;
  bool any_good = c_lo <= c_hi;
  if (any_good) {
    bc0 = static_cast<std::int64_t>(std::floor(c_lo));
    br0 = static_cast<std::int64_t>(std::floor(r_lo));
    bnc = static_cast<std::int64_t>(std::floor(c_hi)) - bc0 + 1;
    bnr = static_cast<std::int64_t>(std::floor(r_hi)) - br0 + 1;
    any_good = bnc * bnr <= kMaxTileValues;
  }
  if (any_good) {
    block.resize(static_cast<std::size_t>(bnc * bnr));
    bathy_.values(bc0, bnc, br0, bnr, block.data());
  }

  for (int j = 0; j < kCellsPerTile; ++j)
    for (int i = 0; i < kCellsPerTile; ++i) {
      const int x0 = px0 + i * kCell, x1 = std::min(x0 + kCell, width_);
      const int ya = py0 + j * kCell, yb = std::min({ya + kCell, height_, y0 + rows});
      const int cy0 = std::max(ya, y0);
      if (x0 >= x1 || cy0 >= yb) continue;
      if (!any_good || !good[j][i]) {
        sample_cell_exact(x0, cy0, x1, yb, y0, out);
        continue;
      }
      const RasterPoint& a = corner[j][i];
      const RasterPoint& b = corner[j][i + 1];
      const RasterPoint& c = corner[j + 1][i];
      const RasterPoint& d = corner[j + 1][i + 1];
      const float* values = block.data();
      const auto stride = static_cast<std::ptrdiff_t>(bnc);
      for (int y = cy0; y < yb; ++y) {
        // The pixel row's ends (on the cell's left and right sides), then along it; positions in
        // the block, where they are >= 1 (its margin), so truncation is floor.
        const double v = static_cast<double>(y - ya) / kCell;
        const double lc = a.c + v * (c.c - a.c) - static_cast<double>(bc0),
                     lr = a.r + v * (c.r - a.r) - static_cast<double>(br0);
        const double dc = (b.c + v * (d.c - b.c) - static_cast<double>(bc0) - lc) / kCell,
                     dr = (b.r + v * (d.r - b.r) - static_cast<double>(br0) - lr) / kCell;
        float* row = out + static_cast<std::ptrdiff_t>(y - y0) * width_;
        // The blend of the four values in float (they are floats; 1e-7 of relative rounding).
        double pc = lc, pr = lr;
        for (int x = x0; x < x1; ++x, pc += dc, pr += dr) {
          const auto c0 = static_cast<int>(pc), r0 = static_cast<int>(pr);
          const auto t = static_cast<float>(pc - c0), u = static_cast<float>(pr - r0);
          const float* p0 = values + r0 * stride + c0;
          const float* p1 = p0 + stride;
          const float lo = p0[0] + t * (p0[1] - p0[0]), hi = p1[0] + t * (p1[1] - p1[0]);
          row[x] = lo + u * (hi - lo);
        }
      }
    }
}

}  // namespace aq::io

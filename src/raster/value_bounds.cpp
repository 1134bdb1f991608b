// SPDX-License-Identifier: GPL-3.0-or-later
// Block minima/maxima of a raster and their box queries (value_bounds.hpp).
#include "raster/value_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aq::raster {

ValueBounds::ValueBounds(const Bathymetry& bathy, std::int64_t block)
    : info_(bathy.info()), edits_(bathy.shared_edits()) {
  if (info_.streamed || info_.tiled || !bathy.samples_bilinear() || info_.ncols <= 0 || info_.nrows <= 0 || block < 1)
    return;
  available_ = true;
  const std::int64_t nc = info_.ncols, nr = info_.nrows;
  Level& l0 = levels_.emplace_back();
  l0.block = block;
  l0.nbx = (nc + block - 1) / block;
  l0.nby = (nr + block - 1) / block;
  const auto nb = static_cast<std::size_t>(l0.nbx * l0.nby);
  l0.lo.assign(nb, std::numeric_limits<float>::infinity());
  l0.hi.assign(nb, -std::numeric_limits<float>::infinity());
  l0.nan.assign(nb, 0);
  const std::int64_t B = block, nbx = l0.nbx, nby = l0.nby;
  float* lo = l0.lo.data();
  float* hi = l0.hi.data();
  unsigned char* nan = l0.nan.data();
#pragma omp parallel default(none) shared(bathy, nc, nr, B, nbx, nby, lo, hi, nan)
  {
    std::vector<float> rows(static_cast<std::size_t>(B * nc));
#pragma omp for schedule(static)
    for (std::int64_t by = 0; by < nby; ++by) {
      const std::int64_t r0 = by * B, n = std::min(B, nr - r0);
      bathy.values(0, nc, r0, n, rows.data());
      for (std::int64_t r = 0; r < n; ++r) {
        const float* v = rows.data() + r * nc;
        for (std::int64_t bx = 0; bx < nbx; ++bx) {
          const auto s = static_cast<std::size_t>(by * nbx + bx);
          float mn = lo[s], mx = hi[s];
          unsigned char has_nan = nan[s];
          const std::int64_t c1 = std::min(nc, (bx + 1) * B);
          for (std::int64_t c = bx * B; c < c1; ++c) {
            const float x = v[c];
            if (std::isnan(x)) {
              has_nan = 1;
            } else {
              mn = std::min(mn, x);
              mx = std::max(mx, x);
            }
          }
          lo[s] = mn;
          hi[s] = mx;
          nan[s] = has_nan;
        }
      }
    }
  }
  // Coarser levels: 2 × 2 blocks of the one below, while a level has more than a few blocks.
  constexpr std::int64_t kMerge = 2;
  while (levels_.back().nbx > 8 || levels_.back().nby > 8) {
    const Level& f = levels_.back();
    Level c;
    c.block = f.block * kMerge;
    c.nbx = (f.nbx + kMerge - 1) / kMerge;
    c.nby = (f.nby + kMerge - 1) / kMerge;
    const auto n = static_cast<std::size_t>(c.nbx * c.nby);
    c.lo.assign(n, std::numeric_limits<float>::infinity());
    c.hi.assign(n, -std::numeric_limits<float>::infinity());
    c.nan.assign(n, 0);
    for (std::int64_t by = 0; by < f.nby; ++by)
      for (std::int64_t bx = 0; bx < f.nbx; ++bx) {
        const auto s = static_cast<std::size_t>(by * f.nbx + bx);
        const auto t = static_cast<std::size_t>((by / kMerge) * c.nbx + bx / kMerge);
        c.lo[t] = std::min(c.lo[t], f.lo[s]);
        c.hi[t] = std::max(c.hi[t], f.hi[s]);
        c.nan[t] = static_cast<unsigned char>(c.nan[t] | f.nan[s]);
      }
    levels_.push_back(std::move(c));
  }
}

std::int64_t ValueBounds::bytes() const {
  std::int64_t b = 0;
  for (const Level& l : levels_) b += static_cast<std::int64_t>(l.lo.size() * (2 * sizeof(float) + 1));
  return b;
}

const ValueBounds::Level& ValueBounds::level_for(std::int64_t cols, std::int64_t rows) const {
  for (const Level& l : levels_) {
    // Blocks a range of `cols` cells can touch: cols / block + 1 (+1 more when it straddles).
    const std::int64_t bx = cols / l.block + 2, by = rows / l.block + 2;
    if (bx * by <= kMaxBlocksPerQuery) return l;
  }
  return levels_.back();
}

void ValueBounds::add_blocks(const Level& l, std::int64_t c_lo, std::int64_t c_hi, std::int64_t r_lo,
                             std::int64_t r_hi, ValueRange& out) {
  for (std::int64_t by = r_lo / l.block; by <= r_hi / l.block; ++by)
    for (std::int64_t bx = c_lo / l.block; bx <= c_hi / l.block; ++bx) {
      const auto s = static_cast<std::size_t>(by * l.nbx + bx);
      out.nan = out.nan || l.nan[s] != 0;
      if (l.lo[s] <= l.hi[s]) {
        out.lo = out.any_finite ? std::min(out.lo, static_cast<double>(l.lo[s])) : l.lo[s];
        out.hi = out.any_finite ? std::max(out.hi, static_cast<double>(l.hi[s])) : l.hi[s];
        out.any_finite = true;
      }
    }
}

ValueRange ValueBounds::in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const {
  ValueRange out = raw_in_box(lon_lo, lon_hi, lat_lo, lat_hi);
  if (!edits_ || !available_) return out;
  // A corridor edit sets values in its own range, whatever the raster holds (a channel also
  // turns no-data into water).
  const ElevationEdits::Reach e = edits_->reach_in_box(lon_lo, lon_hi, lat_lo, lat_hi);
  const auto include = [&out](double z) {
    out.lo = out.any_finite ? std::min(out.lo, z) : z;
    out.hi = out.any_finite ? std::max(out.hi, z) : z;
    out.any_finite = true;
  };
  if (e.channel) include(e.channel_min_m);
  if (e.blockage) include(e.blockage_max_m);
  return out;
}

ValueRange ValueBounds::raw_in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const {
  ValueRange out;
  if (!available_ || !(lon_lo <= lon_hi) || !(lat_lo <= lat_hi) || !std::isfinite(lon_hi - lon_lo) ||
      !std::isfinite(lat_hi - lat_lo)) {
    out.nan = true;
    out.lo = -std::numeric_limits<double>::infinity();
    out.hi = std::numeric_limits<double>::infinity();
    out.any_finite = true;
    return out;
  }
  const std::int64_t nc = info_.ncols, nr = info_.nrows;
  // Sample positions in raster units; a sample uses the cells floor(x) and floor(x) + 1 (after a
  // 1e-9 snap to grid lines), so one cell more on each side is enough.
  const double x_lo = (lon_lo - info_.lon_first) / info_.dlon, x_hi = (lon_hi - info_.lon_first) / info_.dlon;
  const double y_lo = (lat_lo - info_.lat_first) / info_.dlat, y_hi = (lat_hi - info_.lat_first) / info_.dlat;
  std::int64_t r_lo = static_cast<std::int64_t>(std::floor(y_lo)) - 1;
  std::int64_t r_hi = static_cast<std::int64_t>(std::floor(y_hi)) + 2;
  if (y_lo < -0.5 || y_hi > static_cast<double>(nr) - 0.5) out.nan = true;  // NaN, or the edge row clamped
  r_lo = std::clamp<std::int64_t>(r_lo, 0, nr - 1);
  r_hi = std::clamp<std::int64_t>(r_hi, 0, nr - 1);
  auto c_lo = static_cast<std::int64_t>(std::floor(x_lo)) - 1;
  auto c_hi = static_cast<std::int64_t>(std::floor(x_hi)) + 2;
  const Level& l = level_for(std::min(c_hi - c_lo + 1, nc), r_hi - r_lo + 1);
  if (!info_.global_lon) {
    if (x_lo < -0.5 || x_hi > static_cast<double>(nc) - 0.5) out.nan = true;
    add_blocks(l, std::clamp<std::int64_t>(c_lo, 0, nc - 1), std::clamp<std::int64_t>(c_hi, 0, nc - 1), r_lo, r_hi,
               out);
    return out;
  }
  if (c_hi - c_lo + 1 >= nc) {
    add_blocks(l, 0, nc - 1, r_lo, r_hi, out);
    return out;
  }
  const std::int64_t a = ((c_lo % nc) + nc) % nc, b = ((c_hi % nc) + nc) % nc;
  if (a <= b) {
    add_blocks(l, a, b, r_lo, r_hi, out);
  } else {  // across the seam
    add_blocks(l, a, nc - 1, r_lo, r_hi, out);
    add_blocks(l, 0, b, r_lo, r_hi, out);
  }
  return out;
}

int side_of_threshold(const ValueRange& r, double threshold) {
  constexpr double kMargin = 1e-6;
  if (!r.any_finite) return -1;  // nothing but NaN: dry
  if (!r.nan && r.hi <= threshold - kMargin) return 1;
  if (r.lo > threshold + kMargin) return -1;
  return 0;
}

}  // namespace aq::raster

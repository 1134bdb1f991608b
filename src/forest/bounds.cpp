// SPDX-License-Identifier: GPL-3.0-or-later
// Bounds of the bathymetry under a box (see bounds.hpp).
#include "forest/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace aq::forest {

StackBounds::StackBounds(const raster::Bathymetry& bathy, double box_deg, double blend_km) : bathy_(&bathy) {
  const std::size_t n = bathy.source_count();
  blend_ = false;
  available_ = true;
  for (std::size_t k = 0; k < n; ++k) {
    const raster::Bathymetry& s = n == 1 ? bathy : bathy.source(k);
    const bool tiled = s.info().tiled;
    tiled_.push_back(tiled ? 1 : 0);
    const double cells = box_deg / std::min(s.info().dlon, s.info().dlat) / 4.0;
    std::int64_t block = 1;
    while (block < 8 && static_cast<double>(2 * block) <= cells) block *= 2;
    sources_.push_back(tiled ? nullptr : std::make_unique<raster::ValueBounds>(s, block));
    available_ = available_ && (tiled || sources_.back()->available());
  }
  // A blend mixes a source with those below wherever it is within blend_km of its data edge.
  blend_ = n > 1 && blend_km > 0.0;
}

raster::ValueRange StackBounds::in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const {
  raster::ValueRange out;
  out.nan = true;
  if (!available_) {
    out.lo = -std::numeric_limits<double>::infinity();
    out.hi = std::numeric_limits<double>::infinity();
    out.any_finite = true;
    return out;
  }
  for (std::size_t k = 0; k < sources_.size(); ++k) {
    const raster::ValueRange r = source_box(k, lon_lo, lon_hi, lat_lo, lat_hi);
    if (r.any_finite) {
      out.lo = out.any_finite ? std::min(out.lo, r.lo) : r.lo;
      out.hi = out.any_finite ? std::max(out.hi, r.hi) : r.hi;
      out.any_finite = true;
    }
    // Where source k has data everywhere in the box, the sources below supply nothing (no blend).
    if (!r.nan) {
      out.nan = false;
      if (!blend_) break;
    }
  }
  return out;
}

raster::ValueRange StackBounds::source_box(std::size_t k, double lon_lo, double lon_hi, double lat_lo,
                                           double lat_hi) const {
  if (tiled_[k] == 0) return sources_[k]->in_box(lon_lo, lon_hi, lat_lo, lat_hi);
  const raster::Bathymetry& s = bathy_->source_count() == 1 ? *bathy_ : bathy_->source(k);
  const raster::RasterInfo& in = s.info();
  raster::ValueRange out;
  // The cells a bilinear sample in the box can use, one more on every side (ValueBounds::in_box).
  const double x_lo = (lon_lo - in.lon_first) / in.dlon, x_hi = (lon_hi - in.lon_first) / in.dlon;
  const double y_lo = (lat_lo - in.lat_first) / in.dlat, y_hi = (lat_hi - in.lat_first) / in.dlat;
  std::int64_t c_lo = static_cast<std::int64_t>(std::floor(x_lo)) - 1,
               c_hi = static_cast<std::int64_t>(std::floor(x_hi)) + 2;
  const std::int64_t r_lo = static_cast<std::int64_t>(std::floor(y_lo)) - 1,
                     r_hi = static_cast<std::int64_t>(std::floor(y_hi)) + 2;
  if (!in.global_lon && (x_hi < -0.5 || x_lo > static_cast<double>(in.ncols) - 0.5)) {
    // Past the raster's columns (also a whole turn away, as sampling takes it): no data there.
    const double turn = 360.0 / in.dlon;
    const double shift = turn * std::floor((0.5 * (x_lo + x_hi) + 0.5) / turn);
    c_lo -= static_cast<std::int64_t>(shift);
    c_hi -= static_cast<std::int64_t>(shift);
  }
  out.nan = true;
  if (s.surely_empty(c_lo, c_hi, r_lo, r_hi)) return out;  // no tile here
  const std::int64_t nc = c_hi - c_lo + 1, nr = r_hi - r_lo + 1;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  s.values(c_lo, nc, r_lo, nr, v.data());
  out.nan = false;
  for (const float x : v) {
    if (std::isnan(x)) {
      out.nan = true;
      continue;
    }
    out.lo = out.any_finite ? std::min(out.lo, static_cast<double>(x)) : x;
    out.hi = out.any_finite ? std::max(out.hi, static_cast<double>(x)) : x;
    out.any_finite = true;
  }
  // Samples near the raster's edge or past it are NaN.
  if (y_lo < -0.5 || y_hi > static_cast<double>(in.nrows) - 0.5) out.nan = true;
  if (!in.global_lon && (x_lo < -0.5 || x_hi > static_cast<double>(in.ncols) - 0.5)) out.nan = true;
  return out;
}

int side(const raster::ValueRange& r, double threshold, bool float_samples) {
  if (!r.any_finite) return -1;  // nothing but NaN: dry
  double margin = 1e-6;
  if (float_samples) {
    const double scale = std::max({std::fabs(threshold), std::fabs(r.lo), std::fabs(r.hi)});
    margin += 2.4e-7 * scale;
  }
  if (!r.nan && r.hi <= threshold - margin) return 1;
  if (r.lo > threshold + margin) return -1;
  return 0;
}

}  // namespace aq::forest

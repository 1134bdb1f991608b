// Bounds of the bathymetry under a box (see bounds.hpp).
#include "forest/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aq::forest {

StackBounds::StackBounds(const raster::Bathymetry& bathy, double cells_per_pixel, double blend_km) {
  const std::int64_t block = cells_per_pixel < 2.0 ? 4 : 8;
  const std::size_t n = bathy.source_count();
  blend_ = false;
  available_ = true;
  for (std::size_t k = 0; k < n; ++k) {
    const raster::Bathymetry& s = n == 1 ? bathy : bathy.source(k);
    sources_.push_back(std::make_unique<raster::ValueBounds>(s, block));
    available_ = available_ && sources_.back()->available();
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
    const raster::ValueRange r = sources_[k]->in_box(lon_lo, lon_hi, lat_lo, lat_hi);
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

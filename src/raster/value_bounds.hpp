// SPDX-License-Identifier: GPL-3.0-or-later
// Bounds of the raster values under a geographic box, from per-block minima and maxima: lets a
// caller decide that every bilinear sample inside the box is on one side of a threshold without
// sampling it (the rotated classify skips whole tiles of open ocean and inland this way).
#pragma once

#include <cstdint>
#include <vector>

#include <memory>

#include "raster/bathymetry.hpp"

namespace aq::raster {

/// What the values under a box can be: every finite value lies in [lo, hi]; `nan` when a sample
/// inside the box may be NaN (a no-data value, or a point outside the raster's coverage).
struct ValueRange {
  double lo = 0.0, hi = 0.0;
  bool nan = false;
  bool any_finite = false;
};

class ValueBounds {
 public:
  /// Summarises `bathy` in blocks of `block` × `block` raster values, and in blocks 2, 4, ...
  /// times larger (a pyramid: a query reads the finest level that needs at most kMaxBlocksPerQuery
  /// blocks, so a small box gets tight bounds and a large one stays cheap). Not available (every
  /// query answers "unknown") for a streamed raster or bicubic sampling, where the bound would not
  /// hold.
  explicit ValueBounds(const Bathymetry& bathy, std::int64_t block = 32);
  [[nodiscard]] bool available() const { return available_; }
  /// Bounds of every value that `Bathymetry::sample` can return at a point of
  /// [lon_lo, lon_hi] × [lat_lo, lat_hi] (degrees; lon_lo <= lon_hi, any range of λ on a global
  /// raster, wrapping at the seam). Conservative: one raster cell more on every side; with edits
  /// (Bathymetry::set_edits) the elevations of the corridors that may reach the box are included.
  [[nodiscard]] ValueRange in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const;
  /// Bytes held (every level).
  [[nodiscard]] std::int64_t bytes() const;

  static constexpr std::int64_t kMaxBlocksPerQuery = 96;

 private:
  struct Level {
    std::int64_t block = 8, nbx = 0, nby = 0;
    std::vector<float> lo, hi;      ///< per block, over its finite values (+inf/-inf when none)
    std::vector<unsigned char> nan;  ///< per block: holds a NaN
  };
  // The level whose blocks of the cell range [c_lo, c_hi] × [r_lo, r_hi] are fewest but at most
  // kMaxBlocksPerQuery, or the coarsest.
  [[nodiscard]] const Level& level_for(std::int64_t cols, std::int64_t rows) const;
  static void add_blocks(const Level& l, std::int64_t c_lo, std::int64_t c_hi, std::int64_t r_lo, std::int64_t r_hi,
                         ValueRange& out);
  [[nodiscard]] ValueRange raw_in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const;
  RasterInfo info_;
  std::shared_ptr<const ElevationEdits> edits_;  ///< the raster's edits when built, or null
  bool available_ = false;
  std::vector<Level> levels_;  ///< finest first; each coarser one merges 2 × 2 blocks
};

/// Which side of `threshold` every bilinear sample with values in `r` falls on: +1 all <= threshold
/// (no NaN), -1 all > threshold or NaN, 0 undecided. A margin of 1e-6 m absorbs the rounding of
/// the interpolation.
[[nodiscard]] int side_of_threshold(const ValueRange& r, double threshold);

}  // namespace aq::raster

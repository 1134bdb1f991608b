// SPDX-License-Identifier: GPL-3.0-or-later
// Bounds of the bathymetry under a geographic box, for deciding a patch at its own size
// (README "The forest engine", exactness conditions). The bilinear value inside a raster cell is a
// convex combination of its 4 corner values, so every sample in a box lies within the minimum and
// maximum of the raster values of the cells the box touches (and one cell more on every side:
// raster/value_bounds.hpp); a patch whose box is entirely on one side of the threshold is wet or
// dry at every vertex without sampling one.
//
// Several sources (input.paths, first source with data wins; a blend is a convex combination of
// the sources' values): source k's bounds count only while the sources above it may have no data
// in the box; a source with data everywhere in the box ends the search. With a blend every source
// counts. A source the bounds cannot summarise (bicubic sampling, a streamed raster) makes every
// box undecided. A source read in tiles (a fine tile stack) is summarised where it is asked: a box
// where GDAL's data coverage says it has no data (no tile there) leaves it out without reading; any
// other box reads its cells (the same cells the sampling of the box would read).
#pragma once

#include <memory>
#include <vector>

#include "raster/bathymetry.hpp"
#include "raster/value_bounds.hpp"

namespace aq::forest {

class StackBounds {
 public:
  /// Summaries of every source of `bathy` for boxes of about `box_deg` (a patch's side): each
  /// source's finest block is about a quarter of such a box in its own cells (1 to 8 cells), so a
  /// coarse source under a fine lattice is bounded cell by cell. `blend_km` is input.blend_km.
  StackBounds(const raster::Bathymetry& bathy, double box_deg, double blend_km);
  [[nodiscard]] bool available() const { return available_; }
  /// Every value Bathymetry::sample can return at a point of the box (see value_bounds.hpp).
  [[nodiscard]] raster::ValueRange in_box(double lon_lo, double lon_hi, double lat_lo, double lat_hi) const;

 private:
  // Bounds of source k over a box: its held summary, or (tiled) its cells read.
  [[nodiscard]] raster::ValueRange source_box(std::size_t k, double lon_lo, double lon_hi, double lat_lo,
                                              double lat_hi) const;
  const raster::Bathymetry* bathy_ = nullptr;
  std::vector<std::unique_ptr<raster::ValueBounds>> sources_;
  std::vector<char> tiled_;
  bool blend_ = false;
  bool available_ = false;
};

/// +1 when every sample with values in `r` is <= threshold (and none is NaN), -1 when every one
/// is above it or NaN, 0 undecided. `float_samples`: the samples are rounded to float before the
/// comparison (the unrotated vertex rule's rows), so the margin also covers a float's rounding.
[[nodiscard]] int side(const raster::ValueRange& r, double threshold, bool float_samples);

}  // namespace aq::forest

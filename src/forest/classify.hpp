// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel classes on the forest (ARCHITECTURE §4.2, the vertex rule of mask/pixel_classes.hpp) patch
// by patch: a patch whose vertices the bathymetry's bounds put on one side of the threshold
// (forest/bounds.hpp) is decided at its own size, without sampling; any other patch samples its
// (P + 1)² vertices with the very calls of the dense engine (unrotated: prepare_columns and
// sample_row, whose float values are thresholded; rotated: LatticeRowMapper and sample_points), so
// every bit equals the dense engine's.
#pragma once

#include <cstdint>
#include <vector>

#include "core/rotation.hpp"
#include "forest/bounds.hpp"
#include "forest/patches.hpp"
#include "mask/pixel_classes.hpp"
#include "mask/wet_area.hpp"
#include "raster/bathymetry.hpp"

namespace aq::forest {

struct PatchClasses {
  std::vector<PatchBits> wet;  ///< per local patch: pixels whose 4 vertices are wet
  mask::ClassCounts counts;    ///< over all ranks (wet vertices of the nx × (ny+1) lattice, pixel classes)
  std::int64_t decided = 0;    ///< patches decided by bounds, over all ranks
  std::int64_t sampled = 0;    ///< patches sampled vertex by vertex, over all ranks
};

/// Classifies every local patch (collective: the counts are summed over the ranks). `window`:
/// the pixels a regional run classifies (mask::classify_window; default: all), outside which no
/// vertex is wet. Throws ConfigError for a streamed raster on a rotated lattice (as the dense
/// engine does) and what sampling throws.
PatchClasses classify_patches(const PatchForest& pf, const raster::Bathymetry& bathy, const StackBounds& bounds,
                              const PoleRotation& rot, double min_depth_m, const mask::PixelWindow& window);

/// The same at one or two thresholds (a floodplain: mask.min_depth_m and the datum, 0 m), one
/// PatchClasses each: a patch the bounds decide at every threshold is not sampled, any other is
/// sampled once and thresholded at each, so every threshold's bits are the dense engine's.
std::vector<PatchClasses> classify_patches_at(const PatchForest& pf, const raster::Bathymetry& bathy,
                                              const StackBounds& bounds, const PoleRotation& rot,
                                              const std::vector<double>& min_depths_m, const mask::PixelWindow& window);

}  // namespace aq::forest

// The mask stage in one call (seed 002 §2; ARCHITECTURE §4.2-4.3): pixel classes from the
// bathymetry, the K-cursor fill from the seeds, pinch vertices (optionally removed) and the
// critical-passage table. Everything the quadtree stage needs is in WetArea::filled (Ω_L).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/log.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/domain.hpp"
#include "mask/k_cursor_fill.hpp"
#include "mask/passages.hpp"
#include "mask/pinches.hpp"
#include "mask/pixel_classes.hpp"
#include "raster/bathymetry.hpp"

namespace aq::mask {

/// Counts of the pixel classes.
struct ClassCounts {
  std::int64_t wet_vertices = 0, wet = 0, coastal = 0, dry = 0;
};

/// Pinch vertices of the final Ω_L and, when mask.remove_pinches, what their removal did.
struct PinchReport {
  std::int64_t total = 0;      ///< pinch vertices of the final filled set
  std::vector<Pinch> pinches;  ///< all of them, (J, I) order, with positions
  bool removal_requested = false;
  PinchRemovalStats removal;  ///< meaningful when removal_requested
};

struct WetArea {
  Bitmap wet_vertices;  ///< nx × (ny+1): lattice vertex (I, J) wet (d <= -h)
  Bitmap wet;           ///< nx × ny: all 4 vertices wet (or the area rule)
  Bitmap coastal;       ///< nx × ny: neither wet nor dry
  Bitmap filled;        ///< nx × ny: Ω_L, the K-cursor fill from the seeds (pinch-free when asked)
  ClassCounts classes;
  FillStats fill;                  ///< statistics of the fill (before pinch removal)
  std::int64_t filled_pixels = 0;  ///< |Ω_L| as returned (after pinch removal)
  std::vector<SeedInfo> seeds;
  PinchReport pinches;
  std::vector<PassageResult> passages;  ///< empty unless mask.passages
};

/// Runs the mask stage on `options` as validated at load (config/global_config.cpp: every mask.*
/// key's range); seeds as in place_seeds (ConfigError when no
/// all-wet window is within the radius). Logs "classify: done ...", "fill: done ...",
/// "pinches: done ...", "passages: done ..." stage lines (and a progress bar on a terminal);
/// when `report` is given, adds those stages and a "mask" section (see wet_area_json).
/// With a regional `domain` the fill runs on wet ∩ domain from the seeds regional_seeds gives
/// (`wet` stays the whole classification: the open boundary is where the outside is wet) and
/// the passage table is not made.
WetArea compute_wet_area(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                         const config::MaskOptions& options, const Logger& log, Report* report,
                         const Domain* domain = nullptr);

/// The "mask" report section: parameters, class counts, fill statistics, seeds, pinches (the
/// first `max_pinches` listed with lattice and geographic positions, and the total), removal
/// statistics, passages.
Json wet_area_json(const WetArea& area, const config::MaskOptions& options, std::size_t max_pinches = 100);

}  // namespace aq::mask

// SPDX-License-Identifier: GPL-3.0-or-later
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
#include "mask/coast.hpp"
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
  /// A floodplain run (h < 0): nx × ny, the pixels wet at the datum (the pixel rule at 0 m); empty
  /// otherwise (the threshold is then at or below the datum and `wet` is all there is).
  Bitmap datum_wet;
  /// A floodplain run: nx × ny, the pixels of `filled` wet at the datum (filled ∩ datum_wet); the
  /// rest of `filled` is the floodplain. Empty otherwise.
  Bitmap sea;
  /// A regional run: nx × ny, the pixels outside the domain in water at the datum (`wet`, or
  /// `datum_wet` when h < 0): a boundary edge with one on its outer side is open. Empty otherwise.
  Bitmap open;
  ClassCounts classes;
  std::int64_t datum_wet_pixels = 0;   ///< h < 0: pixels wet at the datum
  std::int64_t floodplain_pixels = 0;  ///< h < 0: filled pixels not wet at the datum (after pinch removal)
  /// h < 0: sea pixels the seeds reach only across the floodplain (4-connected through sea pixels
  /// they are not): lakes, lagoons and depressions below the datum behind land. A model starts
  /// them wet at 0 m. Their count, components and geographic box (pixel centres).
  std::int64_t inland_sea_pixels = 0, inland_sea_components = 0;
  double inland_sea_lon_min = 0.0, inland_sea_lon_max = 0.0, inland_sea_lat_min = 0.0, inland_sea_lat_max = 0.0;
  FillStats fill;                  ///< statistics of the fill (before pinch removal)
  std::int64_t filled_pixels = 0;  ///< |Ω_L| as returned (after pinch removal)
  std::vector<SeedInfo> seeds;
  PinchReport pinches;
  std::vector<PassageResult> passages;  ///< empty unless mask.passages

  /// The open water and the sea at the datum for the coastal band and the size field (null when
  /// empty: a global run, h >= 0).
  [[nodiscard]] CoastSources coast() const {
    return CoastSources{open.nx() > 0 ? &open : nullptr, sea.nx() > 0 ? &sea : nullptr};
  }
};

/// The pixels a regional run classifies on an unrotated lattice (README "Regional FE meshes"):
/// the domain's box and one level-0 square around it (clamped to a window lattice); outside it no
/// vertex is sampled and every pixel is dry.
PixelWindow classify_window(const Lattice& lattice, const Domain& domain);

/// The floodplain's warning of inland seas (WetArea::inland_sea_*), when there are any.
void warn_inland_sea(const WetArea& area, const Logger& log);

/// The passages of the built-in table a run judges: all of them, or in a regional run (`domain`
/// regional) those whose box lies inside the domain (its corners' and centre's pixels).
std::vector<Passage> passage_table(const Lattice& lattice, const PoleRotation& rot, const Domain* domain);

/// Marks the judged passages that options.passages_open carves (PassageResult::carved and its note).
void mark_carved(std::vector<PassageResult>& passages, const config::MaskOptions& options);

/// Runs the mask stage on `options` as validated at load (config/global_config.cpp: every mask.*
/// key's range; a negative min_depth_m is a floodplain); seeds as in place_seeds (ConfigError when no
/// all-wet window is within the radius). Logs "classify: done ...", "fill: done ...",
/// "pinches: done ...", "passages: done ..." stage lines (and a progress bar on a terminal);
/// when `report` is given, adds those stages and a "mask" section (see wet_area_json).
/// With a regional `domain` the fill runs on wet ∩ domain from the seeds regional_seeds gives
/// (`wet` stays the whole classification; the open boundary is where the outside is wet at the
/// datum: `open`, which is set) and the passage table holds the passages whose box lies inside the
/// domain. Passages named in options.passages_open are marked carved (the carving itself is
/// mask/carving.hpp's, before). With h < 0 the pixels are classified a second time at the datum
/// (0 m, the same rule and window) for `datum_wet` and `sea`.
WetArea compute_wet_area(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                         const config::MaskOptions& options, const Logger& log, Report* report,
                         const Domain* domain = nullptr);

/// The "mask" report section: parameters, class counts, fill statistics, seeds, pinches (the
/// first `max_pinches` listed with lattice and geographic positions, and the total), removal
/// statistics, passages.
Json wet_area_json(const WetArea& area, const config::MaskOptions& options, std::size_t max_pinches = 100);

}  // namespace aq::mask

// SPDX-License-Identifier: GPL-3.0-or-later
// The wet components the K-cursor fill leaves out, measured, named and explained (README
// "Passages, channels and rivers"): no sea is dropped in silence. Not in seed 002, whose fill
// keeps the component of the seed and reports nothing of the rest.
//
// A dropped component is a 4-connected component (periodic in i) of the wet pixels that are not
// filled (in a regional run: of the wet pixels inside the domain). For each one the stage finds
//   area     Σ of its pixels' areas (km²): on the lon-lat and Mercator lattices without rotation
//            exact on WGS84 (Rq²·Δλ·(sin ξ2 − sin ξ1), ξ the authalic latitude), with rotation on
//            the authalic sphere (within 0.34 % of WGS84 per pixel);
//   centre   the area-weighted mean of its pixel centres' unit vectors, geographic;
//   name     the side of a passage of the built-in table lying in it (a side is in it when one
//            of five points of its box, its centre and the centres of its quarters, falls on a
//            pixel of it), preferring the passage that would join it to the ocean; else an
//            inland basin of a short list (the Caspian, Ladoga, Qattara, Baikal, the Great Lakes,
//            ...) whose point falls on it;
//   cause    the chain of the table's passages that would join it to the filled ocean (a
//            breadth-first search from the filled set over the passages, each an edge between
//            the components or the filled set its two sides lie in: the Black Sea behind the
//            Bosphorus and the Dardanelles); whether it touches the filled set (a pixel of
//            it 4-adjacent to a filled pixel: wet pixels join it to the ocean, but no K-window
//            passes) and where, and the widest cursor K' < K whose fill reaches it (K' = 1 when it
//            touches; K' >= 2 by a K'-fill from the filled set's K'-windows); when it does not
//            touch, the land gap: the fewest 4-steps from the filled set to it (up to
//            kMaxLandGapPixels), and where; in a regional run, whether it reaches the domain's edge;
//   keep     the key to set: mask.passages_open (a closed passage of the table), mask.cursor
//            (a narrower cursor passes), mask.transects (a line through the connection or the
//            gap), mask.seeds (a seed in it meshes it apart).
// Components above mask.warn_dropped_km2 are listed (largest first); the others are counted.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/domain.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::mask {

/// The land gap is searched up to this many pixels from the filled set.
inline constexpr int kMaxLandGapPixels = 8;

struct DroppedSea {
  std::string name;     ///< a passage side's water body, an inland basin's name, or "" (then the centre names it)
  bool inland = false;  ///< named after an inland basin (a lake, a depression below sea level)
  std::int64_t pixels = 0;
  double area_km2 = 0.0;
  LonLat centre;  ///< geographic
  /// The passages of the table that would join it to the filled ocean, nearest it first (one
  /// when the other side of that one is filled; several through other dropped seas, e.g. the
  /// Black Sea: Bosphorus, Dardanelles); when none would, the passages with a side in it.
  std::vector<std::string> passages;
  bool joined_by_chain = false;              ///< `passages` is such a chain
  std::string far_sides;                     ///< not a chain: the water bodies on the passages' other sides
  std::vector<std::string> passages_carved;  ///< of those, the ones mask.passages_open carves
  bool cut = false;                          ///< passages[0]'s other side is filled (the passage that cut it off)
  int connecting_cursor = 0;                 ///< the widest cursor K' < K whose fill reaches it; 0: none (no wet path)
  std::int64_t contact_pixels = 0;           ///< its pixels 4-adjacent to a filled pixel
  LonLat contact{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  int land_gap_pixels = -1;  ///< no contact: pixels between it and the filled set (-1: more than kMaxLandGapPixels)
  double land_gap_km = 0.0;  ///< that gap's length at its place (pixels × the pixel's side)
  LonLat gap_at{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  bool reaches_domain_edge = false;  ///< regional: it is 4-adjacent to wet pixels outside the domain
  std::string keep;                  ///< the key to set to keep it
};

struct DroppedSeas {
  double threshold_km2 = 0.0;
  std::int64_t components = 0;  ///< every dropped component
  std::int64_t pixels = 0;
  double area_km2 = 0.0;
  std::vector<DroppedSea> large;  ///< area above the threshold, largest first
};

/// Finds the dropped components of `wet` against `filled` (nx × ny of `lattice`), restricted to
/// `domain` when it is regional, with `cursor` the fill's K and `carved` the names of
/// mask.passages_open. Deterministic; O(lattice words) plus the dropped pixels' runs, and at most
/// K − 2 fills and kMaxLandGapPixels dilations when a listed component needs them.
DroppedSeas find_dropped_seas(const Bitmap& wet, const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot,
                              int cursor, double threshold_km2, const std::vector<std::string>& carved,
                              const Domain* domain = nullptr);

/// "Mediterranean Sea (2.5 million km², centre 17.9°E 37.8°N): ..." for the log's warning.
std::string describe(const DroppedSea& s, int cursor);

/// The report's "dropped" section.
Json dropped_json(const DroppedSeas& d);

/// Area (km²) of one pixel of row j (see the file comment for the model).
double pixel_area_km2(const Lattice& lattice, bool rotated, std::int64_t j);

}  // namespace aq::mask

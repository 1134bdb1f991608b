// SPDX-License-Identifier: GPL-3.0-or-later
// Critical passages (ARCHITECTURE §4.3; reference/field.md §C2: users hand-curate lists of straits
// that must stay open). Not in seed 002; it reports what its K-fill does to the narrow straits.
//
// Each passage is a small geographic box across the strait with two sides, sub-boxes of open
// water at the two ends of the strait. The box is chosen so that, inside it, the two sides are
// joined by water only through the strait. A passage is
//   open            when a 4-connected path of filled pixels whose centres lie in the box joins a
//                   filled pixel with centre in side A to one with centre in side B;
//   closed          otherwise (including when a side holds no filled pixel);
//   not resolvable  when the box is less than one pixel across in λ or φ (the strait is below
//                   the lattice resolution), or a side contains no pixel centre.
// Pixel centres are mapped to geographic coordinates through the pole rotation, so the boxes work
// on rotated lattices too. Longitudes of a box may be given in any 360° window (lon_min < lon_max).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/report.hpp"
#include "core/rotation.hpp"
#include "mask/pixel_set.hpp"

namespace aq::mask {

/// A lon/lat box in geographic degrees: lon in [lon_min, lon_max] (mod 360), lat in [lat_min, lat_max].
struct GeoBox {
  double lon_min_deg = 0.0, lon_max_deg = 0.0, lat_min_deg = 0.0, lat_max_deg = 0.0;
  [[nodiscard]] bool contains(double lon_deg, double lat_deg) const;
};

struct Passage {
  const char* name = "";
  const char* side_a_name = "";  ///< the water body of side A
  const char* side_b_name = "";
  GeoBox box;             ///< across the strait, holding both sides
  GeoBox side_a, side_b;  ///< open water at the two ends, inside the box
  /// Nominal sill depth (m, positive down) of the strait: a carved channel's depth where the
  /// raster has no path between the sides deeper than mask.min_depth_m (mask/carving.hpp).
  double sill_depth_m = 0.0;
  const char* aliases = "";  ///< other names it is found by, separated by '|'
};

/// The built-in table: the 30 critical passages of ARCHITECTURE §4.3 and the Dardanelles, the
/// three Danish belts (Øresund, Great Belt, Little Belt), the mouths of Chesapeake and Delaware
/// bays and the Gorlo of the White Sea; boxes checked on ETOPO5.
std::span<const Passage> critical_passages();

/// The passage of the table called `name` (its name or an alias; ASCII letters compared without
/// case), or null.
const Passage* find_passage(const std::string& name);

enum class PassageStatus { kOpen, kClosed, kNotResolvable };
/// "open", "closed", "not resolvable".
const char* passage_status_name(PassageStatus s);

struct PassageResult {
  std::string name;
  PassageStatus status = PassageStatus::kClosed;
  GeoBox box;
  std::int64_t pixels_in_box = 0;  ///< pixel centres inside the box
  std::int64_t filled_in_box = 0;  ///< of those, filled
  std::int64_t filled_side_a = 0;  ///< filled pixels with centre in side A
  std::int64_t filled_side_b = 0;
  std::string note;  ///< why closed / not resolvable; empty when open
  bool carved = false;  ///< named in mask.passages_open (carved open before the fill)
};

/// Judges one passage on the filled bitmap (nx × ny of the lattice).
PassageResult judge_passage(const Passage& p, const Bitmap& filled, const Lattice& lattice, const PoleRotation& rot);

/// Judges every passage of the list, in order.
std::vector<PassageResult> judge_passages(std::span<const Passage> passages, const Bitmap& filled,
                                          const Lattice& lattice, const PoleRotation& rot);

/// The same on any pixel set (the forest engine's patches gathered on one rank).
PassageResult judge_passage(const Passage& p, const PixelSet& filled, const Lattice& lattice, const PoleRotation& rot);
std::vector<PassageResult> judge_passages(std::span<const Passage> passages, const PixelSet& filled,
                                          const Lattice& lattice, const PoleRotation& rot);

/// JSON array: [{name, status, box: [lon_min, lon_max, lat_min, lat_max], pixels_in_box,
/// filled_in_box, filled_side_a, filled_side_b, note}, ...].
Json to_json(std::span<const PassageResult> results);

/// Readable table for stderr: a header line, one line per passage, a summary line.
std::vector<std::string> format_passage_table(std::span<const PassageResult> results);

}  // namespace aq::mask

// SPDX-License-Identifier: GPL-3.0-or-later
// Candidate coastal blocks of a global run, ranked by how much coast they hold (ARCHITECTURE §6,
// "aquatoria blocks"). A block is a longitude/latitude box in one of two spherical systems:
//
//   * a level-0 square of the lattice (the default candidates): a box in the lattice system
//     (rotated λ', φ' when the pole is rotated), exactly 2^L × 2^L pixels. On the Mercator
//     lattice its latitudes are those of its Mercator rows (Lattice::lat_of) and the box is
//     marked `mercator_rows`: inside it the rows are evenly spaced in the Mercator ordinate, not
//     in φ' (block_contour.hpp parametrises it so);
//   * a user box ([blocks] boxes = [[lon_min, lon_max, lat_min, lat_max], ...]): a box in
//     geographic λ, φ (lon_max may pass 180: the box then crosses the antimeridian).
//
// Coastal pixel (the ranking measure): a pixel of the filled ocean Ω_L with at least one of its 8
// neighbours not filled — the coastal band of radius 1 (quadtree::coastal_band(filled, 1)):
// columns wrap at the seam, and the lattice edge at φ = ±90° is not coast. Counting the wet side
// of the coast, not coastal *classes* of the mask, makes a block's count the length of the coast
// the global mesh resolves there, at its finest level, in pixels.
//
//   filled:   . . # # #       coastal (c):   . . c # #      (# filled, . not filled;
//             . # # # #                      . c c # #       8-neighbourhood, radius 1)
//             . . # # #                      . . c c #
//
// Level-0 squares are counted exactly, word by word on the bitmaps. A user box is sampled at the
// lattice resolution: sample points (λ, φ) at the centres of a grid of about one pixel's step
// (box_extent_px cells per side, at most 2048) are mapped to the lattice pixel holding them
// (through the pole rotation), so a box counts every pixel under it about once; the wet fraction
// weights samples by cos φ (area).
// Ranking: coastal pixels descending, then wet fraction descending, then candidate order
// (level-0 squares row-major from the south-west, user boxes in the order given): deterministic.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::handoff {

/// A longitude/latitude box, degrees, in the lattice system (`lattice_system`) or geographic.
struct BlockBox {
  double lon_min_deg = 0.0, lon_max_deg = 0.0, lat_min_deg = 0.0, lat_max_deg = 0.0;
  bool lattice_system = false;  ///< true: rotated lattice coordinates; false: geographic
  bool mercator_rows = false;   ///< a box of the Mercator lattice's system: rows even in the Mercator ordinate
};

struct BlockCandidate {
  BlockBox box;
  std::int64_t square_a = -1, square_b = -1;   ///< level-0 square (column, row), or -1 for a user box
  int box_index = -1;                          ///< index into blocks.boxes, or -1 for a square
  std::int64_t coastal_pixels = 0;             ///< coastal pixels inside (sampled for user boxes)
  std::int64_t filled_pixels = 0;              ///< pixels of Ω_L inside (sampled for user boxes)
  double wet_fraction = 0.0;                   ///< area fraction of the box inside Ω_L, 0..1
  int suggested_ny = 0;                        ///< cells along η for the regional grid
  [[nodiscard]] std::string describe() const;  ///< "level-0 square (a, b)" or "box k"
};

/// The box's width and height in lattice pixels, {along λ, along φ} of its system: on the lon-lat
/// lattice its extents in degrees over Δ_L (the seed's measure, also for a geographic box under a
/// rotated pole). On the Mercator lattice a pixel is a square of side Δ_L·cos φ' degrees of arc:
/// a box of the lattice system measures Δλ/Δ_L by its Mercator height over Δ_L (exact: 2^L × 2^L
/// for a level-0 square); a geographic box measures its arc extents at its centre (Δλ·cos φ and
/// Δφ) over the pixel side at the centre's φ'.
std::array<double, 2> box_extent_px(const BlockBox& box, const Lattice& lat, const PoleRotation& rotation);

/// Suggested η cells of a block: its height in lattice pixels (box_extent_px, the finest global
/// element) times `refinement`, at least 8, rounded up to even; `fixed_ny` > 0 wins.
int suggest_ny(const BlockBox& box, const Lattice& lat, const PoleRotation& rotation, int refinement, int fixed_ny);

/// The pixel holding a point given in lattice degrees (the last row or column for a point on the
/// lattice's edge), or nothing for a point beyond the Mercator lattice's rows (a cap, dry by
/// construction).
std::optional<mask::PixelIJ> pixel_holding(const Lattice& lat, mask::LonLat lattice_deg);

/// The filled pixels with a non-filled pixel among their 8 neighbours (see the file comment).
Bitmap coastal_pixels(const Bitmap& filled);

/// Candidates ranked best first (see the file comment): every level-0 square with at least one
/// coastal pixel when options.boxes is empty, else every user box. `filled` is Ω_L on `lat`.
/// Throws ConfigError naming blocks.boxes[k] for a user box holding no pixel of the filled ocean
/// ("a block without water"), and InputError when no level-0 square has coast.
std::vector<BlockCandidate> rank_blocks(const Bitmap& filled, const Lattice& lat, const PoleRotation& rotation,
                                        const config::BlocksOptions& options);

}  // namespace aq::handoff

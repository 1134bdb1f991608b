// SPDX-License-Identifier: GPL-3.0-or-later
// Pinch vertices of the filled set Ω_L (ARCHITECTURE §4.6: "p pinch vertices where the filled set
// touches itself at a single corner"; the Euler check V - E + F = 2 - b - p counts them) and their
// optional removal (mask.remove_pinches). Seed 002 does not discuss them; several ocean models
// reject meshes with such vertices.
//
// A lattice vertex (I, J), 1 <= J <= ny-1, is a pinch when the 2×2 pixel block around it is
// filled in a diagonal pattern. Bits in the order NW NE SW SE:
//
//         I-1     I
//   J   +-----+-----+          1001 = NW and SE filled (kNwSe)
//       | NW  | NE  |          0110 = NE and SW filled (kNeSw)
//       +-----o-----+
//       | SW  | SE  |          NW = pixel (I-1, J), NE = (I, J), SW = (I-1, J-1), SE = (I, J-1),
//   J-1 +-----+-----+          I-1 wraps over the seam. Vertices on the poles (J = 0, ny) have
//                              only two pixels and are never pinches.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/rotation.hpp"
#include "mask/lattice_coords.hpp"
#include "mask/pixel_set.hpp"

namespace aq::mask {

enum class PinchPattern : std::uint8_t {
  kNwSe = 0b1001,  ///< NW and SE pixels filled
  kNeSw = 0b0110,  ///< NE and SW pixels filled
};

/// "1001 (NW-SE)" / "0110 (NE-SW)".
const char* pinch_pattern_name(PinchPattern p);

struct Pinch {
  PixelIJ vertex;  ///< lattice vertex (I, J)
  PinchPattern pattern = PinchPattern::kNwSe;
  LonLat lattice_pos;  ///< lattice (rotated) degrees of the vertex
  LonLat geographic;   ///< geographic degrees of the vertex
};

/// All pinch vertices of `filled` (nx × ny), sorted by (J, I); positions are left zero (see
/// locate_pinches). OpenMP over rows, per-row counts merged by prefix sums: identical output for
/// any thread count.
std::vector<Pinch> find_pinches(const Bitmap& filled);

/// Number of pinch vertices (same rule as find_pinches, without the list).
std::int64_t count_pinches(const Bitmap& filled);

/// Fills lattice_pos and geographic of each pinch.
void locate_pinches(std::vector<Pinch>& pinches, const Lattice& lattice, const PoleRotation& rot);

struct PinchRemovalStats {
  std::int64_t pinches_found = 0;   ///< pinch vertices before removal
  int rounds = 0;                   ///< detect / resolve / refill rounds
  std::int64_t pixels_chosen = 0;   ///< pixels taken out directly at a pinch
  std::int64_t pixels_removed = 0;  ///< total pixels that left the filled set (chosen + lost windows)
  std::int64_t unresolved = 0;      ///< pinches left (both pixels in seed windows; K = 1 only)
};

/// Resolves every pinch of a K-fill result, in rounds:
///   1. list the pinches (J, I order); for each one still present, take out one of its two
///      filled pixels: never one inside a seed window; otherwise the one of smaller cost, then of
///      smaller pixel index j·nx + i. Cost = pixels lost locally (the pixel and the neighbours no
///      longer covered by any all-filled K-window, which leave the set with it) + an estimate of
///      the windows cut off, computed only when the removal splits the all-filled windows of the
///      surrounding (3K+1)² window box into more 4-connected pieces: breadth-first searches of at
///      most 4096 windows per piece; a fully explored piece without a seed window counts its
///      size, cutting a seed's small piece off a large one costs 64·4096, an undecided large piece
///      4096 ("keep the larger area").
///   2. refill: filled = k_fill(filled, k, seed_windows) keeps only windows still reachable.
/// until no pinch is left (or a round removes nothing).
/// Guarantees on return: filled ⊆ its input; filled == k_fill(filled, k, seed_windows), i.e.
/// every filled pixel lies in an all-filled K×K window reachable from a seed window through
/// all-filled windows (the K-cursor property holds exactly: no channel narrower than K pixels is
/// created, Ω_L stays 4-connected from the seeds); count_pinches(filled) == unresolved (0 for
/// K >= 2). Not guaranteed: maximality — a region whose only K-wide connection ran through the
/// removed pixel leaves with it (counted in pixels_removed); the cost makes this rare (ETOPO5
/// upsampled to 1', K = 2: 4658 pinches resolved by removing 4670 pixels in one round).
/// `seed_windows` are the lower-left pixels of the seed windows (from place_seeds).
PinchRemovalStats remove_pinches(Bitmap& filled, int k, std::span<const PixelIJ> seed_windows);

/// Step 1 of one round of remove_pinches on any pixel set: for each of `pinches` (J, I order) still
/// present, takes out the chosen pixel and those its windows leave (cleared in `filled`). Returns
/// the pinches resolved. The forest engine runs it on its patches gathered on one rank.
std::int64_t resolve_pinches(PixelSet& filled, int k, std::span<const PixelIJ> seed_windows,
                             const std::vector<Pinch>& pinches);

}  // namespace aq::mask

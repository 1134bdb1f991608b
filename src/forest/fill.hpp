// SPDX-License-Identifier: GPL-3.0-or-later
// The K-cursor fill on the forest (ARCHITECTURE §4.3; mask/k_cursor_fill.hpp is the dense form):
// connected components of the all-wet K × K windows across patches and ranks.
//
//   A window is named by its lower-left pixel, so it belongs to one patch. With K <= P:
//   * a "core" patch — all wet, and its 8 neighbours all wet — has every window all-wet, and they
//     are one 4-connected component: one node;
//   * every other patch with wet pixels is "materialised": its windows W are computed on the
//     3P × 3P window of its neighbours (the erosion needs K - 1 pixels north and east) and cut
//     into 4-connected components inside the patch, one node each;
//   * nodes of face-adjacent patches are joined where two adjacent windows are both all-wet (a
//     core patch meets only wholly wet patches, whose windows next to it are all-wet).
//   Node ids are key·(P² + 1) + component; a rank joins its nodes (union-find, the root of a set
//   is its smallest id), rank 0 merges the sets that cross ranks, so every component is labelled
//   by its smallest node id on any number of ranks. Ω_L is the dilation by K of the windows whose
//   component holds a seed window (mask::dilate_windows on the 3P × 3P window of reached windows).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/log.hpp"
#include "core/rotation.hpp"
#include "forest/patches.hpp"
#include "mask/k_cursor_fill.hpp"

namespace aq::forest {

/// What the forest's fill made.
struct ForestFill {
  std::vector<PatchBits> filled;  ///< per local patch: Ω_L
  std::vector<mask::SeedInfo> seeds;
  mask::FillStats stats;  ///< over all ranks (the same figures as the dense engine's)
};

/// The fill of the wet pixels `wet` (per local patch; wet ∩ domain for a regional run) from the
/// geographic seeds, K = `k` (1..P). Collective. Throws ConfigError for k outside 1..min(64, P)
/// (naming mask.cursor) and for seeds as mask::place_seeds does (the same message).
ForestFill forest_fill(const PatchForest& pf, const std::vector<PatchBits>& wet, const PoleRotation& rot, int k,
                       const std::vector<std::array<double, 2>>& seeds, double radius_deg, const Logger& log);

/// Ω_L again from the filled set itself (the refill of mask.remove_pinches: mask::k_fill with the
/// seed windows), per local patch. Collective.
std::vector<PatchBits> forest_refill(const PatchForest& pf, const std::vector<PatchBits>& filled, int k,
                                     const std::vector<mask::PixelIJ>& seed_windows);

/// 4-connected components of a pixel set over all ranks (mask::count_components), with `probe`
/// the pixels that mark a component as touching (both per local patch). Collective.
mask::ComponentStats forest_components(const PatchForest& pf, const std::vector<PatchBits>& set,
                                       const std::vector<PatchBits>& probe);

/// The pixels of `set` whose 4-connected component (over all ranks, periodic as the lattice) holds
/// no `probe` pixel, per local patch, and the components' statistics (forest_components). The
/// forest's mask::flood_fill: `set` less what the probe's pixels reach. Collective.
struct Unreached {
  std::vector<PatchBits> pixels;
  mask::ComponentStats stats;
};
Unreached forest_unreached(const PatchForest& pf, const std::vector<PatchBits>& set,
                           const std::vector<PatchBits>& probe);

}  // namespace aq::forest

// SPDX-License-Identifier: GPL-3.0-or-later
// The quadtree's level pyramid on the forest (quadtree/leaves.hpp's omega and any, ARCHITECTURE
// §4.4) in two parts, so that no level is held over every pixel:
//
//   coarse  levels 0 .. lp (lp = the patch level): bitmaps over the patch grid and coarser,
//           replicated on every rank (a few bits per patch);
//   fine    levels lp .. L inside each patch, held by the patch's rank, and only for patches
//           whose leaves are finer than the patch ("active"); an inactive patch is either inside a
//           leaf of level <= lp (every fine bit set) or holds no filled pixel (none set).
//
// Every refinement of the dense engine runs on it with the dense engine's own per-level code
// (apply_size_field_level, apply_rules_level, grade_level) on the coarse bitmaps or on a patch's
// piece, in the dense order, so the leaves are the dense engine's: the coastal band on the 3P × 3P
// window around a patch; the size field per patch (an inactive patch is tested per field cell and
// row, where the field and the square size are constant, and made active only when a square of it
// splits); the grading per level v with the split level-v squares of all ranks gathered (the
// squares of a patch's rows within the grading radii, columns periodic as the dense dilation's).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "config/options.hpp"
#include "core/rotation.hpp"
#include "forest/patches.hpp"
#include "quadtree/leaves.hpp"
#include "size/size_field.hpp"

namespace aq::raster {
class Bathymetry;
}

namespace aq::forest {

class ForestPyramid {
 public:
  /// The bare D_l rule of `filled` (per local patch) and, when `coast_band` > 0, the coastal band
  /// split to level L (quadtree::make_level_masks + apply_coast_band). Collective. Needs L >= 1.
  /// `open` (a regional run; null otherwise): per local patch, the water beyond the domain's edge,
  /// which is no coast (mask/coast.hpp). `sea` (a floodplain run; null otherwise): per local patch,
  /// the filled pixels wet at the datum, whose side of the shoreline at 0 m is in the band as well.
  ForestPyramid(const PatchForest& pf, const std::vector<PatchBits>& filled, int coast_band,
                const std::vector<PatchBits>* open = nullptr, const std::vector<PatchBits>* sea = nullptr);

  /// quadtree::apply_refinement_rules (the level form). Collective.
  void apply_rules(const config::QuadtreeOptions& options, const PoleRotation& rotation,
                   const raster::Bathymetry* bathy);
  /// quadtree::apply_size_field. Collective.
  void apply_size_field(const size::SizeField& field);
  /// quadtree::grade_levels. Collective; the counts are over all ranks.
  quadtree::GradeStats grade(const size::SizeField& field);

  /// quadtree::count_leaves_per_level over all ranks. Collective.
  [[nodiscard]] std::vector<std::int64_t> leaves_per_level() const;

  /// Whether the level-l square (a, b) lies inside a leaf of level <= l (omega) / holds a filled
  /// pixel (any). Squares of level > lp must be in a local patch.
  [[nodiscard]] bool omega(int l, std::int64_t a, std::int64_t b) const;
  [[nodiscard]] bool any(int l, std::int64_t a, std::int64_t b) const;

  /// Local patches holding a fine pyramid, and its bytes (for the log and the memory figures).
  [[nodiscard]] std::int64_t active_patches() const;
  [[nodiscard]] std::int64_t fine_bytes() const;
  [[nodiscard]] int patch_level() const { return lp_; }

 private:
  struct Fine {
    std::vector<Bitmap> omega, any;  // index d = l - lp, 2^d × 2^d squares
  };
  Fine& activate(std::size_t l);
  // The omega (or any) bit of a square of level l > lp in a local patch.
  [[nodiscard]] bool fine_bit(int l, std::int64_t a, std::int64_t b, bool omega) const;
  [[nodiscard]] Bitmap band_bits(std::size_t l, int radius) const;
  void sync_coarse();
  [[nodiscard]] bool would_split(std::size_t l, const size::SizeField& field) const;

  const PatchForest& pf_;
  const std::vector<PatchBits>& filled_;
  std::vector<PatchBits> ghosts_;  // the filled set of the ghost patches
  const std::vector<PatchBits>* open_ = nullptr;
  std::vector<PatchBits> open_ghosts_;  // the open water of the ghost patches (with open_)
  const std::vector<PatchBits>* sea_ = nullptr;
  std::vector<PatchBits> sea_ghosts_;  // the sea of the ghost patches (with sea_)
  int L_ = 0, lp_ = 0, plog_ = 0;
  std::int64_t p_ = 1;
  std::vector<Bitmap> omega_c_, any_c_;  // levels 0..lp
  std::vector<std::unique_ptr<Fine>> fine_;
  std::vector<std::uint8_t> all_;  // inactive patch: 1 = every fine bit set, 0 = none
};

}  // namespace aq::forest

// SPDX-License-Identifier: GPL-3.0-or-later
// A pixel set of the forest gathered on rank 0 as patches (mask/pixel_set.hpp): a state byte per
// patch of the lattice and the bitmaps of the mixed ones, so its memory follows the coast. The
// algorithms that visit a few pixels of the whole set in a fixed global order — the pinch
// removal's choices, the passage table — run on it unchanged.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "forest/patches.hpp"
#include "mask/lattice_coords.hpp"
#include "mask/pinches.hpp"
#include "mask/pixel_set.hpp"

namespace aq::forest {

class SparseSet final : public mask::PixelSet {
 public:
  /// `set` (per local patch) on rank 0; an empty set on the other ranks. Collective.
  static SparseSet gather(const PatchForest& pf, const std::vector<PatchBits>& set);

  [[nodiscard]] std::int64_t nx() const override { return grid_.lat.nx; }
  [[nodiscard]] std::int64_t ny() const override { return grid_.lat.ny; }
  [[nodiscard]] bool get(std::int64_t i, std::int64_t j) const override;
  void clear(std::int64_t i, std::int64_t j) override;
  /// The pixels cleared since the gather that were set, in the order they were cleared.
  [[nodiscard]] const std::vector<mask::PixelIJ>& cleared() const { return cleared_; }
  [[nodiscard]] std::int64_t bytes() const;

 private:
  PatchGrid grid_;
  std::vector<std::uint8_t> state_;  // Fill per patch key
  std::unordered_map<std::int64_t, Bitmap> bits_;
  std::vector<mask::PixelIJ> cleared_;
};

/// Clears `pixels` (lattice pixels, any rank's) in this rank's patches of `set`.
void clear_pixels(const PatchForest& pf, std::vector<PatchBits>& set, const std::vector<mask::PixelIJ>& pixels);

/// The pinch vertices of a set (mask::find_pinches), sorted by (J, I), on rank 0 (empty on the
/// others); their total on every rank in `total`. Collective.
std::vector<mask::Pinch> forest_pinches(const PatchForest& pf, const std::vector<PatchBits>& set, std::int64_t& total);

}  // namespace aq::forest

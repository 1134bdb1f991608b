// SPDX-License-Identifier: GPL-3.0-or-later
// A set of lattice pixels seen through get/clear, for the algorithms that visit only a few pixels
// of it (the pinch removal's choices, the passage table): the dense engine's bitmap, or the forest
// engine's patches gathered on one rank (forest/sparse_set.hpp), which never holds the lattice.
#pragma once

#include <cstdint>

#include "core/bitmap.hpp"

namespace aq::mask {

class PixelSet {
 public:
  virtual ~PixelSet() = default;
  [[nodiscard]] virtual std::int64_t nx() const = 0;
  [[nodiscard]] virtual std::int64_t ny() const = 0;
  /// Pixel (i, j), 0 <= i < nx, 0 <= j < ny.
  [[nodiscard]] virtual bool get(std::int64_t i, std::int64_t j) const = 0;
  virtual void clear(std::int64_t i, std::int64_t j) = 0;
};

/// A bitmap as a PixelSet (not owned).
class BitmapSet final : public PixelSet {
 public:
  explicit BitmapSet(Bitmap& b) : b_(b) {}
  [[nodiscard]] std::int64_t nx() const override { return b_.nx(); }
  [[nodiscard]] std::int64_t ny() const override { return b_.ny(); }
  [[nodiscard]] bool get(std::int64_t i, std::int64_t j) const override { return b_.get(i, j); }
  void clear(std::int64_t i, std::int64_t j) override { b_.clear(i, j); }

 private:
  Bitmap& b_;
};

/// A read-only bitmap as a PixelSet (clear throws InternalError).
class ConstBitmapSet final : public PixelSet {
 public:
  explicit ConstBitmapSet(const Bitmap& b) : b_(b) {}
  [[nodiscard]] std::int64_t nx() const override { return b_.nx(); }
  [[nodiscard]] std::int64_t ny() const override { return b_.ny(); }
  [[nodiscard]] bool get(std::int64_t i, std::int64_t j) const override { return b_.get(i, j); }
  void clear(std::int64_t i, std::int64_t j) override;

 private:
  const Bitmap& b_;
};

}  // namespace aq::mask

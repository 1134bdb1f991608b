// SPDX-License-Identifier: GPL-3.0-or-later
// A 2-D bitmap, 1 bit per pixel, row-major with each row padded to whole 64-bit words so that
// rows can be written by different threads. Used for wet/dry/coastal and filled-pixel masks
// (ARCHITECTURE §4.2: 466 MB for a 15" global lattice).
//
//   word w of row j holds pixels i = 64w .. 64w+63, bit (i & 63) of the word.
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace aq {

/// Number of set bits. Inline SWAR: the baseline x86-64 target has no POPCNT instruction, and
/// std::popcount would call a library function (libgcc's, table-driven) for every word.
constexpr int popcount64(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

/// Number of set bits of words[0..n): the POPCNT instruction when the processor has it (chosen
/// at load time), on the OpenMP threads for large arrays (a 15" lattice bitmap is 58 M words).
std::int64_t count_bits(const std::uint64_t* words, std::int64_t n);

class Bitmap {
 public:
  Bitmap() = default;
  Bitmap(std::int64_t nx, std::int64_t ny)
      : nx_(nx), ny_(ny), words_per_row_((nx + 63) / 64), words_(static_cast<std::size_t>(words_per_row_ * ny), 0ULL) {}

  [[nodiscard]] std::int64_t nx() const { return nx_; }
  [[nodiscard]] std::int64_t ny() const { return ny_; }
  [[nodiscard]] std::int64_t words_per_row() const { return words_per_row_; }

  [[nodiscard]] bool get(std::int64_t i, std::int64_t j) const { return ((word(i, j) >> (i & 63)) & 1ULL) != 0; }
  void set(std::int64_t i, std::int64_t j) { word_ref(i, j) |= (1ULL << (i & 63)); }
  void clear(std::int64_t i, std::int64_t j) { word_ref(i, j) &= ~(1ULL << (i & 63)); }
  void assign(std::int64_t i, std::int64_t j, bool v) { v ? set(i, j) : clear(i, j); }

  /// Pointer to the first word of row j.
  std::uint64_t* row(std::int64_t j) { return words_.data() + j * words_per_row_; }
  [[nodiscard]] const std::uint64_t* row(std::int64_t j) const { return words_.data() + j * words_per_row_; }

  /// Number of set bits (padding bits are always kept clear).
  [[nodiscard]] std::int64_t count() const {
    return count_bits(words_.data(), static_cast<std::int64_t>(words_.size()));
  }
  [[nodiscard]] std::size_t bytes() const { return words_.size() * sizeof(std::uint64_t); }
  [[nodiscard]] bool operator==(const Bitmap& o) const { return nx_ == o.nx_ && ny_ == o.ny_ && words_ == o.words_; }
  std::vector<std::uint64_t>& words() { return words_; }
  [[nodiscard]] const std::vector<std::uint64_t>& words() const { return words_; }

 private:
  [[nodiscard]] std::uint64_t word(std::int64_t i, std::int64_t j) const {
    return words_[static_cast<std::size_t>(j * words_per_row_ + (i >> 6))];
  }
  std::uint64_t& word_ref(std::int64_t i, std::int64_t j) {
    return words_[static_cast<std::size_t>(j * words_per_row_ + (i >> 6))];
  }

  std::int64_t nx_ = 0;
  std::int64_t ny_ = 0;
  std::int64_t words_per_row_ = 0;
  std::vector<std::uint64_t> words_;
};

}  // namespace aq

// SPDX-License-Identifier: GPL-3.0-or-later
// ASCII drawings of bitmaps for the mask tests. The first line of a drawing is the northernmost
// row (j = ny-1), as on a map; column 0 is the westernmost (i = 0, just east of the seam).
// '#' (or any of "#1SX") = set, anything else = clear.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "core/bitmap.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::mask::test {

inline bool is_set_char(char c) { return c == '#' || c == '1' || c == 'S' || c == 'X'; }

/// Bitmap from drawn rows (all of equal length).
inline Bitmap draw(const std::vector<std::string_view>& rows) {
  const auto ny = static_cast<std::int64_t>(rows.size());
  const auto nx = static_cast<std::int64_t>(rows.empty() ? 0 : rows[0].size());
  Bitmap b(nx, ny);
  for (std::int64_t r = 0; r < ny; ++r) {
    const std::string_view row = rows[static_cast<std::size_t>(r)];
    for (std::int64_t i = 0; i < nx && i < static_cast<std::int64_t>(row.size()); ++i)
      if (is_set_char(row[static_cast<std::size_t>(i)])) b.set(i, ny - 1 - r);
  }
  return b;
}

/// Positions of the 'S' characters of a drawing, as pixels (i, j).
inline std::vector<PixelIJ> marks(const std::vector<std::string_view>& rows, char c = 'S') {
  std::vector<PixelIJ> out;
  const auto ny = static_cast<std::int64_t>(rows.size());
  for (std::int64_t r = 0; r < ny; ++r) {
    const std::string_view row = rows[static_cast<std::size_t>(r)];
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(row.size()); ++i)
      if (row[static_cast<std::size_t>(i)] == c) out.push_back({i, ny - 1 - r});
  }
  return out;
}

/// The drawing of a bitmap ('#' set, '.' clear), northernmost row first, rows joined by '\n'.
inline std::string render(const Bitmap& b) {
  std::string s;
  for (std::int64_t j = b.ny() - 1; j >= 0; --j) {
    for (std::int64_t i = 0; i < b.nx(); ++i) s += b.get(i, j) ? '#' : '.';
    s += '\n';
  }
  return s;
}

/// Copies `small` into `big` with its pixel (0, 0) at (i0, j0).
inline void paste(Bitmap& big, const Bitmap& small, std::int64_t i0, std::int64_t j0) {
  for (std::int64_t j = 0; j < small.ny(); ++j)
    for (std::int64_t i = 0; i < small.nx(); ++i) big.assign(i0 + i, j0 + j, small.get(i, j));
}

/// Random bitmap with set probability p (reproducible from `seed`).
inline Bitmap random_bitmap(std::int64_t nx, std::int64_t ny, double p, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution d(p);
  Bitmap b(nx, ny);
  for (std::int64_t j = 0; j < ny; ++j)
    for (std::int64_t i = 0; i < nx; ++i)
      if (d(rng)) b.set(i, j);
  return b;
}

/// A smooth random "ocean" on nx × ny: a sum of a few random cosine waves thresholded at level
/// `t` (larger t = more land); wraps in i. Deterministic from `seed`.
inline Bitmap smooth_random_bitmap(std::int64_t nx, std::int64_t ny, double t, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  struct Wave {
    double kx, ky, phase, amp;
  };
  std::vector<Wave> waves;
  for (int k = 0; k < 12; ++k) {
    const double kx = std::floor(1.0 + 30.0 * u(rng));  // whole periods along i: periodic
    const double ky = 1.0 + 30.0 * u(rng);
    waves.push_back({kx, ky, 6.283185307 * u(rng), 1.0 / (1.0 + 0.1 * kx)});
  }
  Bitmap b(nx, ny);
  for (std::int64_t j = 0; j < ny; ++j)
    for (std::int64_t i = 0; i < nx; ++i) {
      double v = 0.0;
      const double x = 6.283185307 * static_cast<double>(i) / static_cast<double>(nx);
      const double y = 3.141592653 * static_cast<double>(j) / static_cast<double>(ny);
      for (const Wave& w : waves) v += w.amp * std::cos(w.kx * x + w.ky * y + w.phase);
      if (v < t) b.set(i, j);
    }
  return b;
}

}  // namespace aq::mask::test

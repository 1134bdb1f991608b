// SPDX-License-Identifier: GPL-3.0-or-later
// Test fixtures for the quadtree and mesh tests: small lattices, seeded random filled sets,
// masks drawn in ASCII, and naive (per-pixel) reference implementations that the bitmap
// algorithms are checked against.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/bitmap.hpp"
#include "core/lattice.hpp"
#include "core/types.hpp"
#include "quadtree/leaves.hpp"

namespace aq::testing {

/// A lattice of 2·n0·2^L × n0·2^L pixels with n0 = 180 / step_deg.
inline Lattice make_lattice(double step_deg, int levels, double lon0 = -180.0) {
  return Lattice::make(step_deg, levels, lon0);
}

/// A seeded random filled set made of blobs: a coarse random field upsampled and thresholded,
/// plus pixel noise, so that it has big wet areas (coarse leaves) and a ragged coast.
inline Bitmap random_mask(std::int64_t nx, std::int64_t ny, std::uint32_t seed, double wet = 0.6, double noise = 0.03,
                          int cell = 6) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::int64_t cx = nx / cell + 2, cy = ny / cell + 2;
  std::vector<double> field(static_cast<std::size_t>(cx * cy));
  for (double& v : field) v = u(rng);
  Bitmap m(nx, ny);
  for (std::int64_t j = 0; j < ny; ++j) {
    for (std::int64_t i = 0; i < nx; ++i) {
      const double x = static_cast<double>(i) / cell, y = static_cast<double>(j) / cell;
      const auto x0 = static_cast<std::int64_t>(x), y0 = static_cast<std::int64_t>(y);
      const double tx = x - static_cast<double>(x0), ty = y - static_cast<double>(y0);
      const auto at = [&](std::int64_t a, std::int64_t b) {
        return field[static_cast<std::size_t>(b * cx + (a % (cx - 1)))];
      };
      const double v = (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
                       ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
      bool f = v < wet;
      if (u(rng) < noise) f = !f;
      if (f) m.set(i, j);
    }
  }
  return m;
}

/// A filled set drawn in ASCII: rows[0] is the northernmost row (j = ny-1), '#' is filled.
/// Each string has nx characters.
inline Bitmap draw(const std::vector<std::string>& rows) {
  const auto ny = static_cast<std::int64_t>(rows.size());
  const auto nx = static_cast<std::int64_t>(rows.front().size());
  Bitmap m(nx, ny);
  for (std::int64_t r = 0; r < ny; ++r) {
    for (std::int64_t i = 0; i < nx; ++i) {
      if (rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(i)] == '#') m.set(i, ny - 1 - r);
    }
  }
  return m;
}

/// Level of the leaf holding each pixel (-1 where not covered), row-major.
inline std::vector<int> level_map(const std::vector<quadtree::Leaf>& leaves, const Lattice& lat) {
  std::vector<int> lev(static_cast<std::size_t>(lat.nx * lat.ny), -1);
  for (const quadtree::Leaf& f : leaves) {
    const std::int64_t s = quadtree::leaf_size(lat, f);
    for (std::int64_t j = f.b * s; j < (f.b + 1) * s; ++j)
      for (std::int64_t i = f.a * s; i < (f.a + 1) * s; ++i) lev[static_cast<std::size_t>(j * lat.nx + i)] = f.level;
  }
  return lev;
}

/// Naive balance check: number of ordered pairs of 4- (or 8-) adjacent covered pixels whose
/// leaves differ by two levels or more (columns wrap at the seam).
inline std::int64_t naive_violations(const std::vector<quadtree::Leaf>& leaves, const Lattice& lat, bool corner) {
  const std::vector<int> lev = level_map(leaves, lat);
  std::int64_t n = 0;
  for (std::int64_t j = 0; j < lat.ny; ++j) {
    for (std::int64_t i = 0; i < lat.nx; ++i) {
      const int a = lev[static_cast<std::size_t>(j * lat.nx + i)];
      if (a < 0) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || (!corner && dx != 0 && dy != 0)) continue;
          const std::int64_t jj = j + dy;
          if (jj < 0 || jj >= lat.ny) continue;
          const int b = lev[static_cast<std::size_t>(jj * lat.nx + wrap_index(i + dx, lat.nx))];
          if (b >= 0 && std::abs(a - b) >= 2) ++n;
        }
      }
    }
  }
  return n;
}

/// Naive ripple balance: while some pair of adjacent leaves differs by >= 2 levels, split the
/// coarser one into its four children (the textbook worklist; the result is unique).
inline std::vector<quadtree::Leaf> naive_balance(std::vector<quadtree::Leaf> leaves, const Lattice& lat, bool corner) {
  for (;;) {
    const std::vector<int> lev = level_map(leaves, lat);
    // Find the coarsest leaf with a too-fine neighbour.
    std::vector<char> split(leaves.size(), 0);
    bool any = false;
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      const quadtree::Leaf& f = leaves[k];
      const std::int64_t s = quadtree::leaf_size(lat, f);
      const std::int64_t i0 = f.a * s, j0 = f.b * s;
      for (std::int64_t j = j0 - 1; j <= j0 + s && !split[k]; ++j) {
        for (std::int64_t i = i0 - 1; i <= i0 + s && !split[k]; ++i) {
          const bool inside = i >= i0 && i < i0 + s && j >= j0 && j < j0 + s;
          if (inside || j < 0 || j >= lat.ny) continue;
          const bool diag = (i < i0 || i >= i0 + s) && (j < j0 || j >= j0 + s);
          if (diag && !corner) continue;
          const int b = lev[static_cast<std::size_t>(j * lat.nx + wrap_index(i, lat.nx))];
          if (b >= f.level + 2) split[k] = 1;
        }
      }
      any = any || split[k];
    }
    if (!any) break;
    std::vector<quadtree::Leaf> next;
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      const quadtree::Leaf& f = leaves[k];
      if (!split[k]) {
        next.push_back(f);
        continue;
      }
      for (int c = 0; c < 4; ++c) next.push_back({f.level + 1, 2 * f.a + (c & 1), 2 * f.b + (c >> 1)});
    }
    leaves = std::move(next);
  }
  std::sort(leaves.begin(), leaves.end(), [&](const quadtree::Leaf& x, const quadtree::Leaf& y) {
    return quadtree::leaf_key(lat, x) < quadtree::leaf_key(lat, y);
  });
  return leaves;
}

/// Number of 4-connected components of a filled set (columns wrap at the seam).
inline std::int64_t components4(const Bitmap& m) {
  const std::int64_t nx = m.nx(), ny = m.ny();
  std::vector<char> seen(static_cast<std::size_t>(nx * ny), 0);
  std::int64_t comps = 0;
  std::vector<std::int64_t> stack;
  for (std::int64_t s = 0; s < nx * ny; ++s) {
    if (seen[static_cast<std::size_t>(s)] || !m.get(s % nx, s / nx)) continue;
    ++comps;
    stack.push_back(s);
    seen[static_cast<std::size_t>(s)] = 1;
    while (!stack.empty()) {
      const std::int64_t p = stack.back();
      stack.pop_back();
      const std::int64_t i = p % nx, j = p / nx;
      const std::array<std::array<std::int64_t, 2>, 4> nb{
          {{wrap_index(i + 1, nx), j}, {wrap_index(i - 1, nx), j}, {i, j + 1}, {i, j - 1}}};
      for (const auto& q : nb) {
        if (q[1] < 0 || q[1] >= ny || !m.get(q[0], q[1])) continue;
        const std::int64_t id = q[1] * nx + q[0];
        if (seen[static_cast<std::size_t>(id)]) continue;
        seen[static_cast<std::size_t>(id)] = 1;
        stack.push_back(id);
      }
    }
  }
  return comps;
}

/// Naive boundary length in pixel sides: sides between a filled pixel and an unfilled one or
/// the lattice edge at the poles.
inline std::int64_t naive_boundary_length(const Bitmap& m) {
  std::int64_t n = 0;
  for (std::int64_t j = 0; j < m.ny(); ++j) {
    for (std::int64_t i = 0; i < m.nx(); ++i) {
      if (!m.get(i, j)) continue;
      n += !m.get(wrap_index(i + 1, m.nx()), j);
      n += !m.get(wrap_index(i - 1, m.nx()), j);
      n += (j + 1 >= m.ny()) || !m.get(i, j + 1);
      n += (j == 0) || !m.get(i, j - 1);
    }
  }
  return n;
}

}  // namespace aq::testing

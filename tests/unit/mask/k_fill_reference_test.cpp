// SPDX-License-Identifier: GPL-3.0-or-later
// The bitmap K-fill against a literal K-cursor (seed 002 §2): a K×K cursor is moved one pixel at
// a time (BFS over cursor positions, periodic in i, bounded in j), a position is taken only when
// every pixel under the cursor is wet, and Ω_L is the union of the cursors taken. 200 random masks
// of several sizes and densities, K = 1..4, random seeds (some on land).
#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <vector>

#include "mask/k_cursor_fill.hpp"
#include "unit/mask/mask_drawing.hpp"

namespace aq::mask::unit_mask_k_fill_reference_test {
namespace {

bool cursor_all_wet(const Bitmap& wet, int k, std::int64_t i0, std::int64_t j0) {
  if (j0 < 0 || j0 + k > wet.ny()) return false;
  for (int b = 0; b < k; ++b)
    for (int a = 0; a < k; ++a)
      if (!wet.get((i0 + a) % wet.nx(), j0 + b)) return false;
  return true;
}

Bitmap reference_k_fill(const Bitmap& wet, int k, const std::vector<PixelIJ>& seeds) {
  const std::int64_t nx = wet.nx(), ny = wet.ny();
  std::vector<char> visited(static_cast<std::size_t>(nx * ny), 0);
  Bitmap filled(nx, ny);
  std::deque<PixelIJ> queue;
  const auto take = [&](std::int64_t i, std::int64_t j) {
    if (j < 0 || j >= ny) return;
    i = ((i % nx) + nx) % nx;
    auto& v = visited[static_cast<std::size_t>(j * nx + i)];
    if (v != 0 || !cursor_all_wet(wet, k, i, j)) return;
    v = 1;
    queue.push_back({i, j});
    for (int b = 0; b < k; ++b)
      for (int a = 0; a < k; ++a) filled.set((i + a) % nx, j + b);
  };
  for (const PixelIJ& s : seeds) {
    take(s.i, s.j);
    while (!queue.empty()) {
      const PixelIJ c = queue.front();
      queue.pop_front();
      take(c.i + 1, c.j);
      take(c.i - 1, c.j);
      take(c.i, c.j + 1);
      take(c.i, c.j - 1);
    }
  }
  return filled;
}

TEST(KFillReference, EqualsLiteralCursorOn200RandomMasks) {
  struct Size {
    std::int64_t nx, ny;
  };
  const Size sizes[] = {{5, 4}, {13, 7}, {64, 9}, {65, 20}, {130, 33}};
  std::mt19937 rng(20240611);
  int cases = 0, nontrivial = 0;
  for (int m = 0; m < 200; ++m) {
    const Size sz = sizes[m % 5];
    const int k = 1 + (m / 5) % 4;
    // Denser masks for larger K so that windows exist and channels of all widths occur.
    const double p = 0.45 + 0.1 * k + 0.05 * static_cast<double>(m % 3);
    const Bitmap wet = (m % 2 == 0)
                           ? test::random_bitmap(sz.nx, sz.ny, p, static_cast<std::uint32_t>(m))
                           : test::smooth_random_bitmap(sz.nx, sz.ny, 0.3 * (m % 5), static_cast<std::uint32_t>(m));
    std::uniform_int_distribution<std::int64_t> ui(0, sz.nx - 1), uj(0, sz.ny - 1);
    std::vector<PixelIJ> seeds;
    for (int s = 0; s < 3; ++s) seeds.push_back({ui(rng), uj(rng)});
    const Bitmap ref = reference_k_fill(wet, k, seeds);
    const Bitmap got = k_fill(wet, k, seeds);
    ASSERT_EQ(got, ref) << "mask " << m << " K=" << k << " " << sz.nx << "x" << sz.ny << "\nwet:\n"
                        << test::render(wet) << "reference:\n"
                        << test::render(ref) << "got:\n"
                        << test::render(got);
    ++cases;
    if (ref.count() > k * k) ++nontrivial;
  }
  EXPECT_EQ(cases, 200);
  EXPECT_GT(nontrivial, 80);  // the comparison is not between empty fills
}

TEST(KFillReference, FloodFillAndComponentsMatchBfs) {
  std::mt19937 rng(5);
  for (int m = 0; m < 60; ++m) {
    const std::int64_t nx = 3 + m, ny = 2 + (m % 17);
    const Bitmap b = test::random_bitmap(nx, ny, 0.55, static_cast<std::uint32_t>(1000 + m));
    // Components by the K=1 reference fill from every unvisited cell.
    Bitmap seen(nx, ny);
    std::int64_t comps = 0, largest = 0;
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        if (!b.get(i, j) || seen.get(i, j)) continue;
        const Bitmap c = reference_k_fill(b, 1, {{i, j}});
        ++comps;
        largest = std::max(largest, c.count());
        for (std::int64_t jj = 0; jj < ny; ++jj)
          for (std::int64_t ii = 0; ii < nx; ++ii)
            if (c.get(ii, jj)) seen.set(ii, jj);
      }
    const ComponentStats cs = count_components(b);
    ASSERT_EQ(cs.count, comps) << m;
    ASSERT_EQ(cs.largest, largest) << m;
    std::uniform_int_distribution<std::int64_t> ui(0, nx - 1), uj(0, ny - 1);
    const std::vector<PixelIJ> starts = {{ui(rng), uj(rng)}, {ui(rng), uj(rng)}};
    ASSERT_EQ(flood_fill(b, starts), reference_k_fill(b, 1, starts)) << m;
  }
}

}  // namespace
}  // namespace aq::mask::unit_mask_k_fill_reference_test

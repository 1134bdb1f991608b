// SPDX-License-Identifier: GPL-3.0-or-later
// Bit-identical results with 1 and 2 OpenMP threads (ARCHITECTURE §9) on a 2000 × 1000 lattice.
#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <random>
#include <vector>

#include "mask/k_cursor_fill.hpp"
#include "mask/pinches.hpp"
#include "mask/pixel_classes.hpp"
#include "unit/mask/mask_drawing.hpp"

namespace aq::mask::unit_mask_determinism_test {
namespace {

struct Outputs {
  Bitmap wet_vertices, wet, coastal, area_wet, rotated_wet, windows, filled, dilated, after_removal;
  ComponentStats components;
  std::vector<Pinch> pinches;
  PinchRemovalStats removal;
};

Outputs run_all(int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  Outputs o;
  // Classes from a random 0.5° raster on a 2000 × 1000 lattice of 0.18° pixels.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-200.0f, 100.0f);
  std::vector<float> v(720 * 361);
  for (float& x : v) x = u(rng);
  const auto b = raster::Bathymetry::from_grid(std::move(v), 720, 361, -180.0, -90.0, 0.5, 0.5);
  const Lattice l = Lattice::make(0.18, 0, -180.0);
  ClassifyOptions co;
  co.min_depth_m = 10.0;
  PixelClasses pc = classify_pixels(b, l, PoleRotation(), co);
  o.wet_vertices = pc.wet_vertices;
  o.wet = pc.wet;
  o.coastal = pc.coastal;
  co.sampling = Sampling::kArea;
  o.area_wet = classify_pixels(b, l, PoleRotation(), co).wet;
  co.sampling = Sampling::kVertex;
  o.rotated_wet = classify_pixels(b, l, PoleRotation(-44.858333, 78.141667), co).wet;
  // Fill machinery on a smooth random mask of the same size.
  const Bitmap wet = test::smooth_random_bitmap(2000, 1000, 0.3, 99);
  o.windows = all_wet_windows(wet, 2);
  o.dilated = dilate_windows(o.windows, 2);
  std::vector<PixelIJ> seeds;
  for (std::int64_t j = 0; j < 1000 && seeds.size() < 3; j += 97)
    for (std::int64_t i = 0; i < 2000 && seeds.size() < 3; i += 31)
      if (o.windows.get(i, j)) seeds.push_back({i, j});
  o.filled = k_fill(wet, 2, seeds);
  o.components = count_components(wet, &o.filled);
  o.pinches = find_pinches(o.filled);
  o.after_removal = o.filled;
  o.removal = remove_pinches(o.after_removal, 2, seeds);
  return o;
}

TEST(MaskDeterminism, OneAndTwoThreadsGiveIdenticalBitmaps) {
  const Outputs a = run_all(1);
  const Outputs b = run_all(2);
#ifdef _OPENMP
  omp_set_num_threads(omp_get_num_procs());
#endif
  EXPECT_EQ(a.wet_vertices, b.wet_vertices);
  EXPECT_EQ(a.wet, b.wet);
  EXPECT_EQ(a.coastal, b.coastal);
  EXPECT_EQ(a.area_wet, b.area_wet);
  EXPECT_EQ(a.rotated_wet, b.rotated_wet);
  EXPECT_EQ(a.windows, b.windows);
  EXPECT_EQ(a.dilated, b.dilated);
  EXPECT_EQ(a.filled, b.filled);
  EXPECT_EQ(a.after_removal, b.after_removal);
  EXPECT_EQ(a.components.count, b.components.count);
  EXPECT_EQ(a.components.largest, b.components.largest);
  ASSERT_EQ(a.pinches.size(), b.pinches.size());
  for (std::size_t k = 0; k < a.pinches.size(); ++k) {
    EXPECT_EQ(a.pinches[k].vertex, b.pinches[k].vertex);
    EXPECT_EQ(a.pinches[k].pattern, b.pinches[k].pattern);
  }
  EXPECT_EQ(a.removal.pixels_removed, b.removal.pixels_removed);
  // The inputs are not degenerate.
  EXPECT_GT(a.wet.count(), 100000);
  EXPECT_GT(a.coastal.count(), 100000);
  EXPECT_GT(a.filled.count(), 100000);
  EXPECT_GE(a.components.count, 5);
}

}  // namespace
}  // namespace aq::mask::unit_mask_determinism_test

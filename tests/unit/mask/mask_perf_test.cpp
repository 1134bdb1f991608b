// SPDX-License-Identifier: GPL-3.0-or-later
// Timing of the mask stage on a 1' global lattice (Δ0 = 16', L = 4: 21600×10800 = 2.3e8 pixels)
// from a 1' raster (ARCHITECTURE §8: the whole 1' run < 10 s). Prints, does not assert times.
// The raster is ETOPO5 upsampled bilinearly to 1' plus a deterministic 1'-scale relief of ±40 m,
// so coastlines, lakes and channels have 1' detail; without ETOPO5 a synthetic ocean is used.
// Run alone with --gtest_filter='*Perf*' (excluded from quick runs with --gtest_filter=-'*Perf*').
#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/timer.hpp"
#include "core/types.hpp"
#include "mask/wet_area.hpp"

namespace aq::mask::unit_mask_mask_perf_test {
namespace {

raster::Bathymetry one_minute_raster() {
  const std::int64_t nc = 21600, nr = 10801;
  const double d = 1.0 / 60.0;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  const std::string etopo = std::string(AQ_ETOPO_DIR) + "/etopo5.cdf";
  const bool real = std::filesystem::exists(etopo);
  raster::Bathymetry base = [&] {
    if (real) {
      raster::OpenOptions o;
      o.path = etopo;
      return raster::Bathymetry::open(o);
    }
    std::vector<float> s(360 * 181);
    for (std::int64_t r = 0; r < 181; ++r)
      for (std::int64_t c = 0; c < 360; ++c)
        s[static_cast<std::size_t>(r * 360 + c)] =
            static_cast<float>(3000.0 * std::sin(3.0 * static_cast<double>(c) * kDegToRad) *
                                   std::cos(2.0 * static_cast<double>(r) * kDegToRad) -
                               1500.0);
    return raster::Bathymetry::from_grid(std::move(s), 360, 181, -180.0, -90.0, 1.0, 1.0);
  }();
  std::vector<double> lons(static_cast<std::size_t>(nc));
  for (std::int64_t c = 0; c < nc; ++c) lons[static_cast<std::size_t>(c)] = -180.0 + static_cast<double>(c) * d;
  const raster::Bathymetry::Columns cols = base.prepare_columns(lons.data(), nc);
#pragma omp parallel for default(none) shared(base, cols, v, nc, nr, d) schedule(static)
  for (std::int64_t r = 0; r < nr; ++r) {
    float* row = v.data() + r * nc;
    base.sample_row(cols, -90.0 + static_cast<double>(r) * d, row);
    for (std::int64_t c = 0; c < nc; ++c) {
      const double rel = 40.0 * std::sin(0.7 * static_cast<double>(c)) * std::sin(0.9 * static_cast<double>(r)) +
                         20.0 * std::sin(0.23 * static_cast<double>(c + 3 * r));
      row[c] = static_cast<float>(row[c] + rel);
    }
  }
  std::printf("raster: %s upsampled to 1' (%lld x %lld)\n", real ? "ETOPO5" : "synthetic", static_cast<long long>(nc),
              static_cast<long long>(nr));
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, d, d);
}

TEST(MaskPerf, OneMinuteGlobalLattice) {
  Timer t_raster;
  const raster::Bathymetry bathy = one_minute_raster();
  std::printf("make raster: %.2f s\n", t_raster.wall_s());
  const Lattice lat = Lattice::make(16.0 / 60.0, 4, -180.0);
  ASSERT_EQ(lat.nx, 21600);
  ASSERT_EQ(lat.ny, 10800);
#ifdef _OPENMP
  const int max_threads = omp_get_max_threads();
  const std::vector<int> thread_counts = {1, 2};
#else
  const std::vector<int> thread_counts = {1};
#endif
  std::int64_t filled_first = -1;
  for (const int threads : thread_counts) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    ClassifyOptions co;
    Timer tc;
    PixelClasses pc = classify_pixels(bathy, lat, PoleRotation(), co);
    const double t_classify = tc.wall_s(), c_classify = tc.cpu_s();
    Timer tw;
    const Bitmap w = all_wet_windows(pc.wet, 2);
    const double t_windows = tw.wall_s();
    Timer tf;
    const KFillResult kf = k_cursor_fill(pc.wet, lat, PoleRotation(), 2, {{-30.0, -50.0}}, 5.0, Logger::null());
    const double t_fill = tf.wall_s(), c_fill = tf.cpu_s();
    Timer tp;
    const std::vector<Pinch> pinches = find_pinches(kf.filled);
    const double t_pinch = tp.wall_s();
    Timer tg;
    const std::vector<PassageResult> pr = judge_passages(critical_passages(), kf.filled, lat, PoleRotation());
    const double t_pass = tg.wall_s();
    std::printf(
        "threads %d: classify %.3f s (cpu %.3f), erosion alone %.3f s, k_cursor_fill K=2 (erosion + seeds + span fill "
        "+ dilation + wet components) %.3f s (cpu %.3f), pinches %.3f s, passages %.3f s\n",
        threads, t_classify, c_classify, t_windows, t_fill, c_fill, t_pinch, t_pass);
    std::printf(
        "  wet %lld, coastal %lld, filled %lld (%.3f of the globe), wet components %lld, pinches %zu, peak RSS %.0f "
        "MB\n",
        static_cast<long long>(pc.wet_count), static_cast<long long>(pc.coastal_count),
        static_cast<long long>(kf.stats.filled_pixels),
        static_cast<double>(kf.stats.filled_pixels) / static_cast<double>(lat.pixel_count()),
        static_cast<long long>(kf.stats.wet_components), pinches.size(),
        static_cast<double>(peak_rss_bytes()) / 1048576.0);
    EXPECT_GT(kf.stats.filled_pixels, lat.pixel_count() / 2);
    if (filled_first < 0) filled_first = kf.stats.filled_pixels;
    EXPECT_EQ(kf.stats.filled_pixels, filled_first);
    EXPECT_EQ(pr.size(), critical_passages().size());
    EXPECT_GT(w.count(), 0);
  }
#ifdef _OPENMP
  omp_set_num_threads(max_threads);
#endif
  // Pinch removal on the full lattice, once (2 threads).
  config::MaskOptions o;
  o.remove_pinches = true;
  Timer ta;
  const WetArea a = compute_wet_area(bathy, lat, PoleRotation(), o, Logger::null(), nullptr);
  std::printf("compute_wet_area with remove_pinches: %.3f s (%lld pinches found, %lld pixels removed in %d rounds)\n",
              ta.wall_s(), static_cast<long long>(a.pinches.removal.pinches_found),
              static_cast<long long>(a.pinches.removal.pixels_removed), a.pinches.removal.rounds);
  EXPECT_EQ(a.pinches.total, 0);
}

}  // namespace
}  // namespace aq::mask::unit_mask_mask_perf_test

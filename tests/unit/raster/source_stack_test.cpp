// SPDX-License-Identifier: GPL-3.0-or-later
// Several bathymetry sources (raster/source_stack.hpp): a fine patch over a coarse global raster
// gives the patch's values inside, the coarse ones outside and in the patch's no-data holes, the
// blend with its exact weights near the patch's edge; the order matters; every sampling path
// (point, points, row, rows) agrees; 1 and 2 threads give the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/error.hpp"
#include "raster/bathymetry.hpp"
#include "support/synthetic_raster.hpp"

namespace unit_raster_source_stack_test {

using aq::raster::Bathymetry;

namespace {

constexpr double kR = 6371.0088;  // km, the stack's distance sphere
constexpr double kRad = 3.14159265358979323846 / 180.0;

// Coarse: global 1° grid, elevation -1000 + lon (m).
Bathymetry coarse() {
  const std::int64_t nc = 360, nr = 181;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c)
      v[static_cast<std::size_t>(r * nc + c)] = static_cast<float>(-1000.0 - 180.0 + static_cast<double>(c));
  return Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, 1.0, 1.0);
}

// Fine: 0..10°E, 0..10°N at 0.1°, elevation -50 - lat (m); optionally a no-data hole 4..6 × 4..6.
Bathymetry fine(bool hole) {
  const std::int64_t n = 101;
  std::vector<float> v(static_cast<std::size_t>(n * n));
  for (std::int64_t r = 0; r < n; ++r)
    for (std::int64_t c = 0; c < n; ++c) {
      const bool in_hole = hole && c >= 40 && c <= 60 && r >= 40 && r <= 60;
      v[static_cast<std::size_t>(r * n + c)] =
          in_hole ? std::nanf("") : static_cast<float>(-50.0 - 0.1 * static_cast<double>(r));
    }
  return Bathymetry::from_grid(std::move(v), n, n, 0.0, 0.0, 0.1, 0.1);
}

std::vector<Bathymetry> two(Bathymetry a, Bathymetry b) {
  std::vector<Bathymetry> v;
  v.push_back(std::move(a));
  v.push_back(std::move(b));
  return v;
}

}  // namespace

TEST(SourceStack, FineInsideCoarseOutside) {
  const Bathymetry s = Bathymetry::stack(two(fine(false), coarse()), 0.0);
  ASSERT_EQ(s.source_count(), 2u);
  EXPECT_DOUBLE_EQ(s.sample(5.0, 5.0), -50.0 - 5.0);
  EXPECT_NEAR(s.sample(2.25, 7.75), -50.0 - 7.75, 1e-4);
  EXPECT_DOUBLE_EQ(s.sample(20.0, 20.0), -1000.0 + 20.0);
  EXPECT_DOUBLE_EQ(s.sample(-5.0, 5.0), -1000.0 - 5.0);
  // The patch's last sample row (10°N) and half a cell beyond are the patch's; beyond, coarse.
  EXPECT_DOUBLE_EQ(s.sample(5.0, 10.0), -60.0);
  EXPECT_DOUBLE_EQ(s.sample(5.0, 10.2), -1000.0 + 5.0);
}

TEST(SourceStack, PriorityOrderMatters) {
  const Bathymetry a = Bathymetry::stack(two(fine(false), coarse()), 0.0);
  const Bathymetry b = Bathymetry::stack(two(coarse(), fine(false)), 0.0);
  EXPECT_DOUBLE_EQ(a.sample(5.0, 5.0), -55.0);
  EXPECT_DOUBLE_EQ(b.sample(5.0, 5.0), -995.0);  // the coarse raster covers everything
  EXPECT_NE(a.sample(3.0, 3.0), b.sample(3.0, 3.0));
}

TEST(SourceStack, NoDataHolesFallThrough) {
  const Bathymetry s = Bathymetry::stack(two(fine(true), coarse()), 0.0);
  EXPECT_DOUBLE_EQ(s.sample(5.0, 5.0), -995.0);    // inside the hole
  EXPECT_DOUBLE_EQ(s.sample(3.0, 5.0), -55.0);     // beside it
  EXPECT_DOUBLE_EQ(s.sample(3.95, 5.0), -996.05);  // the cell touching the hole: its sample is NaN
  std::vector<double> lon{5.0, 3.0, 20.0, 200.0}, lat{5.0, 5.0, 20.0, 95.0};
  std::vector<int> code(lon.size());
  s.supplying_sources(lon.data(), lat.data(), 4, code.data());
  EXPECT_EQ(code[0], 1);
  EXPECT_EQ(code[1], 0);
  EXPECT_EQ(code[2], 1);
}

TEST(SourceStack, BlendHasTheDocumentedWeights) {
  const double blend = 50.0;
  const Bathymetry s = Bathymetry::stack(two(fine(false), coarse()), blend);
  const auto weight = [blend](double d) {
    const double x = std::min(1.0, d / blend);
    return x * x * (3.0 - 2.0 * x);
  };
  // 2 rows (0.2°) above the patch's southern edge, far from the others: d = 0.2° of meridian.
  const double d1 = 2.0 * 0.1 * kRad * kR;
  const double w1 = weight(d1);
  EXPECT_GT(w1, 0.1);
  EXPECT_LT(w1, 0.9);
  EXPECT_NEAR(s.sample(5.0, 0.2), w1 * (-50.2) + (1.0 - w1) * (-995.0), 1e-3);
  // 3 columns from the western edge at 0.4°N: d = 3 × 0.1° of that parallel (nearer than 4 rows).
  const double d2 = 3.0 * 0.1 * kRad * kR * std::cos(0.4 * kRad);
  const double w2 = weight(d2);
  EXPECT_NEAR(s.sample(0.3, 0.4), w2 * (-50.4) + (1.0 - w2) * (-999.7), 1e-3);
  // On the edge: the coarse raster alone; deep inside: the patch alone.
  EXPECT_NEAR(s.sample(5.0, 0.0), -995.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.sample(5.0, 5.0), -55.0);
  EXPECT_DOUBLE_EQ(Bathymetry::blend_weight(0.0, blend), 0.0);
  EXPECT_DOUBLE_EQ(Bathymetry::blend_weight(25.0, blend), 0.5);
  EXPECT_DOUBLE_EQ(Bathymetry::blend_weight(80.0, blend), 1.0);
  EXPECT_DOUBLE_EQ(Bathymetry::blend_weight(3.0, 0.0), 1.0);
  std::vector<double> lon{5.0, 5.0, 20.0}, lat{0.2, 5.0, 20.0};
  std::vector<int> code(3);
  s.supplying_sources(lon.data(), lat.data(), 3, code.data());
  EXPECT_EQ(code[0], Bathymetry::kBlended + 0);
  EXPECT_EQ(code[1], 0);
  EXPECT_EQ(code[2], 1);
}

TEST(SourceStack, HolesAreEdgesOfTheBlend) {
  const double blend = 30.0;
  const Bathymetry s = Bathymetry::stack(two(fine(true), coarse()), blend);
  // 0.2° east of the hole's eastern edge points (6.1°E: a no-data neighbour at 6.0°E).
  const double d = 2.0 * 0.1 * kRad * kR * std::cos(5.0 * kRad);
  const double x = std::min(1.0, d / blend), w = x * x * (3.0 - 2.0 * x);
  EXPECT_GT(w, 0.1);
  EXPECT_LT(w, 0.9);
  EXPECT_NEAR(s.sample(6.3, 5.0), w * (-55.0) + (1.0 - w) * (-993.7), 1e-3);
}

TEST(SourceStack, AllSamplingPathsAgreeAndThreadsDoNotMatter) {
  const Bathymetry s = Bathymetry::stack(two(fine(true), coarse()), 40.0);
  const std::int64_t nx = 300, ny = 120;
  std::vector<double> lons(static_cast<std::size_t>(nx)), lats(static_cast<std::size_t>(ny));
  for (std::int64_t i = 0; i < nx; ++i)
    lons[static_cast<std::size_t>(i)] = -3.0 + 0.05 * static_cast<double>(i) + 0.013;
  for (std::int64_t j = 0; j < ny; ++j) lats[static_cast<std::size_t>(j)] = -1.0 + 0.1 * static_cast<double>(j) + 0.007;
  const auto cols = s.prepare_columns(lons.data(), nx);
  std::vector<float> rows1(static_cast<std::size_t>(nx * ny)), rows2(rows1.size()), row(static_cast<std::size_t>(nx));
  const auto run = [&](std::vector<float>& out) {
    s.sample_rows(cols, lats.data(), ny,
                  [&out, nx](std::int64_t k, const float* v) { std::copy(v, v + nx, out.begin() + k * nx); });
  };
  aq::test::set_threads(1);
  run(rows1);
  aq::test::set_threads(2);
  run(rows2);
  EXPECT_EQ(0, std::memcmp(rows1.data(), rows2.data(), rows1.size() * sizeof(float)));
  std::vector<double> plon, plat, pts;
  for (std::int64_t j = 0; j < ny; ++j)
    for (std::int64_t i = 0; i < nx; ++i) {
      plon.push_back(lons[static_cast<std::size_t>(i)]);
      plat.push_back(lats[static_cast<std::size_t>(j)]);
    }
  pts.resize(plon.size());
  s.sample_points(plon.data(), plat.data(), static_cast<std::int64_t>(plon.size()), pts.data());
  std::int64_t blended = 0;
  const Bathymetry f_alone = fine(true), c_alone = coarse();
  for (std::int64_t j = 0; j < ny; ++j) {
    s.sample_row(cols, lats[static_cast<std::size_t>(j)], row.data());
    for (std::int64_t i = 0; i < nx; ++i) {
      const auto k = static_cast<std::size_t>(j * nx + i);
      const double one = s.sample(plon[k], plat[k]);
      ASSERT_EQ(pts[k], one) << plon[k] << " " << plat[k];
      ASSERT_NEAR(rows1[k], one, 1e-3) << plon[k] << " " << plat[k];
      ASSERT_EQ(row[static_cast<std::size_t>(i)], rows1[k]);
      const double f = f_alone.sample(plon[k], plat[k]), c = c_alone.sample(plon[k], plat[k]);
      if (!std::isnan(f) && one != f && one != c) ++blended;
    }
  }
  EXPECT_GT(blended, 100);  // the blend zone is crossed
}

TEST(SourceStack, OneSourceIsThatSource) {
  const Bathymetry s = Bathymetry::stack(
      [] {
        std::vector<Bathymetry> v;
        v.push_back(fine(false));
        return v;
      }(),
      10.0);
  EXPECT_EQ(s.source_count(), 1u);
  EXPECT_TRUE(s.samples_bilinear());
  EXPECT_DOUBLE_EQ(s.sample(5.0, 5.0), -55.0);
  const Bathymetry st = Bathymetry::stack(two(fine(false), coarse()), 0.0);
  EXPECT_FALSE(st.samples_bilinear());
  EXPECT_THROW((void)st.value(0, 0), aq::InternalError);
}

}  // namespace unit_raster_source_stack_test

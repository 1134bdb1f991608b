// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel classes (seed 002 §2) on in-memory rasters with analytic values.
#include "mask/pixel_classes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mask/lattice_coords.hpp"
#include "unit/mask/mask_drawing.hpp"

namespace aq::mask::unit_mask_pixel_classes_test {
namespace {

// Global grid-registered raster of step `d` degrees: columns λ = -180 + c·d (c < 360/d), rows
// φ = -90 + r·d (r <= 180/d), values f(λ, φ).
template <typename F>
raster::Bathymetry global_raster(double d, F f) {
  const auto nc = static_cast<std::int64_t>(std::lround(360.0 / d));
  const auto nr = static_cast<std::int64_t>(std::lround(180.0 / d)) + 1;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c)
      v[static_cast<std::size_t>(r * nc + c)] =
          static_cast<float>(f(-180.0 + static_cast<double>(c) * d, -90.0 + static_cast<double>(r) * d));
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, d, d);
}

PixelClasses classify(const raster::Bathymetry& b, const Lattice& l, double h, Sampling s = Sampling::kVertex,
                      const PoleRotation& rot = PoleRotation()) {
  ClassifyOptions o;
  o.min_depth_m = h;
  o.sampling = s;
  return classify_pixels(b, l, rot, o);
}

TEST(PixelClasses, LinearInLatitudeGivesExactRows) {
  // d = 100·φ - 500 m: bilinear sampling is exact, vertices at φ = -90 + 10J.
  const auto b = global_raster(1.0, [](double, double lat) { return 100.0 * lat - 500.0; });
  const Lattice l = Lattice::make(10.0, 0, -180.0);
  ASSERT_EQ(l.nx, 36);
  ASSERT_EQ(l.ny, 18);
  // h = 0: wet where φ <= 5, i.e. vertex rows J <= 9; pixel rows 0..8 wet, row 9 coastal.
  PixelClasses pc = classify(b, l, 0.0);
  EXPECT_EQ(pc.wet_vertex_count, 36 * 10);
  EXPECT_EQ(pc.wet_count, 36 * 9);
  EXPECT_EQ(pc.coastal_count, 36);
  EXPECT_EQ(pc.dry_count, 36 * 8);
  for (std::int64_t i = 0; i < l.nx; ++i) {
    EXPECT_TRUE(pc.wet.get(i, 8));
    EXPECT_TRUE(pc.coastal.get(i, 9));
    EXPECT_FALSE(pc.wet.get(i, 9));
    EXPECT_FALSE(pc.coastal.get(i, 10));
  }
  // h = 500: the vertex row at φ = 0 has d = -500 exactly and d <= -h holds: still wet.
  pc = classify(b, l, 500.0);
  EXPECT_EQ(pc.wet_vertex_count, 36 * 10);
  // h = 600: φ <= -1, vertex rows J <= 8.
  pc = classify(b, l, 600.0);
  EXPECT_EQ(pc.wet_vertex_count, 36 * 9);
  EXPECT_EQ(pc.wet_count, 36 * 8);
}

TEST(PixelClasses, ExactlyZeroMetresIsWetAtHZeroOnly) {
  // +100 m land with a block of exactly 0 m at λ in [-40, 40], φ in [-20, 20] (grid points).
  const auto b = global_raster(
      1.0, [](double lon, double lat) { return (std::abs(lon) <= 40.0 && std::abs(lat) <= 20.0) ? 0.0 : 100.0; });
  const Lattice l = Lattice::make(10.0, 0, -180.0);
  const PixelClasses at0 = classify(b, l, 0.0);
  EXPECT_EQ(at0.wet_vertex_count, 9 * 5);  // λ = -40..40 step 10, φ = -20..20 step 10
  EXPECT_EQ(at0.wet_count, 8 * 4);
  const PixelClasses above = classify(b, l, 0.001);
  EXPECT_EQ(above.wet_vertex_count, 0);
  EXPECT_EQ(above.wet_count, 0);
  // -0.5 m at h = 0.5 is wet (d <= -h), at h = 0.5001 it is not.
  const auto b2 = global_raster(
      1.0, [](double lon, double lat) { return (std::abs(lon) <= 40.0 && std::abs(lat) <= 20.0) ? -0.5 : 100.0; });
  EXPECT_EQ(classify(b2, l, 0.5).wet_vertex_count, 45);
  EXPECT_EQ(classify(b2, l, 0.5001).wet_vertex_count, 0);
}

TEST(PixelClasses, NoDataIsDry) {
  const auto b = global_raster(
      1.0, [](double lon, double) { return lon < 0.0 ? std::numeric_limits<double>::quiet_NaN() : -1000.0; });
  const Lattice l = Lattice::make(10.0, 0, -180.0);
  const PixelClasses pc = classify(b, l, 0.0);
  // Vertices with λ >= 0 are wet: I = 18..35 (18 columns) on 19 rows; λ = -180 (I = 0) is NaN.
  EXPECT_EQ(pc.wet_vertex_count, 18 * 19);
  EXPECT_EQ(pc.wet_count, 17 * 18);     // pixel 35 spans λ 170..180 = vertex I=0 (NaN): coastal
  EXPECT_EQ(pc.coastal_count, 2 * 18);  // pixels 17 (λ -10..0) and 35
}

TEST(PixelClasses, VertexRuleWrapsAcrossTheSeam) {
  // Vertex bitmap 6 × 3 (2 pixel rows): only vertex columns 0 and 5 are wet.
  const Bitmap wv = test::draw({"#....#", "#....#", "#....#"});
  Bitmap wet, coastal;
  classify_from_vertices(wv, wet, coastal);
  EXPECT_EQ(test::render(wet), ".....#\n.....#\n");      // pixel 5 has vertices 5 and 0
  EXPECT_EQ(test::render(coastal), "#...#.\n#...#.\n");  // pixels 0 and 4 touch one wet column
}

TEST(PixelClasses, AreaRuleSeesAShoalInsideAPixel) {
  // Deep everywhere except one raster point at +10 m inside pixel (18, 9) (λ 0..10, φ 0..10) and
  // one on the edge λ = -40 between pixels 13 and 14 of row 6 (φ -30..-20).
  const auto b = global_raster(0.5, [](double lon, double lat) {
    if (lon == 3.5 && lat == 6.0) return 10.0;
    if (lon == -40.0 && lat == -25.0) return 10.0;
    return -1000.0;
  });
  const Lattice l = Lattice::make(10.0, 0, -180.0);
  const PixelClasses vertex = classify(b, l, 0.0, Sampling::kVertex);
  EXPECT_EQ(vertex.wet_count, 36 * 18);  // the shoals are not at vertices
  const PixelClasses area = classify(b, l, 0.0, Sampling::kArea);
  EXPECT_EQ(area.wet_count, 36 * 18 - 3);
  EXPECT_EQ(area.coastal_count, 3);
  EXPECT_TRUE(area.coastal.get(18, 9));
  EXPECT_TRUE(area.coastal.get(13, 6));
  EXPECT_TRUE(area.coastal.get(14, 6));
  EXPECT_EQ(area.wet_vertices, vertex.wet_vertices);  // vertices always use the vertex rule
  // The opposite: dry land with one wet point inside a pixel -> coastal, not dry.
  const auto land = global_raster(0.5, [](double lon, double lat) { return (lon == 3.5 && lat == 6.0) ? -5.0 : 50.0; });
  const PixelClasses la = classify(land, l, 0.0, Sampling::kArea);
  EXPECT_EQ(la.wet_count, 0);
  EXPECT_EQ(la.coastal_count, 1);
  EXPECT_TRUE(la.coastal.get(18, 9));
  EXPECT_EQ(classify(land, l, 0.0, Sampling::kVertex).coastal_count, 0);
}

TEST(PixelClasses, AreaRuleMatchesABruteForceOfItsDefinition) {
  // A coarse random raster (10°) on 2.5° pixels shifted by 1.25° in λ: raster points fall inside
  // some pixels (and on row edges), other pixels hold none and fall back to the vertex rule.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  std::vector<double> vals(37 * 19);
  for (double& x : vals) x = std::round(u(rng));
  const auto b = global_raster(10.0, [&](double lon, double lat) {
    const auto c = static_cast<std::size_t>(std::lround((lon + 180.0) / 10.0));
    const auto r = static_cast<std::size_t>(std::lround((lat + 90.0) / 10.0));
    return vals[r * 37 + c];
  });
  const Lattice l = Lattice::make(2.5, 0, -178.75);
  const double h = 10.0;
  const PixelClasses vertex = classify(b, l, h, Sampling::kVertex);
  const PixelClasses area = classify(b, l, h, Sampling::kArea);
  std::int64_t with_points = 0;
  for (std::int64_t j = 0; j < l.ny; ++j) {
    for (std::int64_t i = 0; i < l.nx; ++i) {
      const double lon0 = l.lon_of(i), lat0 = l.lat_of(j), d = l.pixel_deg();
      bool any = false, all = true, has = false;
      for (std::int64_t r = 0; r <= 18; ++r) {
        const double lat = -90.0 + 10.0 * static_cast<double>(r);
        if (lat < lat0 || lat > lat0 + d) continue;
        for (std::int64_t c = 0; c < 36; ++c) {
          const double lon = wrap_lon_deg(-180.0 + 10.0 * static_cast<double>(c), lon0);
          if (lon > lon0 + d) continue;
          has = true;
          const bool w = vals[static_cast<std::size_t>(r * 37 + c)] <= -h;
          any = any || w;
          all = all && w;
        }
      }
      if (has) {
        ++with_points;
        ASSERT_EQ(area.wet.get(i, j), all) << i << "," << j;
        ASSERT_EQ(area.coastal.get(i, j), any && !all) << i << "," << j;
      } else {
        ASSERT_EQ(area.wet.get(i, j), vertex.wet.get(i, j)) << i << "," << j;
        ASSERT_EQ(area.coastal.get(i, j), vertex.coastal.get(i, j)) << i << "," << j;
      }
    }
  }
  EXPECT_EQ(with_points, 36 * 19 * 2 - 36 * 2);  // each raster row lies on an edge of two pixel rows (poles: one)
}

// Large-scale basins plus ripples of 3-4° wavelength (finer than a 5° pixel, resolved by 1°).
double wavy(double lon, double lat) {
  return 1000.0 * std::sin(2.0 * lon * kDegToRad) * std::cos(lat * kDegToRad) -
         300.0 * std::sin(3.0 * lat * kDegToRad) +
         250.0 * std::sin(120.0 * lon * kDegToRad) * std::cos(100.0 * lat * kDegToRad);
}

TEST(PixelClasses, RotatedLatticeSamplesGeographicPoints) {
  const auto b = global_raster(1.0, wavy);
  const Lattice l = Lattice::make(5.0, 0, -180.0);
  const PoleRotation rot(-44.858333, 78.141667);
  const PixelClasses pc = classify(b, l, 100.0, Sampling::kVertex, rot);
  std::int64_t mismatches = 0;
  for (std::int64_t J = 0; J <= l.ny; ++J)
    for (std::int64_t I = 0; I < l.nx; ++I) {
      const LonLat g = lattice_to_geographic(rot, vertex_lattice_deg(l, I, J));
      mismatches += (b.sample(g.lon_deg, g.lat_deg) <= -100.0) != pc.wet_vertices.get(I, J) ? 1 : 0;
    }
  EXPECT_EQ(mismatches, 0);
  const PixelClasses plain = classify(b, l, 100.0);
  EXPECT_FALSE(pc.wet_vertices == plain.wet_vertices);  // the rotation does change the lattice
  // Area rule through the rotation: 6×6 samples per 5° pixel of a 1° raster, which include the
  // vertices, so area-wet ⊆ vertex-wet, and a spot check of one pixel's samples.
  const PixelClasses area = classify(b, l, 100.0, Sampling::kArea, rot);
  for (std::size_t w = 0; w < area.wet.words().size(); ++w) ASSERT_EQ(area.wet.words()[w] & ~pc.wet.words()[w], 0U);
  EXPECT_LT(area.wet_count, pc.wet_count);
  for (const PixelIJ p : {PixelIJ{10, 7}, PixelIJ{40, 20}, PixelIJ{70, 35}}) {
    bool all = true, any = false;
    for (int bb = 0; bb <= 5; ++bb)
      for (int a = 0; a <= 5; ++a) {
        const LonLat q =
            lattice_xy_to_deg(l, static_cast<double>(p.i * 5 + a) / 5.0, static_cast<double>(p.j * 5 + bb) / 5.0);
        const LonLat g = lattice_to_geographic(rot, q);
        const bool wet = b.sample(g.lon_deg, g.lat_deg) <= -100.0;
        all = all && wet;
        any = any || wet;
      }
    EXPECT_EQ(area.wet.get(p.i, p.j), all);
    EXPECT_EQ(area.coastal.get(p.i, p.j), any && !all);
  }
}

// The rotated vertex rule decides whole units of open ocean and inland from the raster's value
// bounds without sampling them. It must give the bits of sampling every vertex (the reference
// here: every lattice row mapped to geographic points and sampled), on both lattices, with
// no-data holes, a coast of fine detail, a raster value exactly at the threshold and a lattice
// finer than the raster; and with a bicubic raster (no bounds) as well.
TEST(PixelClasses, RotatedUnitsGiveTheBitsOfSamplingEveryVertex) {
  const auto coast = [](double lon, double lat) {
    if (lat > 20.0 && lat < 23.0 && lon > 40.0 && lon < 47.0) return std::nan("");  // a no-data hole
    if (lat > -30.0 && lat < -29.0 && lon > 100.0 && lon < 101.0) return 0.0;       // exactly at h = 0
    return wavy(lon, lat) + 400.0 * std::sin(7.0 * lon * kDegToRad) * std::sin(11.0 * lat * kDegToRad);
  };
  const auto b = global_raster(0.5, coast);
  const auto cubic = [&] {
    const auto smooth = global_raster(0.5, [](double lon, double lat) { return wavy(lon, lat); });
    std::vector<float> v(static_cast<std::size_t>(smooth.info().ncols * smooth.info().nrows));
    smooth.values(0, smooth.info().ncols, 0, smooth.info().nrows, v.data());
    return raster::Bathymetry::from_grid(std::move(v), smooth.info().ncols, smooth.info().nrows, -180.0, -90.0, 0.5,
                                         0.5, raster::Interpolation::kBicubic);
  }();
  const PoleRotation rot(-44.858333, 78.141667);
  const std::vector<Lattice> lattices = {Lattice::make(1.0, 2, -180.0),  // 0.25° vertices on a 0.5° raster
                                         Lattice::make_mercator(2.0, 3, -180.0, 86.5)};
  for (const Lattice& l : lattices) {
    std::vector<double> xs(static_cast<std::size_t>(l.nx));
    for (std::int64_t I = 0; I < l.nx; ++I) xs[static_cast<std::size_t>(I)] = static_cast<double>(I);
    const LatticeRowMapper mapper(l, rot, xs);
    for (const raster::Bathymetry* r : {&b, &cubic}) {
      for (const double h : {0.0, 150.0}) {
        const Bitmap wv = sample_wet_vertices(*r, l, rot, h, {});
        std::vector<double> lon(xs.size()), lat(xs.size()), val(xs.size());
        std::int64_t mismatches = 0, wet = 0;
        for (std::int64_t J = 0; J <= l.ny; ++J) {
          mapper.map_row(static_cast<double>(J), lon.data(), lat.data());
          r->sample_points(lon.data(), lat.data(), l.nx, val.data());
          for (std::int64_t I = 0; I < l.nx; ++I) {
            const bool expect = val[static_cast<std::size_t>(I)] <= -h;
            wet += expect ? 1 : 0;
            mismatches += expect != wv.get(I, J) ? 1 : 0;
          }
        }
        EXPECT_EQ(mismatches, 0) << "nx = " << l.nx << ", h = " << h << (r == &cubic ? ", bicubic" : "");
        EXPECT_GT(wet, l.nx);  // both classes are present
        EXPECT_LT(wet, l.nx * (l.ny + 1) - l.nx);
        for (std::int64_t J = 0; J <= l.ny; ++J) {  // padding bits stay clear
          if (l.nx % 64 != 0) {
            EXPECT_EQ(wv.row(J)[wv.words_per_row() - 1] >> (l.nx % 64), 0U);
          }
        }
      }
    }
  }
}

TEST(PixelClasses, ProgressReachesOne) {
  const auto b = global_raster(1.0, wavy);
  const Lattice l = Lattice::make(1.0, 0, -180.0);
  ClassifyOptions o;
  double last = -1.0;
  int calls = 0;
  o.progress = [&](double f, std::string_view) {
    EXPECT_GE(f, last);
    last = f;
    ++calls;
  };
  (void)classify_pixels(b, l, PoleRotation(), o);
  EXPECT_DOUBLE_EQ(last, 1.0);
  EXPECT_GT(calls, 10);
}

}  // namespace
}  // namespace aq::mask::unit_mask_pixel_classes_test

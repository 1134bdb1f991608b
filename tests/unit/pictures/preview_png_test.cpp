// SPDX-License-Identifier: GPL-3.0-or-later
// Preview PNG: read the pictures back with Cairo and look at pixels (background, level fill,
// seam-crossing squares at both ends, coast, zoom box), sizes, determinism and errors.
#include "pictures/preview_png.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>

#include "core/error.hpp"
#include "support/io_test_mesh.hpp"
#include "support/msh_parse.hpp"
#include "support/png_pixels.hpp"
#include "support/synthetic_raster.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_pictures_preview_png_test {
namespace {

// 5° global raster: ocean 4000 m deep, one land block at λ ∈ [20, 60], φ ∈ [0, 40].
raster::Bathymetry test_bathy() {
  std::vector<float> v(72 * 37, -4000.0f);
  for (int r = 0; r < 37; ++r)
    for (int c = 0; c < 72; ++c) {
      const double lon = -180.0 + 5.0 * c, lat = -90.0 + 5.0 * r;
      if (lon >= 20 && lon <= 60 && lat >= 0 && lat <= 40) v[static_cast<std::size_t>(r * 72 + c)] = 500.0f;
    }
  return raster::Bathymetry::from_grid(std::move(v), 72, 37, -180.0, -90.0, 5.0, 5.0);
}

using Picture = aq::testing::PngPixels;

Picture load(const std::filesystem::path& p) { return aq::testing::load_png_pixels(p); }

// Pixel of map position (lon, lat) in a full-map picture of width w (band = w / 60).
std::pair<int, int> at(double lon, double lat, int w) {
  const int band = std::clamp(w / 60, 18, 64);
  return {static_cast<int>((lon + 180.0) / 360.0 * w), band + static_cast<int>((90.0 - lat) / 180.0 * (w / 2))};
}

TEST(PreviewPng, SizeBackgroundFillsAndCoast) {
  testing::TempDir dir;
  PreviewOptions o;
  o.width_px = 1440;
  const WriteStats st = write_preview_png(testing::tiny_mesh(), test_bathy(), dir / "m.png", o);
  EXPECT_EQ(st.elements, 17);
  const Picture p = load(dir / "m.png");
  EXPECT_EQ(p.width, 1440);
  EXPECT_EQ(p.height, 720 + 2 * 24);
  // Open sea far from the mesh: blue (b > r); land block: grey-green (g > b).
  auto [sx, sy] = at(-100.0, -70.0, 1440);
  auto sea = p.rgb(sx, sy);
  EXPECT_GT(sea[2], sea[0] + 40);
  auto [lx, ly] = at(40.0, 20.0, 1440);
  auto land = p.rgb(lx, ly);
  EXPECT_GT(land[1], land[2]);
  // Inside square D (λ -180..-157.5, φ -45..-22.5) and inside the seam-crossing square C drawn at
  // the east edge (λ 157.5..180): tinted by the level fill, so no longer the plain sea colour.
  for (const double lon : {-165.0, 170.0}) {
    auto [x, y] = at(lon, -40.0, 1440);
    const auto c = p.rgb(x, y);
    EXPECT_NE(c, sea) << "lon " << lon;
    EXPECT_LT(c[2], sea[2]) << "lon " << lon;
  }
  // The coast: the south edge of square A (φ = -45 at λ = -120) is black.
  auto [cx, cy] = at(-120.0, -45.0, 1440);
  int darkest = 765;
  for (int dy = -1; dy <= 1; ++dy) {
    const auto c = p.rgb(cx, cy + dy);
    darkest = std::min(darkest, c[0] + c[1] + c[2]);
  }
  EXPECT_LT(darkest, 120);
  // Title band is white around its right end.
  EXPECT_EQ(p.rgb(1439, 2), (std::array<int, 3>{255, 255, 255}));
}

// output.png_color = "angle" / "size": each triangle filled opaquely in the colour of its value's
// class, read back at its centroid; NaN leaves it unfilled; the legend shows the classes.
TEST(PreviewPng, TrianglesColouredByAngleAndSizeClasses) {
  testing::TempDir dir;
  const mesh::Mesh m = testing::tiny_mesh();
  const std::array<std::array<int, 3>, 6> angle_rgb{
      {{165, 0, 38}, {215, 48, 39}, {244, 109, 67}, {254, 224, 139}, {166, 217, 106}, {26, 152, 80}}};
  PreviewOptions o;
  o.width_px = 1440;
  o.colour = PreviewColour::kAngle;
  for (std::size_t k = 0; k < m.triangles.size(); ++k)
    o.triangle_values.push_back(5.0f + 10.0f * static_cast<float>(k % 6));
  o.triangle_values[0] = std::nanf("");
  write_preview_png(m, test_bathy(), dir / "angle.png", o);
  const Picture p = load(dir / "angle.png");
  // Centroid of triangle k on the map (seam-crossing and pole triangles skipped).
  auto centroid = [&](std::size_t k, double& lon, double& lat) {
    lon = lat = 0.0;
    for (const NodeId n : m.triangles[k]) {
      if (m.node_i[n] == 0 && m.crosses_seam(m.triangles[k])) return false;
      if (m.lat_deg[n] == 90.0) return false;
      lon += m.lon_deg[n] / 3.0;
      lat += m.lat_deg[n] / 3.0;
    }
    return true;
  };
  int checked = 0;
  for (std::size_t k = 1; k < m.triangles.size(); ++k) {
    double lon = 0, lat = 0;
    if (!centroid(k, lon, lat)) continue;
    const auto [x, y] = at(lon, lat, 1440);
    EXPECT_EQ(p.rgb(x, y), angle_rgb[k % 6]) << "triangle " << k;
    ++checked;
  }
  EXPECT_GE(checked, 8);
  double lon0 = 0, lat0 = 0;
  ASSERT_TRUE(centroid(0, lon0, lat0));
  const auto [x0, y0] = at(lon0, lat0, 1440);
  for (const auto& c : angle_rgb) EXPECT_NE(p.rgb(x0, y0), c);  // NaN: not filled
  // The legend band shows the first class's swatch.
  bool swatch = false;
  for (int y = p.height - 24; y < p.height && !swatch; ++y)
    for (int x = 0; x < p.width && !swatch; ++x) swatch = p.rgb(x, y) == angle_rgb[0];
  EXPECT_TRUE(swatch);

  // Size: 3 km (fine, yellow) and 300 km (coarse, dark violet) fall into different classes.
  o.colour = PreviewColour::kSize;
  for (std::size_t k = 0; k < m.triangles.size(); ++k) o.triangle_values[k] = k % 2 == 0 ? 3.0f : 300.0f;
  write_preview_png(m, test_bathy(), dir / "size.png", o);
  const Picture q = load(dir / "size.png");
  for (std::size_t k = 0; k < m.triangles.size(); ++k) {
    double lon = 0, lat = 0;
    if (!centroid(k, lon, lat)) continue;
    const auto [x, y] = at(lon, lat, 1440);
    const auto c = q.rgb(x, y);
    if (k % 2 == 0) {
      EXPECT_EQ(c, (std::array<int, 3>{253, 231, 37})) << k;
    } else {
      EXPECT_EQ(c, (std::array<int, 3>{68, 1, 84})) << k;
    }
  }
}

TEST(PreviewPng, ZoomAcrossTheSeamAndBoxOnTheMap) {
  testing::TempDir dir;
  PreviewOptions o;
  o.width_px = 600;
  o.zoom = {150.0, 210.0, -60.0, -10.0};  // crosses λ = 180: C on the left, D (shifted +360) on the right
  const auto m = testing::tiny_mesh();
  const auto bathy = test_bathy();
  write_preview_png(m, bathy, dir / "m.png", o);
  write_preview_zoom_png(m, bathy, dir / "z.png", o);
  const Picture z = load(dir / "z.png");
  EXPECT_EQ(z.width, 600);
  EXPECT_EQ(z.height, 500 + 2 * 18);
  auto zx = [&](double lon) { return static_cast<int>((lon - 150.0) / 60.0 * 600); };
  auto zy = [&](double lat) { return 18 + static_cast<int>((-10.0 - lat) / 50.0 * 500); };
  const auto sea = z.rgb(zx(152.0), zy(-55.0));
  EXPECT_GT(sea[2], sea[0] + 40);
  EXPECT_NE(z.rgb(zx(165.0), zy(-40.0)), sea);  // C
  EXPECT_NE(z.rgb(zx(195.0), zy(-40.0)), sea);  // D, drawn at λ + 360
  // The zoom box is outlined in red on the map.
  const Picture p = load(dir / "m.png");
  auto [bx, by] = at(150.0, -35.0, 600);
  bool red = false;
  for (int dx = -2; dx <= 2; ++dx) {
    const auto c = p.rgb(bx + dx, by);
    red = red || (c[0] > 180 && c[1] < 80 && c[2] < 80);
  }
  EXPECT_TRUE(red);
}

TEST(PreviewPng, SquaresRotatedAndDeterministic) {
  testing::TempDir dir;
  PreviewOptions o;
  o.width_px = 400;
  o.elements = ElementKinds::kSquares;
  const auto bathy = test_bathy();
  const WriteStats st = write_preview_png(testing::tiny_mesh(false), bathy, dir / "q.png", o);
  EXPECT_EQ(st.elements, 7);
  o.elements = ElementKinds::kTriangles;
  const auto r = testing::tiny_mesh(true, {true, -44.858333, 78.141667});
  write_preview_png(r, bathy, dir / "1.png", o);
  write_preview_png(r, bathy, dir / "2.png", o);
  EXPECT_EQ(testing::read_file_bytes((dir / "1.png").string()), testing::read_file_bytes((dir / "2.png").string()));
}

// 0.25° global raster whose elevation crosses a tint class boundary every few pixels of an
// 800-pixel map (ridges ±6500 m with periods of 2.1° and 3.3°, and a no-data patch).
raster::Bathymetry ridged_bathy() {
  const std::int64_t nc = 1440, nr = 721;
  std::vector<float> v(static_cast<std::size_t>(nc * nr));
  for (std::int64_t r = 0; r < nr; ++r)
    for (std::int64_t c = 0; c < nc; ++c) {
      const double lon = -180.0 + 0.25 * static_cast<double>(c), lat = -90.0 + 0.25 * static_cast<double>(r);
      constexpr double k2pi = 6.283185307179586;
      const double e = 6500.0 * std::sin(k2pi * lon / 2.1) * std::cos(k2pi * lat / 3.3) - 1500.0 +
                       700.0 * std::sin(0.05 * lon * lat);
      const bool hole = lon > 100.0 && lon < 104.0 && lat > 10.0 && lat < 13.0;
      v[static_cast<std::size_t>(r * nc + c)] = hole ? std::nanf("") : static_cast<float>(e);
    }
  return raster::Bathymetry::from_grid(std::move(v), nc, nr, -180.0, -90.0, 0.25, 0.25);
}

// The rotated background from interpolated raster positions (RotatedMapSampler) against the one
// with atan2, asin and Bathymetry::sample at every pixel: where an elevation crosses a tint class
// boundary within the position error, the pixel takes the neighbouring class; that is rare even
// on this raster (1.2% of the pixels; 0.07% on ETOPO5), and the picture is the same on 1 and 2
// threads.
TEST(PreviewPng, RotatedBackgroundIsCloseToTheExactOneAndTheSameOnAnyThreadCount) {
  testing::TempDir dir;
  const auto bathy = ridged_bathy();
  for (const auto& pole : std::vector<std::array<double, 2>>{{-44.858333, 78.141667}, {30.0, 10.0}}) {
    const auto m = testing::tiny_mesh(true, {true, pole[0], pole[1]});
    PreviewOptions o;
    o.width_px = 800;  // 0.45° pixels on the 0.25° raster, as 0.15° on ETOPO5's 5'
    aq::test::set_threads(2);
    write_preview_png(m, bathy, dir / "fast2.png", o);
    aq::test::set_threads(1);
    write_preview_png(m, bathy, dir / "fast1.png", o);
    o.exact_background = true;
    write_preview_png(m, bathy, dir / "exact.png", o);
    aq::test::set_threads(2);
    EXPECT_TRUE(testing::read_file_bytes((dir / "fast2.png").string()) ==
                testing::read_file_bytes((dir / "fast1.png").string()))
        << pole[0];
    const Picture fast = load(dir / "fast2.png"), exact = load(dir / "exact.png");
    ASSERT_EQ(fast.width, exact.width);
    ASSERT_EQ(fast.height, exact.height);
    std::int64_t differ = 0;
    std::set<std::array<int, 3>> colours;
    for (int y = 0; y < fast.height; ++y)
      for (int x = 0; x < fast.width; ++x) {
        differ += fast.rgb(x, y) != exact.rgb(x, y) ? 1 : 0;
        if (x % 7 == 0 && y % 7 == 0) colours.insert(exact.rgb(x, y));
      }
    const auto pixels = static_cast<std::int64_t>(fast.width) * fast.height;
    EXPECT_GT(differ, 0) << pole[0];  // interpolated, not the exact path
    EXPECT_LT(differ, pixels / 50) << pole[0];
    // The picture has the structure the test needs: many tint classes, no-data included.
    EXPECT_GE(colours.size(), 30u) << pole[0];
  }
}

// output.png_width and output.png_zoom are validated at load (tests/unit/config); the writers
// refuse values outside those ranges as a bug.
TEST(PreviewPng, BadOptionsBreakThePreconditions) {
  PreviewOptions o;
  o.width_px = 10;
  EXPECT_THROW(check_preview_options(o), InternalError);
  o.width_px = 800;
  EXPECT_NO_THROW(check_preview_options(o));
  for (const auto& z : std::vector<std::vector<double>>{{1, 2, 3}, {10, 5, 0, 1}, {0, 10, 20, 10}, {0, 10, -95, 0}}) {
    o.zoom = z;
    EXPECT_THROW(check_preview_options(o), InternalError) << z.size();
  }
}

TEST(PreviewPng, UnwritablePathThrowsOutputErrorNamingIt) {
  testing::TempDir dir;
  std::ofstream(dir / "plain_file") << "x";
  const auto bad = dir / "plain_file" / "m.png";
  PreviewOptions o;
  o.width_px = 300;
  try {
    write_preview_png(testing::tiny_mesh(), test_bathy(), bad, o);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aq::io::unit_pictures_preview_png_test

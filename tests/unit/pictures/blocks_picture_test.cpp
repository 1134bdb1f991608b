// SPDX-License-Identifier: GPL-3.0-or-later
// The blocks overview: block outlines drawn on the global mesh preview (io::PreviewOptions::
// outlines) in magenta, also across the seam, with their labels; nothing magenta without them.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cstring>

#include "pictures/preview_png.hpp"
#include "support/io_test_mesh.hpp"
#include "support/png_pixels.hpp"
#include "support/temp_dir.hpp"

namespace unit_pictures_blocks_picture_test {

namespace {

struct Picture : aq::testing::PngPixels {
  [[nodiscard]] bool magenta(int x, int y) const {
    const auto [r, g, b] = rgb(x, y);
    return r > 140 && g < 80 && b > 150;  // the line's colour, alone or anti-aliased over the sea
  }
  [[nodiscard]] int magenta_near(int x, int y) const {
    int n = 0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) n += magenta(x + dx, y + dy);
    return n;
  }
  [[nodiscard]] int magenta_total() const {
    int n = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) n += magenta(x, y);
    return n;
  }
};

Picture load(const std::filesystem::path& p) { return Picture{aq::testing::load_png_pixels(p)}; }

aq::raster::Bathymetry ocean() {
  std::vector<float> v(72 * 37, -4000.0f);
  return aq::raster::Bathymetry::from_grid(std::move(v), 72, 37, -180.0, -90.0, 5.0, 5.0);
}

// Map pixel of (lon, lat) in a full-map picture of width w.
std::pair<int, int> at(double lon, double lat, int w) {
  const int band = std::clamp(w / 60, 18, 64);
  return {static_cast<int>((lon + 180.0) / 360.0 * w), band + static_cast<int>((90.0 - lat) / 180.0 * (w / 2))};
}

}  // namespace

TEST(BlocksPicture, OutlinesAreDrawnAlsoAcrossTheSeam) {
  aq::testing::TempDir dir;
  aq::io::PreviewOptions o;
  o.width_px = 1440;
  const auto mesh = aq::testing::tiny_mesh();
  const auto bathy = ocean();
  aq::io::write_preview_png(mesh, bathy, dir / "none.png", o);
  EXPECT_EQ(load(dir / "none.png").magenta_total(), 0);

  // A box at 0..20°E, 10..30°N and one across the seam, 170°E..190°E (drawn at both map edges).
  o.outlines.push_back({{{0.0, 10.0}, {20.0, 10.0}, {20.0, 30.0}, {0.0, 30.0}}, "1"});
  o.outlines.push_back({{{170.0, -30.0}, {190.0, -30.0}, {190.0, -10.0}, {170.0, -10.0}}, "2"});
  aq::io::write_preview_png(mesh, bathy, dir / "blocks.png", o);
  const Picture p = load(dir / "blocks.png");
  const auto side = [&](double lon, double lat) {
    const auto [x, y] = at(lon, lat, o.width_px);
    return p.magenta_near(x, y);
  };
  EXPECT_GT(side(10.0, 30.0), 0);     // north side of 1
  EXPECT_GT(side(20.0, 20.0), 0);     // east side of 1
  EXPECT_EQ(side(10.0, 20.0), 0);     // inside 1
  EXPECT_GT(side(175.0, -30.0), 0);   // 2 west of the seam
  EXPECT_GT(side(-175.0, -10.0), 0);  // 2 east of the seam (drawn shifted by -360)
  EXPECT_GT(side(-170.0, -20.0), 0);  // its east side at 190 = -170
  EXPECT_EQ(side(-160.0, -20.0), 0);
}

}  // namespace unit_pictures_blocks_picture_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The ROMS grid picture: land in the land colour, water shaded by depth, a legend.
#include "pictures/roms_grid_png.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <vector>

#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/projection.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_pictures_roms_grid_png_test {
namespace {

// A 6 x 4 cell plane rectangle (super grid 13 x 9 points) and, at its rho points, every third
// cell land (depth 10 m), the others water of growing depth.
struct Fixture {
  curvilinear::Grid2D super{13, 9};
  std::vector<std::uint8_t> mask;
  std::vector<double> h;
  Fixture() {
    for (int j = 0; j < super.ny_pts; ++j)
      for (int i = 0; i < super.nx_pts; ++i) {
        super.x[super.at(i, j)] = -50.0 + 100.0 * i / (super.nx_pts - 1);
        super.y[super.at(i, j)] = -30.0 + 60.0 * j / (super.ny_pts - 1);
      }
    curvilinear::ProjectionParams p;
    p.rlat_deg = 43.75;
    p.rlon_deg = 34.5;
    const std::size_t n = curvilinear::build_cgrid(super, curvilinear::Projection(p)).rho.size();
    for (std::size_t k = 0; k < n; ++k) {
      h.push_back(k % 3 == 0 ? 10.0 : 100.0 + static_cast<double>(k));
      mask.push_back(k % 3 == 0 ? 0 : 1);
    }
  }
};

TEST(RomsPicture, ShowsLandAndShadedWater) {
  const Fixture f;
  testing::TempDir dir;
  RomsPictureOptions o;
  o.width_px = 400;
  o.title = "test";
  write_roms_png(dir / "p.png", f.super, f.mask, f.h, o);
  cairo_surface_t* s = cairo_image_surface_create_from_png((dir / "p.png").c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(cairo_image_surface_get_width(s), 400);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s), h = cairo_image_surface_get_height(s);
  std::set<std::uint32_t> colours;
  bool land = false;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 400; ++x) {
      const auto px = *reinterpret_cast<const std::uint32_t*>(data + y * stride + 4 * x) & 0xFFFFFFu;
      colours.insert(px);
      land = land || px == ((212u << 16) | (194u << 8) | 153u);  // kLand (0.83, 0.76, 0.60)
    }
  cairo_surface_destroy(s);
  EXPECT_TRUE(land);
  EXPECT_GT(colours.size(), 20u);  // depth shades, legend, lines
  EXPECT_THROW(write_roms_png(dir / "q.png", f.super, std::vector<std::uint8_t>(3, 0), f.h, o), InternalError);
}

}  // namespace
}  // namespace aq::io::unit_pictures_roms_grid_png_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the regional stage pictures (seed 000 Figs. 2, 3, 10, 11) on the seed's Black Sea
// input: every stage writes a readable PNG of the requested width, with the colours of what
// that stage must show (contour in black, corners/tangents red, nodes blue, grid lines), a
// coastline given as lon/lat polylines appears, and the errors.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "curvilinear/regional.hpp"
#include "grid_params/izogrid_file.hpp"
#include "pictures/regional_pictures.hpp"

namespace aq::io::unit_pictures_regional_pictures_test {
namespace {

using curvilinear::Stage;

struct Counts {
  int width = 0, height = 0;
  long black = 0, red = 0, blue = 0, brown = 0, nonwhite = 0;
};

Counts count_colours(const std::filesystem::path& png) {
  Counts c;
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << png;
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) return c;
  c.width = cairo_image_surface_get_width(s);
  c.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* d = cairo_image_surface_get_data(s);
  for (int y = 28; y < c.height; ++y)  // below the title
    for (int x = 0; x < c.width; ++x) {
      const auto* p = d + static_cast<std::ptrdiff_t>(y) * stride + 4 * x;  // B, G, R, (A)
      const int b = p[0], g = p[1], r = p[2];
      if (r < 250 || g < 250 || b < 250) ++c.nonwhite;
      if (r < 40 && g < 40 && b < 40) ++c.black;
      if (r > 180 && g < 60 && b < 60) ++c.red;
      if (b > 170 && r < 60 && g < 120) ++c.blue;
      if (r > 110 && r < 170 && g > 60 && g < 120 && b < 60) ++c.brown;
    }
  cairo_surface_destroy(s);
  return c;
}

TEST(RegionalPicturesTest, EveryStageDrawsWhatItShows) {
  curvilinear::RegionalParams p =
      curvilinear::read_izogrid_file(std::string(AQ_SOURCE_DIR) + "/configs/black_sea.izogrid");
  p.ny = 25;  // a small grid keeps the test fast; the pictures are the same kind
  const curvilinear::RegionalResult r = curvilinear::run_regional(p, Stage::kGrid);
  const auto dir = std::filesystem::temp_directory_path() / "aq_regional_pictures_test";
  std::filesystem::create_directories(dir);
  RegionalPictureOptions o;
  o.width_px = 800;
  // A crude "coastline": the Crimean peninsula's outline, roughly.
  o.coastlines = {{{32.5, 45.4}, {33.6, 44.5}, {34.5, 44.6}, {35.4, 45.0}, {36.6, 45.4}, {35.5, 45.9}, {33.7, 46.0}}};
  Counts c[5];
  for (int s = 0; s <= 4; ++s) {
    const auto path = dir / fmt::format("stage{}.png", s);
    write_regional_png(path, r, static_cast<Stage>(s), o);
    c[s] = count_colours(path);
    EXPECT_EQ(c[s].width, 800) << s;
    EXPECT_GT(c[s].height, 300) << s;
    EXPECT_GT(c[s].brown, 50) << "coastline missing in stage " << s;
  }
  EXPECT_GT(c[0].red, 15 * 10);                     // 15 control points
  EXPECT_GT(c[1].black, 1500);                      // the contour
  EXPECT_GT(c[1].red, c[0].red);                    // + corner tangents
  EXPECT_GT(c[1].blue, 250);                        // spline_type = 4: the cubic, dashed blue
  EXPECT_GT(c[2].blue, c[1].blue);                  // + nodes
  EXPECT_GT(c[4].nonwhite, 4 * c[1].nonwhite / 3);  // grid lines fill the inside
}

TEST(RegionalPicturesTest, RefusesStagesThatWereNotRun) {
  const curvilinear::RegionalParams p =
      curvilinear::read_izogrid_file(std::string(AQ_SOURCE_DIR) + "/configs/black_sea.izogrid");
  const curvilinear::RegionalResult r = curvilinear::run_regional(p, Stage::kContour);
  const auto path = std::filesystem::temp_directory_path() / "aq_regional_refused.png";
  EXPECT_THROW(write_regional_png(path, r, Stage::kGrid), InternalError);
  EXPECT_THROW(write_regional_png("/nonexistent-dir/x.png", r, Stage::kContour), OutputError);
}

}  // namespace
}  // namespace aq::io::unit_pictures_regional_pictures_test

// SPDX-License-Identifier: GPL-3.0-or-later
// The quality heat map PNG: cells coloured by their error on a log scale, same bytes every time,
// errors naming the file.
#include "pictures/grid_quality_png.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/output_files.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_pictures_grid_quality_png_test {
namespace {

namespace fs = std::filesystem;

using aq::testing::TempDir;

/// RGB of pixel (x, y) of a PNG.
std::array<int, 3> pixel(const fs::path& png, int x, int y, int* width = nullptr, int* height = nullptr) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  if (width) *width = cairo_image_surface_get_width(s);
  if (height) *height = cairo_image_surface_get_height(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  std::uint32_t v = 0;
  std::memcpy(&v, data + static_cast<std::ptrdiff_t>(y) * stride + 4 * x, 4);
  cairo_surface_destroy(s);
  return {static_cast<int>((v >> 16) & 0xff), static_cast<int>((v >> 8) & 0xff), static_cast<int>(v & 0xff)};
}

TEST(GridQualityPng, DrawsTheCellsColouredAndIsReproducible) {
  const TempDir dir;
  // A square grid whose left half has error 1e-2 and right half 1e-8: the left must be yellow
  // (top of viridis), the right dark purple (bottom).
  curvilinear::Grid2D g(41, 41);
  for (int j = 0; j < 41; ++j) {
    for (int i = 0; i < 41; ++i) {
      g.x[g.at(i, j)] = 1000.0 * i;
      g.y[g.at(i, j)] = 1000.0 * j;
    }
  }
  std::vector<double> v(40 * 40);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = (k % 40) < 20 ? 1e-2 : -1e-8;
  QualityPngOptions o;
  o.width_px = 600;
  o.title = "test";
  write_quality_png(dir / "a.png", g, v, o);
  write_quality_png(dir / "b.png", g, v, o);
  EXPECT_EQ(file_checksum(dir / "a.png"), file_checksum(dir / "b.png"));
  int w = 0;
  int h = 0;
  // Plot area: x in [16, 470], y from 56 down 454 px. Sample away from grid lines.
  const auto left = pixel(dir / "a.png", 16 + 454 / 4 + 3, 56 + 454 / 2 + 3, &w, &h);
  const auto right = pixel(dir / "a.png", 16 + 3 * 454 / 4 + 3, 56 + 454 / 2 + 3);
  EXPECT_EQ(w, 600);
  EXPECT_GE(h, 56 + 454);
  EXPECT_GT(left[0], 200);  // yellow: red and green high, blue low
  EXPECT_GT(left[1], 180);
  EXPECT_LT(left[2], 90);
  EXPECT_LT(right[0], 100);  // purple: low green
  EXPECT_LT(right[1], 60);
  EXPECT_GT(right[2], 60);
  EXPECT_THROW(write_quality_png(dir / "c.png", g, std::vector<double>(5), o), InternalError);
  try {
    write_quality_png(dir / "no_dir" / "c.png", g, v, o);
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_dir"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aq::io::unit_pictures_grid_quality_png_test

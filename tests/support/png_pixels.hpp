// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper: a PNG read back through Cairo as ARGB32 pixels, for tests that check what a
// picture shows (colours at map positions, counts of a line colour).
#pragma once

#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

namespace aq::testing {

struct PngPixels {
  int width = 0, height = 0;
  std::vector<std::uint32_t> px;  ///< row-major ARGB32 (Cairo's premultiplied native layout)

  [[nodiscard]] std::array<int, 3> rgb(int x, int y) const {
    const std::uint32_t p = px[static_cast<std::size_t>(y * width + x)];
    return {static_cast<int>((p >> 16) & 0xff), static_cast<int>((p >> 8) & 0xff), static_cast<int>(p & 0xff)};
  }
};

/// Reads `path`; a file Cairo cannot read fails the calling test.
inline PngPixels load_png_pixels(const std::filesystem::path& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << path;
  PngPixels pic;
  pic.width = cairo_image_surface_get_width(s);
  pic.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* d = cairo_image_surface_get_data(s);
  for (int y = 0; y < pic.height; ++y)
    for (int x = 0; x < pic.width; ++x) {
      std::uint32_t v = 0;
      std::memcpy(&v, d + y * stride + 4 * x, 4);
      pic.px.push_back(v);
    }
  cairo_surface_destroy(s);
  return pic;
}

}  // namespace aq::testing

// SPDX-License-Identifier: GPL-3.0-or-later
// PNG encoder: pictures decoded again by libpng (through Cairo) must have exactly the pixels that
// were encoded, including pictures whose data spans several IDAT chunks and strips.
#include "pictures/png_encode.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "support/msh_parse.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_pictures_png_encode_test {
namespace {

cairo_surface_t* make_picture(int w, int h, bool noisy) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  unsigned char* d = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  std::uint32_t state = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      state = state * 1664525u + 1013904223u;
      const std::uint32_t v = noisy ? (state >> 8) : static_cast<std::uint32_t>((x / 7) * 0x010203 + y * 0x000101);
      const std::uint32_t px = 0xff000000u | (v & 0xffffff);
      std::memcpy(d + y * stride + 4 * x, &px, 4);
    }
  cairo_surface_mark_dirty(s);
  return s;
}

void expect_round_trip(int w, int h, bool noisy) {
  testing::TempDir dir;
  cairo_surface_t* s = make_picture(w, h, noisy);
  {
    FileWriter f(dir / "p.png");
    write_png(s, f);
    f.close();
  }
  cairo_surface_t* back = cairo_image_surface_create_from_png((dir / "p.png").c_str());
  ASSERT_EQ(cairo_surface_status(back), CAIRO_STATUS_SUCCESS);
  ASSERT_EQ(cairo_image_surface_get_width(back), w);
  ASSERT_EQ(cairo_image_surface_get_height(back), h);
  const unsigned char* a = cairo_image_surface_get_data(s);
  const unsigned char* b = cairo_image_surface_get_data(back);
  const int sa = cairo_image_surface_get_stride(s), sb = cairo_image_surface_get_stride(back);
  int bad = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t pa = 0, pb = 0;
      std::memcpy(&pa, a + y * sa + 4 * x, 4);
      std::memcpy(&pb, b + y * sb + 4 * x, 4);
      bad += (pa & 0xffffff) != (pb & 0xffffff) ? 1 : 0;
    }
  EXPECT_EQ(bad, 0);
  cairo_surface_destroy(back);

  // Same bytes again.
  {
    FileWriter f(dir / "q.png");
    write_png(s, f);
    f.close();
  }
  EXPECT_EQ(testing::read_file_bytes((dir / "p.png").string()), testing::read_file_bytes((dir / "q.png").string()));
  cairo_surface_destroy(s);
}

TEST(PngEncode, SmoothPictureRoundTrips) { expect_round_trip(301, 157, false); }
TEST(PngEncode, NoisyPictureOverSeveralIdatChunksRoundTrips) { expect_round_trip(800, 600, true); }
TEST(PngEncode, TinyPicturesWithFewerRowsThanStrips) { expect_round_trip(3, 2, true); }

}  // namespace
}  // namespace aq::io::unit_pictures_png_encode_test

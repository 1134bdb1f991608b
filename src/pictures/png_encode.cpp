// SPDX-License-Identifier: GPL-3.0-or-later
// PNG encoder (see png_encode.hpp).
#include "pictures/png_encode.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <exception>
#include <utility>
#include <vector>

#include "core/error.hpp"

#if defined(AQ_HAVE_ZLIB)
#include <zlib.h>
#endif

namespace aq::io {

namespace {

#if defined(AQ_HAVE_ZLIB)

constexpr int kStrips = 16;  // fixed: the output must not depend on the thread count
constexpr int kLevel = 1;    // deflate level: speed over the last 10% of size
constexpr std::size_t kIdatBytes = std::size_t{1} << 20;

void put_u32(std::vector<unsigned char>& out, std::uint32_t v) {
  out.push_back(static_cast<unsigned char>(v >> 24));
  out.push_back(static_cast<unsigned char>(v >> 16));
  out.push_back(static_cast<unsigned char>(v >> 8));
  out.push_back(static_cast<unsigned char>(v));
}

void write_png_chunk(FileWriter& f, const char type[4], const unsigned char* data, std::size_t n) {
  std::vector<unsigned char> head;
  put_u32(head, static_cast<std::uint32_t>(n));
  head.insert(head.end(), type, type + 4);
  f.bytes(head.data(), head.size());
  if (n > 0) f.bytes(data, n);
  uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(type), 4);
  if (n > 0) crc = crc32_z(crc, data, n);
  std::vector<unsigned char> tail;
  put_u32(tail, static_cast<std::uint32_t>(crc));
  f.bytes(tail.data(), tail.size());
  f.maybe_flush();
}

// Filtered scanlines of rows [y0, y1): filter byte 1 ("Sub"), then RGB minus the pixel to the left.
void filter_rows(const unsigned char* data, int width, int stride, int y0, int y1, std::vector<unsigned char>& out) {
  const std::size_t line = 1 + 3 * static_cast<std::size_t>(width);
  out.resize(line * static_cast<std::size_t>(y1 - y0));
  for (int y = y0; y < y1; ++y) {
    unsigned char* o = out.data() + line * static_cast<std::size_t>(y - y0);
    o[0] = 1;
    const auto* cur = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    std::uint32_t left = 0;
    for (int x = 0; x < width; ++x) {
      const std::uint32_t c = cur[x];
      unsigned char* p = o + 1 + 3 * static_cast<std::size_t>(x);
      p[0] = static_cast<unsigned char>(((c >> 16) & 0xff) - ((left >> 16) & 0xff));
      p[1] = static_cast<unsigned char>(((c >> 8) & 0xff) - ((left >> 8) & 0xff));
      p[2] = static_cast<unsigned char>((c & 0xff) - (left & 0xff));
      left = c;
    }
  }
}

struct Strip {
  std::vector<unsigned char> deflated;
  uLong adler = 0;
  uLong raw_bytes = 0;
  int error = Z_OK;
};

void deflate_strip(const unsigned char* data, int width, int stride, int y0, int y1, bool last, Strip& s) {
  std::vector<unsigned char> raw;
  filter_rows(data, width, stride, y0, y1, raw);
  s.raw_bytes = static_cast<uLong>(raw.size());
  s.adler = adler32_z(adler32(0L, Z_NULL, 0), raw.data(), raw.size());
  z_stream z{};
  s.error = deflateInit2(&z, kLevel, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY);  // raw deflate
  if (s.error != Z_OK) return;
  s.deflated.resize(deflateBound(&z, static_cast<uLong>(raw.size())) + 16);
  z.next_in = raw.data();
  z.avail_in = static_cast<uInt>(raw.size());
  z.next_out = s.deflated.data();
  z.avail_out = static_cast<uInt>(s.deflated.size());
  const int r = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  if (r != (last ? Z_STREAM_END : Z_OK) || z.avail_in != 0) s.error = r == Z_OK ? Z_BUF_ERROR : r;
  s.deflated.resize(z.total_out);
  deflateEnd(&z);
}

void write_with_zlib(cairo_surface_t* surface, FileWriter& f) {
  cairo_surface_flush(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int width = cairo_image_surface_get_width(surface), height = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  if (data == nullptr || width <= 0 || height <= 0) {
    throw OutputError(fmt::format("{}: no picture to encode", f.path().string()));
  }
  const int strips = std::min(kStrips, height);
  std::vector<Strip> out(static_cast<std::size_t>(strips));
  Strip* o = out.data();
#pragma omp parallel for schedule(static) default(none) shared(o, data, width, height, stride, strips)
  for (int k = 0; k < strips; ++k) {
    const int y0 = static_cast<int>(static_cast<std::int64_t>(height) * k / strips);
    const int y1 = static_cast<int>(static_cast<std::int64_t>(height) * (k + 1) / strips);
    deflate_strip(data, width, stride, y0, y1, k == strips - 1, o[k]);
  }

  std::vector<unsigned char> z = {0x78, 0x5e};  // zlib header: deflate, 32K window, "fast" level
  uLong adler = adler32(0L, Z_NULL, 0);
  for (const Strip& s : out) {
    if (s.error != Z_OK) {
      throw OutputError(fmt::format("{}: PNG deflate failed (zlib error {})", f.path().string(), s.error));
    }
    z.insert(z.end(), s.deflated.begin(), s.deflated.end());
    adler = adler32_combine(adler, s.adler, static_cast<z_off_t>(s.raw_bytes));
  }
  put_u32(z, static_cast<std::uint32_t>(adler));

  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  f.bytes(kSignature, sizeof(kSignature));
  std::vector<unsigned char> ihdr;
  put_u32(ihdr, static_cast<std::uint32_t>(width));
  put_u32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filters, no interlace
  write_png_chunk(f, "IHDR", ihdr.data(), ihdr.size());
  for (std::size_t at = 0; at < z.size(); at += kIdatBytes) {
    write_png_chunk(f, "IDAT", z.data() + at, std::min(kIdatBytes, z.size() - at));
  }
  write_png_chunk(f, "IEND", nullptr, 0);
}

#else

cairo_status_t write_chunk(void* closure, const unsigned char* data, unsigned int length) {
  auto* w = static_cast<std::pair<FileWriter*, std::exception_ptr>*>(closure);
  try {
    w->first->bytes(data, length);
    w->first->maybe_flush();
  } catch (...) {
    w->second = std::current_exception();
    return CAIRO_STATUS_WRITE_ERROR;
  }
  return CAIRO_STATUS_SUCCESS;
}

void write_with_cairo(cairo_surface_t* surface, FileWriter& file) {
  std::pair<FileWriter*, std::exception_ptr> sink{&file, nullptr};
  const cairo_status_t st = cairo_surface_write_to_png_stream(surface, write_chunk, &sink);
  if (sink.second) std::rethrow_exception(sink.second);
  if (st != CAIRO_STATUS_SUCCESS) {
    throw OutputError(fmt::format("{}: PNG encoding failed: {}", file.path().string(), cairo_status_to_string(st)));
  }
}

#endif

}  // namespace

void write_png(cairo_surface_t* surface, FileWriter& file) {
#if defined(AQ_HAVE_ZLIB)
  write_with_zlib(surface, file);
#else
  write_with_cairo(surface, file);
#endif
}

}  // namespace aq::io

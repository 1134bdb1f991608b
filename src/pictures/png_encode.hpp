// SPDX-License-Identifier: GPL-3.0-or-later
// PNG encoding of an RGB picture held in Cairo's RGB24 layout (one 32-bit 0x00RRGGBB word per
// pixel, `stride` bytes per row), written through a FileWriter (PNG 1.2 / ISO 15948).
//
// With zlib (AQ_HAVE_ZLIB, the pictures target linked to ZLIB::ZLIB) the encoder is ours and fast:
// 8-bit RGB, filter "Sub" on every row, the rows cut into a fixed number of strips that are
// deflated independently at level 1 (in parallel; each strip but the last ends on a byte-aligned
// sync flush, the way pigz does it), one zlib stream with the combined Adler-32, IDAT chunks of
// at most 1 MiB. The strip count does not depend on the thread count, so the bytes are the same
// for any number of threads. Without zlib it falls back to cairo_surface_write_to_png_stream
// (libpng's default compression, several times slower).
#pragma once

#include <cairo.h>

#include "io/file_writer.hpp"

namespace aq::io {

/// Writes `surface` (CAIRO_FORMAT_RGB24 or ARGB32, alpha ignored) as an RGB PNG. Throws
/// OutputError naming the file on any failure.
void write_png(cairo_surface_t* surface, FileWriter& file);

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Owning handles of cairo surfaces and contexts, shared by the picture writers.
#pragma once

#include <cairo.h>

#include <memory>

namespace aq::io {

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Cairo heat map of a per-cell quality field of a curvilinear grid (see grid_quality_png.hpp).
//
//   +------------------------------------------------------+
//   |  title                                               |
//   |  +------------------------------------+   +--+ 1e-2  |
//   |  |  cells coloured by log10|v|,       |   |  |       |
//   |  |  grid lines every k-th line        |   |  | 1e-6  |
//   |  +------------------------------------+   +--+ 1e-10 |
//   +------------------------------------------------------+
#include "pictures/grid_quality_png.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "pictures/cairo_handles.hpp"

namespace aq::io {

namespace {

constexpr int kTop = 56;
constexpr int kBottom = 16;
constexpr int kLeft = 16;
constexpr int kRight = 130;  // colour bar and its labels
constexpr int kMinHeight = 320;

struct Rgb {
  double r, g, b;
};

/// Viridis, 9 stops (matplotlib's values at 0, 1/8, ..., 1), interpolated linearly.
Rgb viridis(double t) {
  static constexpr std::array<Rgb, 9> kStops = {{{0.267, 0.005, 0.329},
                                                 {0.279, 0.175, 0.483},
                                                 {0.230, 0.322, 0.546},
                                                 {0.173, 0.449, 0.558},
                                                 {0.128, 0.567, 0.551},
                                                 {0.154, 0.680, 0.504},
                                                 {0.364, 0.786, 0.386},
                                                 {0.678, 0.864, 0.190},
                                                 {0.993, 0.906, 0.144}}};
  t = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(t), kStops.size() - 2);
  const double f = t - static_cast<double>(k);
  const Rgb& a = kStops[k];
  const Rgb& b = kStops[k + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

/// Maps plane coordinates to pixels (y up in the plane, down in the image).
struct QualityView {
  double x0, y1, scale;
  [[nodiscard]] double px(double x) const { return kLeft + (x - x0) * scale; }
  [[nodiscard]] double py(double y) const { return kTop + (y1 - y) * scale; }
};

}  // namespace

void write_quality_png(const std::filesystem::path& path, const curvilinear::Grid2D& g,
                       const std::vector<double>& cell_values, const QualityPngOptions& options) {
  const int cx = g.nx_pts - 1;
  const int cy = g.ny_pts - 1;
  const std::size_t n_nodes =
      static_cast<std::size_t>(std::max(g.nx_pts, 0)) * static_cast<std::size_t>(std::max(g.ny_pts, 0));
  if (cx < 1 || cy < 1 || g.x.size() != n_nodes || g.y.size() != n_nodes ||
      cell_values.size() != static_cast<std::size_t>(cx) * static_cast<std::size_t>(cy)) {
    throw InternalError(fmt::format("write_quality_png {}: grid {}x{} ({} nodes) with {} cell values", path.string(),
                                    g.nx_pts, g.ny_pts, g.x.size(), cell_values.size()));
  }
  const int width = std::clamp(options.width_px, 200, 20000);

  // Geometry: the grid's bounding box fitted into the plot area.
  const auto [xmin, xmax] = std::minmax_element(g.x.begin(), g.x.end());
  const auto [ymin, ymax] = std::minmax_element(g.y.begin(), g.y.end());
  const double bw = std::max(*xmax - *xmin, 1e-300);
  const double bh = std::max(*ymax - *ymin, 1e-300);
  const double plot_w = width - kLeft - kRight;
  double scale = plot_w / bw;
  if (bh * scale > 1.5 * width) scale = 1.5 * width / bh;
  const int height = std::max(kMinHeight, static_cast<int>(std::ceil(kTop + bh * scale + kBottom)));
  const QualityView view{*xmin, *ymax, scale};

  // Colour range in decades.
  double vmax = 0.0;
  double vmin = HUGE_VAL;
  for (const double v : cell_values) {
    if (std::isnan(v)) continue;
    const double a = std::fabs(v);
    vmax = std::max(vmax, a);
    if (a > 0.0) vmin = std::min(vmin, a);
  }
  const int decades = std::max(options.decades, 1);
  const double top = vmax > 0.0 && std::isfinite(vmax) ? std::ceil(std::log10(vmax)) : 0.0;
  double bottom = std::isfinite(vmin) ? std::floor(std::log10(vmin)) : top - 1.0;
  bottom = std::max(bottom, top - decades);
  if (bottom >= top) bottom = top - 1.0;
  auto colour_of = [&](double v) -> Rgb {
    if (std::isnan(v)) return {0.75, 0.75, 0.75};
    const double a = std::fabs(v);
    const double l = a > 0.0 ? std::log10(a) : bottom;
    return viridis((l - bottom) / (top - bottom));
  };

  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
    throw OutputError(fmt::format("{}: cannot create a {}x{} image: {}", path.string(), width, height,
                                  cairo_status_to_string(cairo_surface_status(surface.get()))));
  }
  std::unique_ptr<cairo_t, ContextDeleter> context(cairo_create(surface.get()));
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);

  // Cells, in blocks of k x k when they are much smaller than a pixel; a block shows its worst.
  const int k = std::max(1, static_cast<int>(std::max(cx, cy) / std::max(1.0, plot_w / 1.5)));
  auto node = [&](int i, int j) {
    const std::size_t p = g.at(std::min(i, g.nx_pts - 1), std::min(j, g.ny_pts - 1));
    return std::pair{view.px(g.x[p]), view.py(g.y[p])};
  };
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  for (int j = 0; j < cy; j += k) {
    for (int i = 0; i < cx; i += k) {
      double worst = std::nan("");
      for (int jj = j; jj < std::min(j + k, cy); ++jj) {
        for (int ii = i; ii < std::min(i + k, cx); ++ii) {
          const double v = cell_values[static_cast<std::size_t>(jj) * static_cast<std::size_t>(cx) + ii];
          if (!std::isnan(v) && !(std::fabs(v) <= std::fabs(worst))) worst = v;
        }
      }
      const Rgb c = colour_of(worst);
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      const auto p1 = node(i, j);
      const auto p2 = node(i + k, j);
      const auto p3 = node(i + k, j + k);
      const auto p4 = node(i, j + k);
      cairo_move_to(cr, p1.first, p1.second);
      cairo_line_to(cr, p2.first, p2.second);
      cairo_line_to(cr, p3.first, p3.second);
      cairo_line_to(cr, p4.first, p4.second);
      cairo_close_path(cr);
      cairo_fill_preserve(cr);
      cairo_set_line_width(cr, 1.0);  // covers the hairline gaps between blocks
      cairo_stroke(cr);
    }
  }

  // Grid lines: every m-th line and the boundary.
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
  cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 0.45);
  cairo_set_line_width(cr, 0.6);
  const int max_lines = std::max(options.max_lines, 2);
  const int mi = std::max(1, (cx + max_lines - 1) / max_lines);
  const int mj = std::max(1, (cy + max_lines - 1) / max_lines);
  for (int j = 0; j <= cy; ++j) {
    if (j % mj != 0 && j != cy) continue;
    for (int i = 0; i <= cx; ++i) {
      const auto p = node(i, j);
      if (i == 0)
        cairo_move_to(cr, p.first, p.second);
      else
        cairo_line_to(cr, p.first, p.second);
    }
    cairo_stroke(cr);
  }
  for (int i = 0; i <= cx; ++i) {
    if (i % mi != 0 && i != cx) continue;
    for (int j = 0; j <= cy; ++j) {
      const auto p = node(i, j);
      if (j == 0)
        cairo_move_to(cr, p.first, p.second);
      else
        cairo_line_to(cr, p.first, p.second);
    }
    cairo_stroke(cr);
  }

  // Title.
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 16.0);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_move_to(cr, kLeft, 24.0);
  cairo_show_text(cr, options.title.c_str());
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12.0);
  cairo_move_to(cr, kLeft, 44.0);
  const std::string subtitle =
      fmt::format("colour: {}; grid lines: every {} (xi) x {} (eta)", options.value_label, mi, mj);
  cairo_show_text(cr, subtitle.c_str());

  // Colour bar with a tick per decade (at most ~12 labels).
  const double bar_x = width - kRight + 24.0;
  const double bar_top = kTop + 6.0;
  const double bar_h = std::min(360.0, height - bar_top - kBottom - 10.0);
  const int steps = static_cast<int>(bar_h);
  for (int s = 0; s < steps; ++s) {
    const Rgb c = viridis(1.0 - (s + 0.5) / steps);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, bar_x, bar_top + s, 18.0, 1.0);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, bar_x, bar_top, 18.0, bar_h);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 11.0);
  const int n_dec = static_cast<int>(top - bottom);
  const int label_step = std::max(1, (n_dec + 11) / 12);
  for (int d = 0; d <= n_dec; d += label_step) {
    const double y = bar_top + bar_h * d / n_dec;
    cairo_move_to(cr, bar_x + 18.0, y);
    cairo_line_to(cr, bar_x + 22.0, y);
    cairo_stroke(cr);
    cairo_move_to(cr, bar_x + 25.0, y + 4.0);
    cairo_show_text(cr, fmt::format("1e{}", static_cast<int>(top) - d).c_str());
  }

  cairo_surface_flush(surface.get());
  const cairo_status_t status = cairo_surface_write_to_png(surface.get(), path.c_str());
  if (status != CAIRO_STATUS_SUCCESS) {
    throw OutputError(fmt::format("{}: cannot write PNG: {}", path.string(), cairo_status_to_string(status)));
  }
}

}  // namespace aq::io

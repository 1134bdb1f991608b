// SPDX-License-Identifier: GPL-3.0-or-later
// Cairo picture of a ROMS grid's mask and depth; see roms_grid_png.hpp.
#include "pictures/roms_grid_png.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/error.hpp"

namespace aq::io {

namespace {

struct SurfaceFree {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextFree {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

constexpr double kTitleBand = 30.0;  // title band, px
constexpr double kLegend = 70.0;     // legend band at the bottom, px
constexpr double kMargin = 12.0;

struct RgbColour {
  double r, g, b;
};
constexpr RgbColour kLand{0.83, 0.76, 0.60};
constexpr RgbColour kShallow{0.74, 0.88, 0.97};
constexpr RgbColour kDeep{0.03, 0.12, 0.42};

// Water colour at depth h on a log scale between h0 and h1.
RgbColour water(double h, double h0, double h1) {
  double t = 0.0;
  if (h1 > h0 && h > h0) t = std::clamp(std::log(h / h0) / std::log(h1 / h0), 0.0, 1.0);
  return {kShallow.r + t * (kDeep.r - kShallow.r), kShallow.g + t * (kDeep.g - kShallow.g),
          kShallow.b + t * (kDeep.b - kShallow.b)};
}

}  // namespace

void write_roms_png(const std::filesystem::path& path, const curvilinear::Grid2D& g,
                    const std::vector<std::uint8_t>& mask, const std::vector<double>& h, const RomsPictureOptions& o) {
  const int L = (g.nx_pts - 1) / 2, M = (g.ny_pts - 1) / 2;
  const std::size_t nr = static_cast<std::size_t>(L + 1) * static_cast<std::size_t>(M + 1);
  if (g.nx_pts < 3 || g.ny_pts < 3 || g.nx_pts % 2 == 0 || g.ny_pts % 2 == 0 || mask.size() != nr || h.size() != nr)
    throw InternalError(fmt::format("roms picture {}: supergrid {} x {} with {} mask and {} depth values",
                                    path.string(), g.nx_pts, g.ny_pts, mask.size(), h.size()));
  if (o.width_px < 200 || o.width_px > 20000 || o.max_grid_lines < 2)
    throw InternalError(
        fmt::format("roms picture {}: width {} px, {} grid lines", path.string(), o.width_px, o.max_grid_lines));

  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    x0 = std::min(x0, g.x[k]);
    x1 = std::max(x1, g.x[k]);
    y0 = std::min(y0, g.y[k]);
    y1 = std::max(y1, g.y[k]);
  }
  const double pad = 0.04 * std::max(x1 - x0, y1 - y0);
  x0 -= pad;
  x1 += pad;
  y0 -= pad;
  y1 += pad;
  const double scale = (o.width_px - 2 * kMargin) / (x1 - x0);
  const int height = static_cast<int>(std::clamp((y1 - y0) * scale + kTitleBand + kLegend, 200.0, 20000.0));
  const auto px = [&](double x) { return kMargin + (x - x0) * scale; };
  const auto py = [&](double y) { return kTitleBand + (y1 - y) * scale; };

  std::unique_ptr<cairo_surface_t, SurfaceFree> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, o.width_px, height));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw OutputError(fmt::format("{}: cannot create a {} x {} picture: {}", path.string(), o.width_px, height,
                                  cairo_status_to_string(cairo_surface_status(surface.get()))));
  std::unique_ptr<cairo_t, ContextFree> context(cairo_create(surface.get()));
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);

  // Depth range of the water for the colour scale.
  double h0 = 1e300, h1 = 0.0;
  for (std::size_t k = 0; k < nr; ++k)
    if (mask[k] != 0) {
      h0 = std::min(h0, h[k]);
      h1 = std::max(h1, h[k]);
    }
  if (!(h0 < h1)) {
    h0 = 1.0;
    h1 = std::max(10.0, h1);
  }
  h0 = std::max(h0, 1.0);

  // Control volumes, without antialiasing so that neighbours leave no seams.
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  const int nI = g.nx_pts - 1, nJ = g.ny_pts - 1;
  for (int j = 0; j <= M; ++j)
    for (int i = 0; i <= L; ++i) {
      const int ia = std::max(2 * i - 1, 0), ib = std::min(2 * i + 1, nI);
      const int ja = std::max(2 * j - 1, 0), jb = std::min(2 * j + 1, nJ);
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(L + 1) + static_cast<std::size_t>(i);
      const RgbColour c = mask[k] != 0 ? water(h[k], h0, h1) : kLand;
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      // Corners and side midpoints of the control volume (boundary ones are half/quarter cells).
      const std::array<std::pair<int, int>, 8> ring = {
          {{ia, ja}, {2 * i, ja}, {ib, ja}, {ib, 2 * j}, {ib, jb}, {2 * i, jb}, {ia, jb}, {ia, 2 * j}}};
      for (std::size_t q = 0; q < ring.size(); ++q) {
        const std::size_t s = g.at(ring[q].first, ring[q].second);
        if (q == 0) {
          cairo_move_to(cr, px(g.x[s]), py(g.y[s]));
        } else {
          cairo_line_to(cr, px(g.x[s]), py(g.y[s]));
        }
      }
      cairo_close_path(cr);
      cairo_fill_preserve(cr);
      cairo_set_line_width(cr, 0.6);
      cairo_stroke(cr);
    }
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);

  // ψ lines (the cell faces), every k-th.
  const int step = std::max(1, (std::max(L, M) + o.max_grid_lines - 1) / o.max_grid_lines);
  cairo_set_source_rgba(cr, 0.15, 0.15, 0.15, 0.35);
  cairo_set_line_width(cr, 0.5);
  for (int i = 1; i < nI; i += 2 * step) {
    for (int J = 0; J <= nJ; ++J) {
      const std::size_t s = g.at(i, J);
      if (J == 0)
        cairo_move_to(cr, px(g.x[s]), py(g.y[s]));
      else
        cairo_line_to(cr, px(g.x[s]), py(g.y[s]));
    }
    cairo_stroke(cr);
  }
  for (int j = 1; j < nJ; j += 2 * step) {
    for (int I = 0; I <= nI; ++I) {
      const std::size_t s = g.at(I, j);
      if (I == 0)
        cairo_move_to(cr, px(g.x[s]), py(g.y[s]));
      else
        cairo_line_to(cr, px(g.x[s]), py(g.y[s]));
    }
    cairo_stroke(cr);
  }

  // Coastline, then the outlines.
  const double max_jump = 0.5 * std::max(x1 - x0, y1 - y0);
  const auto polylines = [&](const std::vector<std::vector<curvilinear::PlanePoint>>& lines, bool closed) {
    for (const auto& line : lines) {
      bool down = false;
      curvilinear::PlanePoint prev{};
      for (const auto& q : line) {
        const bool ok = std::isfinite(q.x) && std::isfinite(q.y);
        if (ok && down && std::hypot(q.x - prev.x, q.y - prev.y) <= max_jump) {
          cairo_line_to(cr, px(q.x), py(q.y));
        } else if (ok) {
          cairo_move_to(cr, px(q.x), py(q.y));
        }
        down = ok;
        prev = q;
      }
      if (closed) cairo_close_path(cr);
      cairo_stroke(cr);
    }
  };
  cairo_set_source_rgb(cr, 0.35, 0.22, 0.08);
  cairo_set_line_width(cr, 1.0);
  polylines(o.coastlines, false);

  // The contour (the supergrid's outline).
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.6);
  std::vector<std::pair<int, int>> outline;
  for (int I = 0; I <= nI; ++I) outline.emplace_back(I, 0);
  for (int J = 1; J <= nJ; ++J) outline.emplace_back(nI, J);
  for (int I = nI - 1; I >= 0; --I) outline.emplace_back(I, nJ);
  for (int J = nJ - 1; J >= 1; --J) outline.emplace_back(0, J);
  for (std::size_t q = 0; q < outline.size(); ++q) {
    const std::size_t s = g.at(outline[q].first, outline[q].second);
    if (q == 0)
      cairo_move_to(cr, px(g.x[s]), py(g.y[s]));
    else
      cairo_line_to(cr, px(g.x[s]), py(g.y[s]));
  }
  cairo_close_path(cr);
  cairo_stroke(cr);

  cairo_set_source_rgb(cr, 0.85, 0.1, 0.1);
  cairo_set_line_width(cr, 2.4);
  polylines(o.outlines, true);

  // Title and legend: land swatch, then the depth bar with 1-2-5 ticks.
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 15.0);
  cairo_move_to(cr, kMargin, 20.0);
  cairo_show_text(cr, o.title.c_str());
  const double ly = height - kLegend + 18.0;
  cairo_set_font_size(cr, 11.0);
  cairo_set_source_rgb(cr, kLand.r, kLand.g, kLand.b);
  cairo_rectangle(cr, kMargin, ly, 30.0, 14.0);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_move_to(cr, kMargin + 36.0, ly + 11.0);
  cairo_show_text(cr, "land (mask_rho = 0)");
  const double bx = kMargin + 170.0, bw = std::max(100.0, o.width_px - bx - 3 * kMargin);
  const int nbar = 256;
  for (int q = 0; q < nbar; ++q) {
    const double hq = h0 * std::pow(h1 / h0, (q + 0.5) / nbar);
    const RgbColour c = water(hq, h0, h1);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, bx + bw * q / nbar, ly, bw / nbar + 0.5, 14.0);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 1.0);
  for (double decade = std::pow(10.0, std::floor(std::log10(h0))); decade <= h1; decade *= 10.0)
    for (const double m : {1.0, 2.0, 5.0}) {
      const double hv = decade * m;
      if (hv < h0 * 0.999 || hv > h1 * 1.001) continue;
      const double xq = bx + bw * std::log(hv / h0) / std::log(h1 / h0);
      cairo_move_to(cr, xq, ly + 14.0);
      cairo_line_to(cr, xq, ly + 19.0);
      cairo_stroke(cr);
      const std::string label = fmt::format("{:g}", hv);
      cairo_move_to(cr, xq - 3.0 * static_cast<double>(label.size()), ly + 31.0);
      cairo_show_text(cr, label.c_str());
    }
  cairo_move_to(cr, bx, ly - 4.0);
  cairo_show_text(cr, fmt::format("water: model depth h (m), {:.4g} to {:.4g}, log scale", h0, h1).c_str());

  const cairo_status_t st = cairo_surface_write_to_png(surface.get(), path.c_str());
  if (st != CAIRO_STATUS_SUCCESS)
    throw OutputError(fmt::format("{}: cannot write the PNG: {}", path.string(), cairo_status_to_string(st)));
}

std::vector<std::vector<curvilinear::PlanePoint>> grid_coastlines(const raster::Bathymetry& bathy, double level_m,
                                                                  const double* lon_deg, const double* lat_deg,
                                                                  std::size_t n,
                                                                  const curvilinear::Projection& projection) {
  double w = 1e9, e = -1e9, s = 1e9, north = -1e9;
  for (std::size_t k = 0; k < n; ++k) {
    w = std::min(w, lon_deg[k]);
    e = std::max(e, lon_deg[k]);
    s = std::min(s, lat_deg[k]);
    north = std::max(north, lat_deg[k]);
  }
  constexpr double kPadDeg = 0.5;
  std::vector<std::vector<curvilinear::PlanePoint>> out;
  for (const auto& line : raster::contour_lines(bathy, level_m, w - kPadDeg, e + kPadDeg, std::max(-90.0, s - kPadDeg),
                                                std::min(90.0, north + kPadDeg))) {
    std::vector<curvilinear::PlanePoint> q(line.lon_deg.size());
    for (std::size_t k = 0; k < q.size(); ++k) q[k] = projection.forward(line.lon_deg[k], line.lat_deg[k]);
    out.push_back(std::move(q));
  }
  return out;
}

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// PNG pictures of the regional stages with Cairo; see regional_pictures.hpp (seed 000 Figs. 2,
// 3, 10, 11).
#include "pictures/regional_pictures.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "pictures/cairo_handles.hpp"

namespace aq::io {

namespace {

using curvilinear::GeoPoint;
using curvilinear::PlanePoint;
using curvilinear::RegionalResult;
using curvilinear::Stage;

struct Box {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  void add(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  [[nodiscard]] bool valid() const { return x1 > x0 && y1 > y0; }
  void grow(double f) {
    const double dx = (x1 - x0) * f, dy = (y1 - y0) * f;
    x0 -= dx;
    x1 += dx;
    y0 -= dy;
    y1 += dy;
  }
};

// Plane -> pixel transform (y up in the plane, down in the image).
struct RegionalView {
  double x0 = 0, y1 = 0, scale = 1;
  int width = 0, height = 0;
  static constexpr double kTop = 28.0;  // room for the title
  [[nodiscard]] double px(double x) const { return (x - x0) * scale; }
  [[nodiscard]] double py(double y) const { return kTop + (y1 - y) * scale; }
};

// 1, 2 or 5 times a power of ten, close to `raw`.
double nice_step(double raw) {
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return (m < 1.5 ? 1.0 : (m < 3.5 ? 2.0 : (m < 7.5 ? 5.0 : 10.0))) * p;
}

class Painter {
 public:
  Painter(cairo_t* cr, const RegionalView& v, double lw) : cr_(cr), v_(v), lw_(lw) {}

  // A polyline of plane points, cut at non-finite points and at jumps longer than `max_jump`
  // (a projection seam).
  void polyline(const std::vector<PlanePoint>& pts, double max_jump, bool closed = false) {
    bool down = false;
    PlanePoint prev{};
    const std::size_t n = pts.size() + (closed && !pts.empty() ? 1 : 0);
    for (std::size_t i = 0; i < n; ++i) {
      const PlanePoint& q = pts[i % pts.size()];
      const bool ok = std::isfinite(q.x) && std::isfinite(q.y);
      if (ok && down && std::hypot(q.x - prev.x, q.y - prev.y) <= max_jump) {
        cairo_line_to(cr_, v_.px(q.x), v_.py(q.y));
      } else if (ok) {
        cairo_move_to(cr_, v_.px(q.x), v_.py(q.y));
      }
      down = ok;
      prev = q;
    }
    cairo_stroke(cr_);
  }
  void line(double xa, double ya, double xb, double yb) {
    cairo_move_to(cr_, v_.px(xa), v_.py(ya));
    cairo_line_to(cr_, v_.px(xb), v_.py(yb));
    cairo_stroke(cr_);
  }
  void dot(double x, double y, double radius_px) {
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, v_.px(x), v_.py(y), radius_px * lw_, 0.0, 6.283185307179586);
    cairo_fill(cr_);
  }
  void square(double x, double y, double half_px) {
    const double h = half_px * lw_;
    cairo_rectangle(cr_, v_.px(x) - h, v_.py(y) - h, 2 * h, 2 * h);
    cairo_fill(cr_);
  }
  void style(double r, double g, double b, double width_px, std::initializer_list<double> dashes = {}) {
    cairo_set_source_rgb(cr_, r, g, b);
    cairo_set_line_width(cr_, width_px * lw_);
    std::vector<double> d;
    for (double x : dashes) d.push_back(x * lw_);
    cairo_set_dash(cr_, d.data(), static_cast<int>(d.size()), 0.0);
  }
  void text(double x_px, double y_px, const std::string& s, double size) {
    cairo_set_font_size(cr_, size);
    cairo_move_to(cr_, x_px, y_px);
    cairo_show_text(cr_, s.c_str());
  }

 private:
  cairo_t* cr_;
  const RegionalView& v_;
  double lw_;
};

// Geographic box of the picture for the map stage: the params' edges, else the plane box's.
struct GeoBox {
  double w, e, s, n;
};

GeoBox geo_box(const RegionalResult& r, const Box& plane) {
  const auto& p = r.params;
  if (std::isfinite(p.west_edge) && std::isfinite(p.east_edge) && std::isfinite(p.south_edge) &&
      std::isfinite(p.north_edge))
    return {p.west_edge, p.east_edge, p.south_edge, p.north_edge};
  GeoBox g{1e300, -1e300, 1e300, -1e300};
  const double lon_ref = p.projection.rlon_deg;
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 100.0;
    for (const auto& [x, y] : {std::pair{plane.x0 + t * (plane.x1 - plane.x0), plane.y0},
                               std::pair{plane.x0 + t * (plane.x1 - plane.x0), plane.y1},
                               std::pair{plane.x0, plane.y0 + t * (plane.y1 - plane.y0)},
                               std::pair{plane.x1, plane.y0 + t * (plane.y1 - plane.y0)}}) {
      const GeoPoint q = r.projection->inverse(x, y);
      double lon = q.lon_deg;
      while (lon < lon_ref - 180.0) lon += 360.0;
      while (lon >= lon_ref + 180.0) lon -= 360.0;
      g.w = std::min(g.w, lon);
      g.e = std::max(g.e, lon);
      g.s = std::min(g.s, q.lat_deg);
      g.n = std::max(g.n, q.lat_deg);
    }
  }
  return g;
}

}  // namespace

void write_regional_png(const std::filesystem::path& path, const RegionalResult& r, Stage stage,
                        const RegionalPictureOptions& options) {
  if (static_cast<int>(stage) > static_cast<int>(r.completed) || !r.projection)
    throw InternalError(
        fmt::format("regional picture of stage '{}' requested, but the run stopped after '{}'", stage, r.completed));
  if (options.width_px < 200 || options.width_px > 20000 || !(options.line_width > 0.0) || options.max_grid_lines < 2)
    throw InternalError(
        fmt::format("regional picture: width {} px (200..20000), line width {} (> 0), max grid lines "
                    "{} (>= 2)",
                    options.width_px, options.line_width, options.max_grid_lines));
  const auto& proj = *r.projection;
  const double lw = options.line_width;

  // Extent in the plane.
  Box box;
  if (stage == Stage::kMap) {
    const auto& p = r.params;
    if (std::isfinite(p.west_edge) && std::isfinite(p.east_edge) && std::isfinite(p.south_edge) &&
        std::isfinite(p.north_edge)) {
      for (int i = 0; i <= 200; ++i) {
        const double t = i / 200.0;
        const double lon = p.west_edge + t * (p.east_edge - p.west_edge);
        const double lat = p.south_edge + t * (p.north_edge - p.south_edge);
        for (const PlanePoint& q : {proj.forward(lon, p.south_edge), proj.forward(lon, p.north_edge),
                                    proj.forward(p.west_edge, lat), proj.forward(p.east_edge, lat)})
          box.add(q.x, q.y);
      }
    } else {
      for (std::size_t k = 0; k < r.control_x.size(); ++k) box.add(r.control_x[k], r.control_y[k]);
      box.grow(0.15);
    }
  } else {
    for (const PlanePoint& q : r.contour_samples) box.add(q.x, q.y);
    if (r.cubic_contour)
      for (const PlanePoint& q : r.cubic_contour->sample(16)) box.add(q.x, q.y);
    box.grow(0.06);
  }
  if (!box.valid()) {
    box = Box{};
    box.add(-1.0, -1.0);
    box.add(1.0, 1.0);
  }
  RegionalView v;
  v.x0 = box.x0;
  v.y1 = box.y1;
  v.width = options.width_px;
  v.scale = v.width / (box.x1 - box.x0);
  const double h = (box.y1 - box.y0) * v.scale + RegionalView::kTop;
  v.height = static_cast<int>(std::clamp(h, 100.0, 20000.0));
  const double diag = std::hypot(box.x1 - box.x0, box.y1 - box.y0);

  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, v.width, v.height));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw OutputError(fmt::format("{}: cannot create a {} x {} picture: {}", path.string(), v.width, v.height,
                                  cairo_status_to_string(cairo_surface_status(surface.get()))));
  std::unique_ptr<cairo_t, ContextDeleter> context(cairo_create(surface.get()));
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  Painter paint(cr, v, lw);

  // Background: graticule (map) or graph paper (other stages).
  if (stage == Stage::kMap) {
    const GeoBox g = geo_box(r, box);
    // regional.latlongrid, coarsened tenfold until at most 200 lines cross the map each way (a
    // spacing of 1e-6° once drew lines for minutes).
    double step = r.params.latlongrid;
    while ((g.e - g.w) / step > 200.0 || (g.n - g.s) / step > 200.0) step *= 10.0;
    paint.style(0.6, 0.6, 0.6, 0.8);
    const int nsamp = 240;
    for (double lon = std::ceil(g.w / step) * step; lon <= g.e + 1e-9; lon += step) {
      std::vector<PlanePoint> pts;
      for (int i = 0; i <= nsamp; ++i) pts.push_back(proj.forward(lon, g.s + (g.n - g.s) * i / nsamp));
      paint.polyline(pts, 0.5 * diag);
      const PlanePoint q = proj.forward(lon, g.s);
      if (std::isfinite(q.x))
        paint.text(v.px(q.x) + 2, std::min(v.py(q.y), v.height - 4.0), fmt::format("{:g}E", lon), 11);
    }
    for (double lat = std::ceil(g.s / step) * step; lat <= g.n + 1e-9; lat += step) {
      std::vector<PlanePoint> pts;
      for (int i = 0; i <= nsamp; ++i) pts.push_back(proj.forward(g.w + (g.e - g.w) * i / nsamp, lat));
      paint.polyline(pts, 0.5 * diag);
      const PlanePoint q = proj.forward(g.w, lat);
      if (std::isfinite(q.x)) paint.text(std::max(v.px(q.x), 2.0), v.py(q.y) - 2, fmt::format("{:g}N", lat), 11);
    }
    // The projection's axes through the centre (Fig. 2's dash-dot lines).
    paint.style(0.2, 0.2, 0.6, 1.0, {8.0, 3.0, 2.0, 3.0});
    paint.line(box.x0, 0.0, box.x1, 0.0);
    paint.line(0.0, box.y0, 0.0, box.y1);
  } else {
    // Graph paper in kilometres from the projection's centre, at the map's scale there (the plane
    // is conformal: the scale varies slowly away from it).
    const double km_per_unit = proj.metres_per_unit(0.0, 0.0) / 1000.0;
    const double minor = nice_step((box.x1 - box.x0) * km_per_unit / 40.0) / km_per_unit;
    for (int pass = 0; pass < 2; ++pass) {
      const double step = pass == 0 ? minor : 5.0 * minor;
      if (pass == 0) {
        paint.style(0.88, 0.93, 0.88, 0.5);
      } else {
        paint.style(0.65, 0.8, 0.65, 0.8);
      }
      for (double x = std::ceil(box.x0 / step) * step; x <= box.x1; x += step) paint.line(x, box.y0, x, box.y1);
      for (double y = std::ceil(box.y0 / step) * step; y <= box.y1; y += step) paint.line(box.x0, y, box.x1, y);
    }
    paint.style(0.3, 0.5, 0.3, 0.8);
    const auto km = [&](double u) {
      return fmt::format("{:g} km", std::round(u * km_per_unit * 1000.0) / 1000.0 + 0.0);
    };
    for (double x = std::ceil(box.x0 / (5 * minor)) * 5 * minor; x <= box.x1; x += 5 * minor)
      paint.text(v.px(x) + 2, v.height - 4.0, km(x), 10);
    for (double y = std::ceil(box.y0 / (5 * minor)) * 5 * minor; y <= box.y1; y += 5 * minor)
      paint.text(2.0, v.py(y) - 2, km(y), 10);
    paint.text(v.width / 2.0 - 150.0, v.height - 18.0, "x, y: km from the projection centre (its scale there)", 10);
    paint.style(0.2, 0.2, 0.6, 1.0, {8.0, 3.0, 2.0, 3.0});
    paint.line(box.x0, 0.0, box.x1, 0.0);
    paint.line(0.0, box.y0, 0.0, box.y1);
  }

  // Coastline.
  paint.style(0.55, 0.35, 0.1, 1.0);
  for (const auto& line : options.coastlines) {
    std::vector<PlanePoint> pts;
    pts.reserve(line.size());
    for (const GeoPoint& g : line) pts.push_back(proj.forward(g.lon_deg, g.lat_deg));
    paint.polyline(pts, 0.25 * diag);
  }

  // Contour and its corners.
  if (stage != Stage::kMap && r.contour) {
    if (r.cubic_contour) {
      paint.style(0.1, 0.3, 0.9, 1.2, {6.0, 4.0});
      paint.polyline(r.cubic_contour->sample(32), diag, true);
    }
    paint.style(0.0, 0.0, 0.0, stage == Stage::kGrid ? 1.6 : 1.8);
    paint.polyline(r.contour_samples, diag, true);
    if (stage == Stage::kContour) {
      // The two tangents at each corner: exactly perpendicular.
      paint.style(0.85, 0.0, 0.0, 1.6);
      const double len = 0.04 * diag;
      for (int c = 0; c < 4; ++c) {
        const auto out = static_cast<curvilinear::Side>(c), in = static_cast<curvilinear::Side>((c + 3) % 4);
        const double s = r.contour->side_begin(out);
        const PlanePoint o = r.contour->point(s);
        const PlanePoint a = r.contour->side_derivative(in, c == 0 ? r.contour->period() : s);
        const PlanePoint b = r.contour->side_derivative(out, s);
        const double na = std::hypot(a.x, a.y), nb = std::hypot(b.x, b.y);
        // Each tangent through the corner, so the right angle shows outside the contour too.
        paint.line(o.x - len * a.x / na, o.y - len * a.y / na, o.x + len * a.x / na, o.y + len * a.y / na);
        paint.line(o.x - len * b.x / nb, o.y - len * b.y / nb, o.x + len * b.x / nb, o.y + len * b.y / nb);
      }
    }
  }

  // Control points (corners as red squares).
  if (stage == Stage::kMap || stage == Stage::kContour) {
    for (std::size_t k = 0; k < r.control_x.size(); ++k) {
      if (r.control_corner[k]) {
        cairo_set_source_rgb(cr, 0.85, 0.0, 0.0);
        paint.square(r.control_x[k], r.control_y[k], 4.0);
      } else {
        cairo_set_source_rgb(cr, 0.85, 0.1, 0.1);
        paint.dot(r.control_x[k], r.control_y[k], 3.0);
      }
    }
  }

  // Boundary nodes.
  if (stage == Stage::kUniform || stage == Stage::kConformal) {
    if (stage == Stage::kConformal) {
      cairo_set_source_rgb(cr, 1.0, 0.75, 0.45);
      for (const PlanePoint& q : r.node_points(r.uniform_nodes)) paint.dot(q.x, q.y, 2.2);
    }
    cairo_set_source_rgb(cr, 0.0, 0.25, 0.85);
    const auto& n = stage == Stage::kUniform ? r.uniform_nodes : r.nodes;
    for (const PlanePoint& q : r.node_points(n)) paint.dot(q.x, q.y, 1.8);
  }

  // The grid: every k-th line and the boundary.
  if (stage == Stage::kGrid) {
    const auto& g = r.grid;
    const int ki = std::max(1, (g.nx_pts + options.max_grid_lines - 1) / options.max_grid_lines);
    const int kj = std::max(1, (g.ny_pts + options.max_grid_lines - 1) / options.max_grid_lines);
    paint.style(0.0, 0.2, 0.6, 0.6);
    std::vector<PlanePoint> pts;
    for (int i = 0; i < g.nx_pts; ++i) {
      if (i % ki != 0 && i != g.nx_pts - 1) continue;
      pts.clear();
      for (int j = 0; j < g.ny_pts; ++j) pts.push_back({g.x[g.at(i, j)], g.y[g.at(i, j)]});
      paint.polyline(pts, diag);
    }
    for (int j = 0; j < g.ny_pts; ++j) {
      if (j % kj != 0 && j != g.ny_pts - 1) continue;
      pts.clear();
      for (int i = 0; i < g.nx_pts; ++i) pts.push_back({g.x[g.at(i, j)], g.y[g.at(i, j)]});
      paint.polyline(pts, diag);
    }
  }

  // Title.
  std::string title = options.title;
  if (title.empty()) {
    title = fmt::format("{}: {}", r.params.source, std::string(name_of(stage)));
    if (stage == Stage::kMap)
      title += fmt::format(" ({} centred at {}N {}E, rota {})", std::string(name_of(r.params.projection.kind)),
                           r.params.projection.rlat_deg, r.params.projection.rlon_deg, r.params.projection.rota_deg);
    if (stage == Stage::kUniform || stage == Stage::kConformal) {
      const auto& n = stage == Stage::kUniform ? r.uniform_nodes : r.nodes;
      title += fmt::format(" ({} x {} boundary nodes)", n.nx_pts, n.ny_pts);
    }
    if (stage == Stage::kConformal) title += fmt::format(", W/H = {:.6f}", r.aspect_ratio);
    if (stage == Stage::kGrid) title += fmt::format(" ({} x {} supergrid)", r.grid.nx_pts, r.grid.ny_pts);
  }
  cairo_set_dash(cr, nullptr, 0, 0.0);
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_rectangle(cr, 0, 0, v.width, RegionalView::kTop - 4);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  paint.text(8.0, 19.0, title, 15);

  cairo_surface_flush(surface.get());
  const cairo_status_t st = cairo_surface_write_to_png(surface.get(), path.c_str());
  if (st != CAIRO_STATUS_SUCCESS)
    throw OutputError(fmt::format("{}: cannot write the picture: {}", path.string(), cairo_status_to_string(st)));
}

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// Cairo previews of a global mesh (see preview_png.hpp).
#include "pictures/preview_png.hpp"

#include <cairo.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/rotation.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/seam_nodes.hpp"
#include "pictures/png_encode.hpp"
#include "pictures/rotated_map_sampler.hpp"

namespace aq::io {

namespace {

// Boundary types of a regional mesh in the preview (index = mesh::BoundaryType).
// By mesh::BoundaryType: mainland black, island blue, open red, river inflow green.
constexpr std::array<std::array<double, 3>, 4> kBoundaryRgb{
    {{0.0, 0.0, 0.0}, {0.0, 0.35, 0.95}, {0.9, 0.05, 0.05}, {0.0, 0.65, 0.2}}};

bool typed_boundary(const mesh::Mesh& m) {
  return m.typed && m.boundary_edge_type.size() == m.boundary_edges.size();
}

}  // namespace

namespace {

// Picture geometry: map degrees (lattice plane) -> device pixels.
struct View {
  double lon_min = 0, lon_max = 0, lat_min = 0, lat_max = 0;
  int width = 0, map_h = 0, band = 0;
  [[nodiscard]] int height() const { return map_h + 2 * band; }
  [[nodiscard]] double sx() const { return width / (lon_max - lon_min); }
  [[nodiscard]] double sy() const { return map_h / (lat_max - lat_min); }
  [[nodiscard]] double px(double lon) const { return (lon - lon_min) * sx(); }
  [[nodiscard]] double py(double lat) const { return band + (lat_max - lat) * sy(); }
};

View make_view(double lon_min, double lon_max, double lat_min, double lat_max, int width) {
  View v{lon_min, lon_max, lat_min, lat_max, width, 0, 0};
  const double h = std::round(width * (lat_max - lat_min) / (lon_max - lon_min));
  v.map_h = static_cast<int>(std::clamp(h, 16.0, 4.0 * width));
  v.band = std::clamp(width / 60, 18, 64);
  return v;
}

// Viridis samples, coarse (level 0) to fine (level L).
constexpr std::array<std::array<double, 3>, 8> kLevelColours{{{0.267, 0.005, 0.329},
                                                              {0.275, 0.194, 0.497},
                                                              {0.213, 0.359, 0.552},
                                                              {0.153, 0.498, 0.558},
                                                              {0.122, 0.633, 0.530},
                                                              {0.288, 0.761, 0.428},
                                                              {0.626, 0.854, 0.225},
                                                              {0.993, 0.906, 0.144}}};

std::array<double, 3> level_colour(int level, int levels) {
  const int k = levels <= 0 ? 7 : static_cast<int>(std::lround(7.0 * level / levels));
  return kLevelColours[static_cast<std::size_t>(std::clamp(k, 0, 7))];
}

// Value classes of the "angle" and "size" fills: class k holds values below upper[k] (and at or
// above upper[k-1]); the last class has upper = +inf.
struct FillClasses {
  std::vector<double> upper;
  std::vector<std::array<int, 3>> rgb;
  std::vector<std::string> labels;
  [[nodiscard]] std::size_t class_of(float v) const {
    std::size_t k = 0;
    while (k + 1 < upper.size() && !(v < upper[k])) ++k;
    return k;
  }
};

FillClasses angle_classes() {
  FillClasses c;
  c.upper = {10, 20, 30, 40, 50, std::numeric_limits<double>::infinity()};
  c.rgb = {{165, 0, 38}, {215, 48, 39}, {244, 109, 67}, {254, 224, 139}, {166, 217, 106}, {26, 152, 80}};
  c.labels = {"min angle < 10°", "10-20°", "20-30°", "30-40°", "40-50°", ">= 50°"};
  return c;
}

// The "elevation" fill (a floodplain mesh, README "A storm-surge mesh"): a triangle's mean node
// elevation, sea in blues by depth (at or below the datum) and land above the datum in yellow to
// brown. The first class above the datum starts just above 0 m: a node at 0 m is not floodplain.
FillClasses elevation_classes() {
  FillClasses c;
  c.upper = {-200, -50, -10, 1e-9, 1, 2, 5, 10, std::numeric_limits<double>::infinity()};
  c.rgb = {{8, 48, 107},    {33, 113, 181}, {107, 174, 214}, {198, 219, 239}, {255, 247, 188},
           {254, 227, 145}, {254, 196, 79}, {254, 153, 41},  {204, 76, 2}};
  c.labels = {"depth > 200 m", "50-200 m", "10-50 m", "0-10 m", "above the datum 0-1 m",
              "1-2 m",         "2-5 m",    "5-10 m",  "> 10 m"};
  return c;
}

// 1-2-5 steps (km) from the largest at or below the smallest value to the smallest at or above
// the largest, at most 8 classes (every other step dropped until they fit).
FillClasses size_classes(const std::vector<float>& values, const std::vector<double>& range, const char* what) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const float v : values)
    if (std::isfinite(v) && v > 0.0f) {
      lo = std::min(lo, static_cast<double>(v));
      hi = std::max(hi, static_cast<double>(v));
    }
  if (range.size() == 2 && range[0] > 0.0 && range[1] >= range[0]) {  // a scale shared by several pictures
    lo = range[0];
    hi = range[1];
  }
  if (!std::isfinite(lo)) lo = hi = 1.0;
  std::vector<double> steps;
  for (double decade = std::pow(10.0, std::floor(std::log10(lo))); steps.empty() || steps.back() < hi; decade *= 10.0)
    for (const double m : {1.0, 2.0, 5.0})
      if (steps.empty() || steps.back() < hi) steps.push_back(m * decade);
  while (steps.size() > 2 && steps[1] <= lo) steps.erase(steps.begin());
  while (steps.size() > 9) {
    std::vector<double> fewer;
    for (std::size_t k = 0; k < steps.size(); k += 2) fewer.push_back(steps[k]);
    if (fewer.back() < steps.back()) fewer.push_back(steps.back());
    steps = fewer;
  }
  FillClasses c;
  const std::size_t n = std::max<std::size_t>(1, steps.size() - 1);
  for (std::size_t k = 0; k < n; ++k) {
    c.upper.push_back(k + 1 < n ? steps[k + 1] : std::numeric_limits<double>::infinity());
    const auto& v = kLevelColours[static_cast<std::size_t>(7 - (n > 1 ? 7 * k / (n - 1) : 0))];
    c.rgb.push_back({static_cast<int>(std::lround(255 * v[0])), static_cast<int>(std::lround(255 * v[1])),
                     static_cast<int>(std::lround(255 * v[2]))});
    c.labels.push_back(fmt::format("{}{:g}-{:g} km", k == 0 ? what : "", steps[k],
                                   steps.size() > 1 ? steps[std::min(k + 1, steps.size() - 1)] : steps[k]));
  }
  return c;
}

// Opaque RGB24 pixel for an elevation (m): hypsometric tints in depth/height classes (sea light
// to dark blue, land grey-green to brown-grey, no data light grey). Classes rather than a
// continuous ramp: the map reads like a chart and the PNG compresses several times better.
struct TintClass {
  double upper_m;  // the class holds elevations below this (and at or above the previous one)
  std::array<int, 3> rgb;
};
constexpr std::array<TintClass, 15> kTints{{{-6000, {8, 29, 88}},
                                            {-5000, {20, 52, 128}},
                                            {-4000, {33, 78, 160}},
                                            {-3000, {47, 105, 183}},
                                            {-2000, {66, 133, 201}},
                                            {-1000, {96, 160, 214}},
                                            {-500, {129, 186, 226}},
                                            {-200, {160, 206, 236}},
                                            {0, {198, 228, 246}},
                                            {200, {176, 196, 156}},
                                            {500, {160, 178, 136}},
                                            {1000, {146, 158, 118}},
                                            {2000, {138, 134, 104}},
                                            {4000, {128, 118, 100}},
                                            {1e9, {150, 146, 142}}}};
std::uint32_t pack_rgb(const std::array<int, 3>& c) {
  return 0xff000000u | (static_cast<std::uint32_t>(c[0]) << 16) | (static_cast<std::uint32_t>(c[1]) << 8) |
         static_cast<std::uint32_t>(c[2]);
}
std::uint32_t shade_exact(double e) {
  if (std::isnan(e)) return pack_rgb({221, 221, 221});
  for (const auto& t : kTints)
    if (e < t.upper_m) return pack_rgb(t.rgb);
  return pack_rgb(kTints.back().rgb);
}

// shade_exact tabulated per metre over [-kShadeDeep, kShadeHigh] (the background samples
// millions of pixels).
constexpr int kShadeDeep = 7000, kShadeHigh = 5000;
const std::vector<std::uint32_t>& shade_table() {
  static const std::vector<std::uint32_t> table = [] {
    std::vector<std::uint32_t> t(kShadeDeep + kShadeHigh + 1);
    for (int k = 0; k <= kShadeDeep + kShadeHigh; ++k) t[static_cast<std::size_t>(k)] = shade_exact(k - kShadeDeep);
    return t;
  }();
  return table;
}
// The nearest whole metre (halves away from zero, as std::lround) without a library call: for a
// float within [-kShadeDeep, kShadeHigh], k ± 0.5 is exact in double, so the truncation is.
std::uint32_t shade(const std::uint32_t* table, float e) {
  if (std::isnan(e)) return shade_exact(e);
  const double k = std::clamp(e, -static_cast<float>(kShadeDeep), static_cast<float>(kShadeHigh));
  return table[static_cast<int>(k < 0.0 ? k - 0.5 : k + 0.5) + kShadeDeep];
}

// Samples the raster at every map pixel centre (bands of rows in parallel; each band
// independent). With a rotated pole the pixels' raster values come from RotatedMapSampler
// (`exact`: atan2, asin and Bathymetry::sample at every pixel).
void draw_background(cairo_surface_t* surface, const View& v, const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                     bool exact) {
  cairo_surface_flush(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const int w = v.width, h = v.map_h, top = v.band;
  const Lattice& lattice = mesh.lattice;
  const auto rlon = [&v](double x) { return v.lon_min + (x + 0.5) / v.sx(); };
  const auto rlat = [&v, &lattice](double y) {
    const double plane_y = v.lat_max - (y + 0.5) / v.sy();
    return lattice.mercator() ? mercator_lat_deg(plane_y) : plane_y;
  };
  std::vector<double> lons(static_cast<std::size_t>(w));
  for (std::size_t x = 0; x < lons.size(); ++x) lons[x] = rlon(static_cast<double>(x));
  const bool rotated = mesh.rotation.enabled;
  const RotatedMapSampler sampler(
      bathy, rotated ? PoleRotation(mesh.rotation.pole_lon_deg, mesh.rotation.pole_lat_deg) : PoleRotation(),
      rotated ? w : 0, rotated ? h : 0, rlon, rlat);
  // A source read in tiles (a fine tile stack) is not drawn: a picture's pixel holds many of its
  // cells, and a sample per pixel would read a tile per pixel; the sources below it are.
  const raster::Bathymetry::Columns cols = bathy.prepare_columns(lons.data(), w, true);
  const raster::Bathymetry* b = &bathy;
  const raster::Bathymetry::Columns* c = &cols;
  const RotatedMapSampler* rs = &sampler;
  const std::function<double(double)> lat_of_row = rlat;
  const std::function<double(double)>* row_lat = &lat_of_row;
  const std::uint32_t* table = shade_table().data();
  constexpr int kBand = RotatedMapSampler::kTile;
  const int bands = (h + kBand - 1) / kBand;
  // Bands handed out as threads come free: the picture may be drawn while another thread writes
  // a file (app/output_jobs.hpp), and each band depends only on its own inputs.
#pragma omp parallel default(none) shared(data, stride, w, h, top, rotated, exact, b, c, rs, row_lat, table, bands)
  {
    std::vector<float> band(static_cast<std::size_t>(w) * kBand);
#pragma omp for schedule(dynamic, 1)
    for (int k = 0; k < bands; ++k) {
      const int y0 = k * kBand, rows = std::min(int{kBand}, h - y0);
      if (rotated) {
        exact ? rs->sample_rows_exact(y0, rows, band.data()) : rs->sample_rows(y0, rows, band.data());
      } else {
        for (int y = y0; y < y0 + rows; ++y)
          b->sample_row(*c, (*row_lat)(y), band.data() + static_cast<std::ptrdiff_t>(y - y0) * w);
      }
      for (int y = y0; y < y0 + rows; ++y) {
        const float* e = band.data() + static_cast<std::ptrdiff_t>(y - y0) * w;
        auto* px = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(top + y) * stride);
        for (int x = 0; x < w; ++x) px[x] = shade(table, e[x]);
      }
    }
  }
  cairo_surface_mark_dirty(surface);
}

// p + (c - p) * alpha / 256 per channel of an RGB24 pixel.
inline std::uint32_t blend(std::uint32_t p, const std::array<int, 3>& c, int alpha256) {
  std::uint32_t out = 0xff000000u;
  for (int k = 0; k < 3; ++k) {
    const int sh = 16 - 8 * k;
    const int old = static_cast<int>((p >> sh) & 0xff);
    out |= static_cast<std::uint32_t>(old + (((c[static_cast<std::size_t>(k)] - old) * alpha256) >> 8)) << sh;
  }
  return out;
}

// Draws the mesh at horizontal shifts of 0 and ±360° that reach into the view.
class MeshPainter {
 public:
  MeshPainter(cairo_t* cr, const View& v, const mesh::Mesh& m) : cr_(cr), v_(v), m_(m) {}

  [[nodiscard]] double x(std::int64_t i) const { return plane_lon_deg(m_.lattice, i); }
  // The lattice plane: φ′ on the lon-lat lattice, the Mercator ordinate on the Mercator one.
  [[nodiscard]] double y(std::int64_t j) const { return m_.lattice.plane_y_of(j); }

  // Shifts (degrees) at which the x-range [a, b] is inside the view.
  template <typename Fn>
  void at_shifts(double a, double b, Fn&& fn) const {
    for (const double s : {0.0, -360.0, 360.0})
      if (b + s >= v_.lon_min && a + s <= v_.lon_max) fn(s);
  }
  [[nodiscard]] bool rows_visible(double y0, double y1) const { return y1 >= v_.lat_min && y0 <= v_.lat_max; }

  // Side of a level-l square on the picture, in pixels.
  [[nodiscard]] double side_px(int level) const {
    return static_cast<double>(m_.lattice.pixels_per_square(level)) * m_.lattice.pixel_deg() * v_.sx();
  }
  // Edges of elements smaller than this are not drawn: they would only grey the picture out.
  static constexpr double kMinEdgePx = 2.5;

  // Blends every square's level colour into the pixels whose centres it contains. The squares
  // tile the wet area, so each pixel is filled once however small the squares are.
  void fill_squares(cairo_surface_t* surface, int levels, std::int64_t& drawn) const {
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    std::vector<std::array<int, 3>> colour(static_cast<std::size_t>(levels + 1));
    for (int l = 0; l <= levels; ++l) {
      const auto c = level_colour(l, levels);
      colour[static_cast<std::size_t>(l)] = {static_cast<int>(std::lround(255 * c[0])),
                                             static_cast<int>(std::lround(255 * c[1])),
                                             static_cast<int>(std::lround(255 * c[2]))};
    }
    constexpr int kAlpha = 108;  // of 256
    const double pix = m_.lattice.pixel_deg();
    for (std::size_t s = 0; s < m_.squares.size(); ++s) {
      const int level = m_.square_level[s];
      const NodeId sw = m_.squares[s][0];
      const double side = static_cast<double>(m_.lattice.pixels_per_square(level)) * pix;
      const double x0 = x(m_.node_i[sw]), y0 = y(m_.node_j[sw]);
      ++drawn;
      if (!rows_visible(y0, y0 + side)) continue;
      const auto& c = colour[static_cast<std::size_t>(std::min(level, levels))];
      at_shifts(x0, x0 + side, [&](double sh) {
        // Pixel k covers [k, k+1): its centre k + 0.5 is inside [a, b) for ceil(a - 0.5) <= k < ceil(b - 0.5).
        const int xa = std::max(0, static_cast<int>(std::ceil(v_.px(x0 + sh) - 0.5)));
        const int xb = std::min(v_.width, static_cast<int>(std::ceil(v_.px(x0 + side + sh) - 0.5)));
        const int ya = std::max(v_.band, static_cast<int>(std::ceil(v_.py(y0 + side) - 0.5)));
        const int yb = std::min(v_.band + v_.map_h, static_cast<int>(std::ceil(v_.py(y0) - 0.5)));
        for (int yy = ya; yy < yb; ++yy) {
          auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(yy) * stride);
          for (int xx = xa; xx < xb; ++xx) row[xx] = blend(row[xx], c, kAlpha);
        }
      });
    }
  }

  // Fills every triangle with a finite value opaquely in its class colour: the pixels whose
  // centres it contains (on a shared edge the later triangle wins).
  void fill_triangles(cairo_surface_t* surface, const std::vector<float>& values, const FillClasses& classes) const {
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (std::size_t k = 0; k < m_.triangles.size() && k < values.size(); ++k) {
      if (!std::isfinite(values[k])) continue;
      const auto& t = m_.triangles[k];
      std::array<double, 3> tx{}, ty{};
      for (std::size_t a = 0; a < 3; ++a) {
        tx[a] = x(m_.unwrapped_i(t, t[a])) + m_.plane_dx_deg(t[a]);
        ty[a] = m_.plane_y_deg(t[a]);
      }
      if (!rows_visible(std::min({ty[0], ty[1], ty[2]}), std::max({ty[0], ty[1], ty[2]}))) continue;
      const auto& rgb = classes.rgb[classes.class_of(values[k])];
      const std::uint32_t colour = 0xff000000u | (static_cast<std::uint32_t>(rgb[0]) << 16) |
                                   (static_cast<std::uint32_t>(rgb[1]) << 8) | static_cast<std::uint32_t>(rgb[2]);
      const auto [lo, hi] = std::minmax({tx[0], tx[1], tx[2]});
      at_shifts(lo, hi, [&](double sh) {
        std::array<double, 3> px{}, py{};
        for (std::size_t a = 0; a < 3; ++a) {
          px[a] = v_.px(tx[a] + sh);
          py[a] = v_.py(ty[a]);
        }
        const int xa = std::max(0, static_cast<int>(std::floor(std::min({px[0], px[1], px[2]}))));
        const int xb = std::min(v_.width - 1, static_cast<int>(std::ceil(std::max({px[0], px[1], px[2]}))));
        const int ya = std::max(v_.band, static_cast<int>(std::floor(std::min({py[0], py[1], py[2]}))));
        const int yb = std::min(v_.band + v_.map_h - 1, static_cast<int>(std::ceil(std::max({py[0], py[1], py[2]}))));
        auto side = [&](std::size_t a, double cx, double cy) {
          const std::size_t b = (a + 1) % 3;
          return (px[b] - px[a]) * (cy - py[a]) - (py[b] - py[a]) * (cx - px[a]);
        };
        for (int yy = ya; yy <= yb; ++yy) {
          auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(yy) * stride);
          for (int xx = xa; xx <= xb; ++xx) {
            const double cx = xx + 0.5, cy = yy + 0.5;
            const double s0 = side(0, cx, cy), s1 = side(1, cx, cy), s2 = side(2, cx, cy);
            if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) row[xx] = colour;
          }
        }
      });
    }
  }

  // seg(ax, ay, bx, by) in device pixels for each triangle edge once (a < b; the boundary edges
  // with a > b are drawn as coast).
  template <typename Seg>
  void triangle_edges(Seg&& seg) const {
    for (std::size_t k = 0; k < m_.triangles.size(); ++k) {
      if (side_px(m_.triangle_level[k]) < kMinEdgePx) continue;
      const auto& t = m_.triangles[k];
      std::array<double, 3> tx{}, ty{};
      for (int a = 0; a < 3; ++a) {
        tx[a] = x(m_.unwrapped_i(t, t[a])) + m_.plane_dx_deg(t[a]);
        ty[a] = m_.plane_y_deg(t[a]);
      }
      const auto [lo, hi] = std::minmax({tx[0], tx[1], tx[2]});
      if (!rows_visible(std::min({ty[0], ty[1], ty[2]}), std::max({ty[0], ty[1], ty[2]}))) continue;
      at_shifts(lo, hi, [&](double sh) {
        for (int a = 0; a < 3; ++a) {
          const int b = (a + 1) % 3;
          if (t[a] < t[b]) seg(v_.px(tx[a] + sh), v_.py(ty[a]), v_.px(tx[b] + sh), v_.py(ty[b]));
        }
      });
    }
  }

  // seg(...) for the four sides of every square.
  template <typename Seg>
  void square_edges(Seg&& seg) const {
    const double pix = m_.lattice.pixel_deg();
    for (std::size_t s = 0; s < m_.squares.size(); ++s) {
      if (side_px(m_.square_level[s]) < kMinEdgePx) continue;
      const NodeId sw = m_.squares[s][0];
      const double side = static_cast<double>(m_.lattice.pixels_per_square(m_.square_level[s])) * pix;
      const double x0 = x(m_.node_i[sw]), y0 = y(m_.node_j[sw]);
      if (!rows_visible(y0, y0 + side)) continue;
      at_shifts(x0, x0 + side, [&](double sh) {
        const double ax = v_.px(x0 + sh), bx = v_.px(x0 + side + sh);
        const double ay = v_.py(y0), by = v_.py(y0 + side);
        seg(ax, ay, bx, ay);
        seg(bx, ay, bx, by);
        seg(bx, by, ax, by);
        seg(ax, by, ax, ay);
      });
    }
  }

  // seg(...) for every boundary edge, unwrapped like the element it bounds.
  // `type` >= 0 (a typed regional mesh): only the edges of that mesh::BoundaryType.
  template <typename Seg>
  void coast_edges(Seg&& seg, int type = -1) const {
    for (std::size_t k = 0; k < m_.boundary_edges.size(); ++k) {
      const auto& e = m_.boundary_edges[k];
      if (type >= 0 && static_cast<int>(m_.boundary_edge_type[k]) != type) continue;
      const auto u = SeamNodes::edge_unwrapped(m_, e);
      const double ax = x(u[0] ? m_.lattice.nx : m_.node_i[e[0]]) + m_.plane_dx_deg(e[0]);
      const double bx = x(u[1] ? m_.lattice.nx : m_.node_i[e[1]]) + m_.plane_dx_deg(e[1]);
      const double ay = m_.plane_y_deg(e[0]), by = m_.plane_y_deg(e[1]);
      if (!rows_visible(std::min(ay, by), std::max(ay, by))) continue;
      at_shifts(std::min(ax, bx), std::max(ax, bx),
                [&](double sh) { seg(v_.px(ax + sh), v_.py(ay), v_.px(bx + sh), v_.py(by)); });
    }
  }

 private:
  cairo_t* cr_;
  const View& v_;
  const mesh::Mesh& m_;
};

// std::floor to int without the library call (the baseline x86-64 build has no SSE4.1
// rounding instruction); |v| < 2^31.
inline int floor_int(double v) {
  const int i = static_cast<int>(v);
  return i - (v < static_cast<double>(i) ? 1 : 0);
}

// Thin lines blended straight into the picture, one pixel per step along the major axis. The
// mesh has ~10^5 edges a few pixels long; Cairo's antialiased stroking of them costs more than
// all the rest of the picture, and at one pixel width the difference does not show.
class PixelPen {
 public:
  PixelPen(cairo_surface_t* surface, const View& v, std::array<int, 3> rgb, int alpha256)
      : data_(cairo_image_surface_get_data(surface)),
        stride_(cairo_image_surface_get_stride(surface)),
        y_lo_(v.band),
        y_hi_(v.band + v.map_h),
        w_(v.width),
        rgb_(rgb),
        a_(alpha256) {}
  void operator()(double x0, double y0, double x1, double y1) const {
    const double dx = x1 - x0, dy = y1 - y0;
    const int n = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)))));
    for (int k = 0; k < n; ++k) {
      const int ix = floor_int(x0 + dx * k / n);
      const int iy = floor_int(y0 + dy * k / n);
      if (ix < 0 || ix >= w_ || iy < y_lo_ || iy >= y_hi_) continue;
      auto* p = reinterpret_cast<std::uint32_t*>(data_ + static_cast<std::ptrdiff_t>(iy) * stride_) + ix;
      *p = blend(*p, rgb_, a_);
    }
  }

 private:
  unsigned char* data_;
  int stride_, y_lo_, y_hi_, w_;
  std::array<int, 3> rgb_;
  int a_;
};

// Segments as Cairo path pieces, stroked every 20000 segments and at the end.
class CairoStroker {
 public:
  explicit CairoStroker(cairo_t* cr) : cr_(cr) {}
  ~CairoStroker() { cairo_stroke(cr_); }
  CairoStroker(const CairoStroker&) = delete;
  CairoStroker& operator=(const CairoStroker&) = delete;
  void operator()(double ax, double ay, double bx, double by) {
    cairo_move_to(cr_, ax, ay);
    cairo_line_to(cr_, bx, by);
    if (++n_ == 20000) {
      cairo_stroke(cr_);
      n_ = 0;
    }
  }

 private:
  cairo_t* cr_;
  int n_ = 0;
};

int max_level(const mesh::Mesh& m) {
  int l = 0;
  for (const auto v : m.square_level) l = std::max(l, static_cast<int>(v));
  for (const auto v : m.triangle_level) l = std::max(l, static_cast<int>(v));
  return l;
}

void draw_text(cairo_t* cr, double x, double y, const std::string& s) {
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

// Draws `text` with its left end at x and returns its advance.
double text_advance(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  return ext.x_advance;
}

// Sets the font size to `size`, shrunk so that `width` (measured at `size`) fits in `room`.
void fit_font(cairo_t* cr, double size, double width, double room) {
  cairo_set_font_size(cr, width > room ? std::max(6.0, size * room / width) : size);
}

FillClasses fill_classes(const PreviewOptions& o) {
  if (o.colour == PreviewColour::kAngle) return angle_classes();
  if (o.colour == PreviewColour::kElevation) return elevation_classes();
  return size_classes(o.triangle_values, o.value_range_km, o.colour == PreviewColour::kTarget ? "target " : "size ");
}

void draw_bands(cairo_t* cr, const View& v, const mesh::Mesh& m, const PreviewOptions& o, const std::string& title) {
  const double font = v.band * 0.62, margin = font * 0.5, room = v.width - 2 * margin;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, 0, 0, v.width, v.band);
  cairo_rectangle(cr, 0, v.band + v.map_h, v.width, v.band);
  cairo_fill(cr);
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font);
  fit_font(cr, font, text_advance(cr, title), room);
  cairo_set_source_rgb(cr, 0, 0, 0);
  draw_text(cr, margin, v.band * 0.72, title);

  // Legend: a swatch per level with its element count, then depth classes, land and the coast.
  const int levels = m.lattice.levels;
  std::vector<std::int64_t> count(static_cast<std::size_t>(levels + 1), 0);
  const bool tri = has_triangles(o.elements) && !m.triangles.empty();
  for (const auto l : tri ? m.triangle_level : m.square_level)
    if (l <= levels) ++count[l];
  struct Item {
    std::array<double, 3> rgb;
    std::string label;
  };
  std::vector<Item> items;
  if (o.colour == PreviewColour::kLevel) {
    for (int l = 0; l <= levels; ++l) {
      items.push_back({level_colour(l, levels), fmt::format("level {}: {}{}", l, count[static_cast<std::size_t>(l)],
                                                            l == 0 ? (tri ? " triangles" : " squares") : "")});
    }
  } else {
    const FillClasses classes = fill_classes(o);
    std::vector<std::int64_t> in_class(classes.rgb.size(), 0);
    for (const float value : o.triangle_values)
      if (std::isfinite(value)) ++in_class[classes.class_of(value)];
    for (std::size_t k = 0; k < classes.rgb.size(); ++k) {
      const auto& c = classes.rgb[k];
      items.push_back({{c[0] / 255.0, c[1] / 255.0, c[2] / 255.0},
                       fmt::format("{}: {}{}", classes.labels[k], in_class[k], k == 0 ? " triangles" : "")});
    }
  }
  // The background's tints (with "elevation" the classes above say the depths: land and no data only).
  std::vector<std::pair<float, const char*>> tints{{-100.0f, "0-200 m"},      {-1500.0f, "1000-2000 m"},
                                                   {-4500.0f, "4000-5000 m"}, {-7000.0f, "> 6000 m"},
                                                   {100.0f, "land"},          {std::nanf(""), "no data"}};
  if (o.colour == PreviewColour::kElevation) tints.erase(tints.begin(), tints.begin() + 4);
  for (const auto& [e, label] : tints) {
    const std::uint32_t p = shade_exact(e);
    items.push_back({{((p >> 16) & 0xff) / 255.0, ((p >> 8) & 0xff) / 255.0, (p & 0xff) / 255.0}, label});
  }
  if (typed_boundary(m)) {
    items.push_back({kBoundaryRgb[0], "mainland"});
    items.push_back({kBoundaryRgb[1], "island"});
    items.push_back({kBoundaryRgb[2], "open boundary"});
    if (std::find(m.boundary_edge_type.begin(), m.boundary_edge_type.end(), mesh::BoundaryType::kRiver) !=
        m.boundary_edge_type.end())
      items.push_back({kBoundaryRgb[3], "river inflow"});
  } else {
    items.push_back({{0.0, 0.0, 0.0}, "coast"});
  }
  const double sw = v.band * 0.6;
  cairo_set_font_size(cr, font);
  double need = 0.0;
  for (const auto& it : items) need += sw * 1.3 + text_advance(cr, it.label) + font;
  fit_font(cr, font, need, room);
  const double scale = need > room ? room / need : 1.0;
  const double y0 = v.band + v.map_h;
  double x = margin;
  for (const auto& it : items) {
    cairo_set_source_rgb(cr, it.rgb[0], it.rgb[1], it.rgb[2]);
    cairo_rectangle(cr, x, y0 + v.band * 0.2, sw * scale, sw);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, x + sw * 1.3 * scale, y0 + v.band * 0.72, it.label);
    x += (sw * 1.3 + font) * scale + text_advance(cr, it.label);
  }
}

// Outlines (o.outlines) in magenta, each also shifted by ±360°, labels on a white box.
void draw_outlines(cairo_t* cr, const View& v, const Lattice& lattice, const std::vector<PreviewOutline>& outlines) {
  const double lat_max = lattice.lat_max_deg();
  const auto py = [&](double lat_deg) { return v.py(lattice.plane_y_of_lat(std::clamp(lat_deg, -lat_max, lat_max))); };
  const double font = std::clamp(v.width / 110.0, 9.0, 28.0);
  cairo_set_font_size(cr, font);
  for (const PreviewOutline& ol : outlines) {
    if (ol.points.size() < 2) continue;
    for (const double shift : {-360.0, 0.0, 360.0}) {
      cairo_set_line_width(cr, std::clamp(v.width / 1000.0, 1.5, 4.0));
      cairo_set_source_rgb(cr, 0.85, 0.0, 0.75);
      for (std::size_t k = 0; k < ol.points.size(); ++k) {
        const double x = v.px(ol.points[k][0] + shift), y = py(ol.points[k][1]);
        k == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
      }
      cairo_close_path(cr);
      cairo_stroke(cr);
      if (ol.label.empty()) continue;
      const double x = v.px(ol.points[0][0] + shift) + 2.0, y = py(ol.points[0][1]) - 2.0;
      cairo_set_source_rgb(cr, 1, 1, 1);
      cairo_rectangle(cr, x - 1.0, y - font, text_advance(cr, ol.label) + 2.0, font * 1.2);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      draw_text(cr, x, y, ol.label);
    }
  }
}

WriteStats render(const mesh::Mesh& mesh, const raster::Bathymetry& bathy, const std::filesystem::path& path,
                  const PreviewOptions& o, const View& v, const std::string& title, const std::vector<double>* box) {
  check_elements(mesh, o.elements);
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, v.width, v.height());
  cairo_t* cr = cairo_create(surface);
  struct Release {
    cairo_surface_t* s;
    cairo_t* c;
    ~Release() {
      cairo_destroy(c);
      cairo_surface_destroy(s);
    }
  } release{surface, cr};
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
    throw OutputError(fmt::format("{}: cannot create a {}x{} picture: {}", path.string(), v.width, v.height(),
                                  cairo_status_to_string(cairo_status(cr))));
  }

  draw_background(surface, v, mesh, bathy, o.exact_background);
  cairo_save(cr);
  cairo_rectangle(cr, 0, v.band, v.width, v.map_h);
  cairo_clip(cr);
  const MeshPainter paint(cr, v, mesh);
  WriteStats stats;
  std::int64_t squares = 0;
  // Fills and mesh edges straight into the pixels, then the coast with Cairo on top.
  cairo_surface_flush(surface);
  if (o.colour == PreviewColour::kLevel) {
    paint.fill_squares(surface, mesh.lattice.levels, squares);
  } else {
    squares = mesh.square_count();
    paint.fill_triangles(surface, o.triangle_values, fill_classes(o));
  }
  const bool tri = has_triangles(o.elements) && !mesh.triangles.empty();
  if (tri) paint.triangle_edges(PixelPen(surface, v, {30, 30, 40}, 140));
  if (!tri || has_squares(o.elements)) {
    paint.square_edges(PixelPen(surface, v, {0, 0, 0}, o.elements == ElementKinds::kBoth ? 210 : 150));
  }
  cairo_surface_mark_dirty(surface);
  cairo_set_line_width(cr, std::clamp(v.width / 1600.0, 1.2, 3.0));
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (typed_boundary(mesh)) {  // regional: mainland black, islands blue, open boundary red, rivers green
    cairo_set_line_width(cr, std::clamp(v.width / 800.0, 2.0, 4.0));
    for (int t = 0; t < 4; ++t) {
      const auto& c = kBoundaryRgb[static_cast<std::size_t>(t)];
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      CairoStroker coast(cr);
      paint.coast_edges(coast, t);
    }
  } else {
    CairoStroker coast(cr);
    paint.coast_edges(coast);
  }
  if (box != nullptr && box->size() == 4) {
    const auto& b = *box;
    cairo_set_line_width(cr, 2.0);
    cairo_set_source_rgb(cr, 0.9, 0.05, 0.05);
    const double y2 = mesh.lattice.plane_y_of_lat(b[2]), y3 = mesh.lattice.plane_y_of_lat(b[3]);
    cairo_rectangle(cr, v.px(b[0]), v.py(y3), v.px(b[1]) - v.px(b[0]), v.py(y2) - v.py(y3));
    cairo_stroke(cr);
  }
  draw_outlines(cr, v, mesh.lattice, o.outlines);
  cairo_restore(cr);
  draw_bands(cr, v, mesh, o, title);
  cairo_surface_flush(surface);
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
    throw OutputError(fmt::format("{}: drawing failed: {}", path.string(), cairo_status_to_string(cairo_status(cr))));
  }

  FileWriter f(path);
  write_png(surface, f);
  stats.bytes = f.close();
  stats.nodes = mesh.node_count();
  stats.elements = has_triangles(o.elements) && !mesh.triangles.empty() ? mesh.triangle_count() : squares;
  stats.boundary_edges = static_cast<std::int64_t>(mesh.boundary_edges.size());
  return stats;
}

std::string counts_title(const mesh::Mesh& m, const PreviewOptions& o) {
  std::string s = fmt::format("{}: {} nodes", o.title, m.node_count());
  if (has_triangles(o.elements) && !m.triangles.empty()) s += fmt::format(", {} triangles", m.triangle_count());
  s += fmt::format(", {} squares, levels 0-{}, step {} deg, {} boundary loops", m.square_count(), max_level(m),
                   m.lattice.step0_deg, m.loops.size());
  if (m.rotation.enabled) {
    s += fmt::format("; rotated pole ({:.6g}, {:.6g}), map in rotated coordinates", m.rotation.pole_lon_deg,
                     m.rotation.pole_lat_deg);
  }
  return s;
}

}  // namespace

void check_preview_options(const PreviewOptions& o) {
  const auto& z = o.zoom;
  const bool zoom_ok =
      z.empty() || (z.size() == 4 && std::all_of(z.begin(), z.end(), [](double v) { return std::isfinite(v); }) &&
                    z[0] < z[1] && z[1] - z[0] <= 360.0 && z[2] < z[3] && z[2] >= -90.0 && z[3] <= 90.0);
  if (o.width_px < 200 || o.width_px > 20000 || !zoom_ok)
    throw InternalError(
        fmt::format("preview: width {} px (200..20000) or zoom box [{}] out of range", o.width_px, fmt::join(z, ", ")));
}

WriteStats write_preview_png(const mesh::Mesh& mesh, const raster::Bathymetry& bathy, const std::filesystem::path& path,
                             const PreviewOptions& options) {
  check_preview_options(options);
  const double lon0 = mesh.lattice.lon0_deg;
  if (typed_boundary(mesh) && mesh.node_count() > 0) {  // a regional mesh: its own extent, 3% margin
    const auto [i_lo, i_hi] = std::minmax_element(mesh.node_i.begin(), mesh.node_i.end());
    const auto [j_lo, j_hi] = std::minmax_element(mesh.node_j.begin(), mesh.node_j.end());
    const Lattice& l = mesh.lattice;
    // Not across the seam (that one gets the whole map); a window lattice's columns never cross it.
    if (!l.periodic() || *i_hi - *i_lo < l.nx / 2) {
      const double x0 = l.lon_of(*i_lo), x1 = l.lon_of(*i_hi), y0 = l.plane_y_of(*j_lo), y1 = l.plane_y_of(*j_hi);
      const double mx = 0.03 * (x1 - x0) + l.pixel_deg(), my = 0.03 * (y1 - y0) + l.pixel_deg();
      // Clamped to the global lattice's rows (a window lattice's rows end a level-0 square from the mesh).
      const View v = make_view(x0 - mx, x1 + mx, std::max(y0 - my, l.plane_y_of(-l.j_origin)),
                               std::min(y1 + my, l.plane_y_of(l.ny_global - l.j_origin)), options.width_px);
      return render(mesh, bathy, path, options, v, counts_title(mesh, options), &options.zoom);
    }
  }
  const Lattice& gl = mesh.lattice;  // the global lattice's rows, also from a window lattice
  const View v = make_view(lon0, lon0 + 360.0, gl.plane_y_of(-gl.j_origin), gl.plane_y_of(gl.ny_global - gl.j_origin),
                           options.width_px);
  return render(mesh, bathy, path, options, v, counts_title(mesh, options), &options.zoom);
}

WriteStats write_preview_zoom_png(const mesh::Mesh& mesh, const raster::Bathymetry& bathy,
                                  const std::filesystem::path& path, const PreviewOptions& options) {
  check_preview_options(options);
  if (options.zoom.size() != 4) throw InternalError("write_preview_zoom_png: no zoom box given");
  const auto& z = options.zoom;
  const double lat_lo = std::max(z[2], -mesh.lattice.lat_max_deg()),
               lat_hi = std::min(z[3], mesh.lattice.lat_max_deg());
  if (!(lat_lo < lat_hi))
    throw ConfigError(
        fmt::format("output.png_zoom: latitudes [{}, {}] are outside the Mercator lattice's rows (|φ′| <= {:.4f})",
                    z[2], z[3], mesh.lattice.lat_max_deg()));
  const View v =
      make_view(z[0], z[1], mesh.lattice.plane_y_of_lat(lat_lo), mesh.lattice.plane_y_of_lat(lat_hi), options.width_px);
  const std::string title =
      fmt::format("{} - zoom lon [{}, {}] lat [{}, {}]", counts_title(mesh, options), z[0], z[1], z[2], z[3]);
  return render(mesh, bathy, path, options, v, title, nullptr);
}

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// The target size field: terms, combination, clamp, gradient limit, CFL (see size_field.hpp).
#include "size/size_field.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "core/types.hpp"
#include "raster/bathymetry.hpp"
#include "size/limit_gradient.hpp"
#include "size/terms.hpp"

namespace aq::size {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double round3(double x) { return std::round(x * 1000.0) / 1000.0; }

// min / median / max of the finite values of `v` over water cells (null when none).
Json summary(const std::vector<double>& v, const std::vector<std::uint8_t>& water, double* lo = nullptr,
             double* mid = nullptr, double* hi = nullptr) {
  std::vector<double> x;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (water[k] != 0 && std::isfinite(v[k])) x.push_back(v[k]);
  if (x.empty()) return Json{{"cells", 0}};
  const auto m = x.begin() + static_cast<std::ptrdiff_t>((x.size() - 1) / 2);
  std::nth_element(x.begin(), m, x.end());
  const double med = *m;
  const auto [a, b] = std::minmax_element(x.begin(), x.end());
  if (lo != nullptr) *lo = *a;
  if (mid != nullptr) *mid = med;
  if (hi != nullptr) *hi = *b;
  return Json{{"cells", x.size()}, {"min_km", round3(*a)}, {"median_km", round3(med)}, {"max_km", round3(*b)}};
}

void take_min(std::vector<double>& h, const std::vector<double>& t) {
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = std::min(h[k], t[k]);
}

// Per water cell the deepest H (m, >= min_depth) of the raster at the cell's pixel corners
// (stride max(1, s/8) pixels), NaN elsewhere; sampled in bands of cell rows.
std::vector<double> max_corner_depth(const FieldGrid& grid, const raster::Bathymetry& bathy, const PoleRotation& rotation,
                                     const std::vector<std::uint8_t>& water, double min_depth) {
  const Lattice& lat = grid.lattice();
  const std::int64_t s = grid.pixels_per_cell();
  const std::int64_t stride = std::max<std::int64_t>(1, s / 8);
  const std::int64_t per = s / stride;  // samples per cell side (corners: per + 1)
  const std::int64_t cols = grid.nx() * per;  // corner columns (periodic)
  const auto n = static_cast<std::size_t>(grid.cells());
  std::vector<double> out(n, std::numeric_limits<double>::quiet_NaN());
  const std::int64_t band = std::max<std::int64_t>(1, 256 / per);
  std::vector<double> lon, la, elev;
  for (std::int64_t j0 = 0; j0 < grid.ny(); j0 += band) {
    const std::int64_t j1 = std::min(grid.ny(), j0 + band);
    const std::int64_t r0 = j0 * per, r1 = j1 * per;  // corner rows r0..r1
    const auto pts = static_cast<std::size_t>((r1 - r0 + 1) * cols);
    lon.resize(pts);
    la.resize(pts);
    elev.resize(pts);
    for (std::int64_t r = r0; r <= r1; ++r) {
      const double plat = lat.lat_of_row(static_cast<double>(r * stride));
      for (std::int64_t q = 0; q < cols; ++q) {
        const auto k = static_cast<std::size_t>((r - r0) * cols + q);
        rotation.to_geographic(lat.lon_of(q * stride), plat, lon[k], la[k]);
      }
    }
    bathy.sample_points(lon.data(), la.data(), static_cast<std::int64_t>(pts), elev.data());
    for (std::int64_t j = j0; j < j1; ++j)
      for (std::int64_t i = 0; i < grid.nx(); ++i) {
        const auto k = static_cast<std::size_t>(grid.index(i, j));
        if (water[k] == 0) continue;
        double hm = min_depth;
        for (std::int64_t r = j * per; r <= (j + 1) * per; ++r)
          for (std::int64_t q = i * per; q <= (i + 1) * per; ++q) {
            const double e = elev[static_cast<std::size_t>((r - r0) * cols + wrap_index(q, cols))];
            if (std::isfinite(e)) hm = std::max(hm, -e);
          }
        out[k] = hm;
      }
  }
  return out;
}

// The pyramid of a field grid's values: level c (the grid's) is `top`; each coarser level
// combines the 2 × 2 cells under it with `combine` (min for sizes, max for the CFL bound).
template <typename Combine>
std::vector<std::vector<float>> pyramid(const FieldGrid& g, std::vector<float> top, Combine combine) {
  std::vector<std::vector<float>> levels(static_cast<std::size_t>(g.level()) + 1);
  levels.back() = std::move(top);
  for (int l = g.level() - 1; l >= 0; --l) {
    const std::vector<float>& fine = levels[static_cast<std::size_t>(l) + 1];
    const std::int64_t fnx = g.nx() >> (g.level() - l - 1);
    const std::int64_t nx = fnx / 2, ny = (g.ny() >> (g.level() - l - 1)) / 2;
    std::vector<float>& out = levels[static_cast<std::size_t>(l)];
    out.resize(static_cast<std::size_t>(nx * ny));
    for (std::int64_t b = 0; b < ny; ++b)
      for (std::int64_t a = 0; a < nx; ++a) {
        const auto f = [&](std::int64_t i, std::int64_t j) { return fine[static_cast<std::size_t>(j * fnx + i)]; };
        out[static_cast<std::size_t>(b * nx + a)] =
            combine(combine(f(2 * a, 2 * b), f(2 * a + 1, 2 * b)), combine(f(2 * a, 2 * b + 1), f(2 * a + 1, 2 * b + 1)));
      }
  }
  return levels;
}

// The pyramid's value over level-l square (a, b); a square finer than the grid reads the grid
// cell that holds it.
double pyramid_at(const FieldGrid& g, const std::vector<std::vector<float>>& levels, int l, std::int64_t a,
                  std::int64_t b) {
  const int c = g.level();
  if (l > c) {
    a >>= (l - c);
    b >>= (l - c);
    l = c;
  }
  const std::int64_t nx = g.nx() >> (c - l);
  return levels[static_cast<std::size_t>(l)][static_cast<std::size_t>(b * nx + a)];
}

}  // namespace

SizeField::SizeField(FieldGrid grid, std::vector<float> h_km, double band_km, int band_radius)
    : grid_(std::move(grid)), band_km_(band_km), band_radius_(band_radius) {
  const FieldGrid& g = *grid_;
  if (static_cast<std::int64_t>(h_km.size()) != g.cells())
    throw InternalError(fmt::format("size: {} values for a grid of {} cells", h_km.size(), g.cells()));
  levels_ = pyramid(g, std::move(h_km), [](float x, float y) { return std::min(x, y); });
}

double SizeField::grid_min_over_square(int l, std::int64_t a, std::int64_t b) const {
  if (!grid_) return kInf;
  return pyramid_at(*grid_, levels_, l, a, b);
}

void SizeField::set_cfl_edges(std::vector<float> edge_km) {
  cfl_levels_.clear();
  if (edge_km.empty()) return;
  const FieldGrid& g = *grid_;
  if (static_cast<std::int64_t>(edge_km.size()) != g.cells())
    throw InternalError(fmt::format("size: {} CFL values for a grid of {} cells", edge_km.size(), g.cells()));
  cfl_levels_ = pyramid(g, std::move(edge_km), [](float x, float y) { return std::max(x, y); });
}

double SizeField::cfl_edge_over_square(int l, std::int64_t a, std::int64_t b) const {
  if (cfl_levels_.empty()) return 0.0;
  return pyramid_at(*grid_, cfl_levels_, l, a, b);
}

double SizeField::at_pixel(std::int64_t i, std::int64_t j) const {
  if (!grid_) return kInf;
  const std::int64_t s = grid_->pixels_per_cell();
  return levels_.back()[static_cast<std::size_t>((j / s) * grid_->nx() + wrap_index(i, grid_->lattice().nx) / s)];
}

bool needs_depth(const config::SizeOptions& s) { return s.wavelength.wl > 0.0 || s.slope.slp > 0.0 || s.cfl.dt_s > 0.0; }

namespace {
template <typename Rule>
bool any_size_rule(const std::vector<Rule>& rules) {
  return std::any_of(rules.begin(), rules.end(), [](const Rule& r) { return r.size_km > 0.0; });
}
bool in_box(const config::BoxRule& r, double lon, double lat) {
  if (lat < r.lat_min_deg || lat > r.lat_max_deg) return false;
  const double hi = r.lon_max_deg < r.lon_min_deg ? r.lon_max_deg + 360.0 : r.lon_max_deg;
  return wrap_lon_deg(lon, r.lon_min_deg) <= hi;
}
}  // namespace

bool has_size_rules(const config::QuadtreeOptions& q) {
  return any_size_rule(q.depth_rules) || any_size_rule(q.box_rules);
}

bool needs_grid(const config::GlobalConfig& c) {
  const config::SizeOptions& s = c.size;
  const bool floodplain = c.mask.min_depth_m < 0.0 && (s.inland.h0_km > 0.0 || s.elevation.h0_km > 0.0);
  return c.quadtree.size_km > 0.0 || has_size_rules(c.quadtree) || s.coast.h0_km > 0.0 || s.feature.r > 0.0 ||
         needs_depth(s) || !s.raster.empty() || s.h_max_km > 0.0 ||
         (s.gradation > 0.0 && c.quadtree.coast_size_km > 0.0) || floodplain;
}

SizeField build_size_field(const Bitmap& filled, const Lattice& lat, const config::GlobalConfig& c,
                           const PoleRotation& rotation, const raster::Bathymetry* bathy, const Logger& log,
                           Report* report, const mask::CoastSources& coast_sources) {
  return build_size_field(
      [&](const FieldGrid& grid) {
        FieldCells cells;
        cells.filled = grid.filled_counts(filled);
        cells.coast =
            coast_sources.plain() ? coast_cells(grid, cells.filled) : shore_cells(grid, filled, coast_sources);
        if (coast_sources.sea != nullptr) cells.sea = grid.filled_counts(*coast_sources.sea);
        return cells;
      },
      lat, c, rotation, bathy, log, report);
}

SizeField build_size_field(const std::function<FieldCells(const FieldGrid&)>& field_cells, const Lattice& lat,
                           const config::GlobalConfig& c, const PoleRotation& rotation, const raster::Bathymetry* bathy,
                           const Logger& log, Report* report) {
  const config::SizeOptions& s = c.size;
  const double band_km = c.quadtree.coast_size_km;
  const int band_radius = std::max(c.quadtree.coast_band, 1);
  if (!needs_grid(c)) return SizeField(band_km, band_radius);
  const bool depth_size_rules = any_size_rule(c.quadtree.depth_rules);
  if ((needs_depth(s) || depth_size_rules || s.elevation.h0_km > 0.0) && bathy == nullptr)
    throw InternalError("size: depth and elevation terms need the bathymetry raster");

  StageScope stage("size", report, log);
  Timer t_total;
  const FieldGrid grid(lat, choose_grid_level(lat, s.grid_level));
  const auto n = static_cast<std::size_t>(grid.cells());
  // The coast (mask/coast.hpp): cells holding land, not the open water beyond the domain edge;
  // with a floodplain the land at the datum, so the coast terms measure from the shoreline.
  const FieldCells cells = field_cells(grid);
  const std::vector<std::int32_t>& counts = cells.filled;
  const std::vector<std::uint8_t>& coast = cells.coast;
  std::vector<std::uint8_t> water(n);
  for (std::size_t k = 0; k < n; ++k) water[k] = counts[k] > 0 ? 1 : 0;
  // With a floodplain: the cells holding sea (what the coast and feature terms size) and those
  // holding floodplain pixels (what the inland and elevation terms size).
  std::vector<std::uint8_t> sea_cells, floodplain_cells;
  if (!cells.sea.empty()) {
    const std::vector<std::int32_t>& sea_counts = cells.sea;
    sea_cells.resize(n);
    floodplain_cells.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      sea_cells[k] = sea_counts[k] > 0 ? 1 : 0;
      floodplain_cells[k] = counts[k] > sea_counts[k] ? 1 : 0;
    }
  }
  const std::vector<std::uint8_t>& coast_water = sea_cells.empty() ? water : sea_cells;
  SizeFieldStats st;
  std::vector<double> h(n, kInf);
  Json timings = Json::object();

  if (c.quadtree.size_km > 0.0) {
    std::fill(h.begin(), h.end(), c.quadtree.size_km);
    st.terms["size_km"] = summary(h, water);
  }
  std::vector<double> coast_d;  // distance to the coast and the nearest coast cell, shared by both terms
  std::vector<std::int32_t> nearest;
  if (s.coast.h0_km > 0.0 || s.feature.r > 0.0) {
    Timer t;
    coast_d = distance_to(grid, coast, &nearest);
    timings["coast_distance"] = round3(t.wall_s());
  }
  if (s.coast.h0_km > 0.0) {
    Timer t;
    std::vector<double> term = coast_term(coast_d, s.coast.h0_km, s.coast.alpha);
    for (std::size_t k = 0; k < floodplain_cells.size(); ++k)  // the floodplain terms size floodplain without sea
      if (floodplain_cells[k] != 0 && sea_cells[k] == 0) term[k] = kInf;
    st.terms["coast"] = summary(term, water);
    take_min(h, term);
    timings["coast"] = round3(t.wall_s());
  }
  if (s.feature.r > 0.0) {
    Timer t;
    const std::vector<double> term = feature_term(grid, coast_d, nearest, coast_water, s.feature.r);
    st.terms["feature"] = summary(term, water);
    take_min(h, term);
    timings["feature"] = round3(t.wall_s());
  }
  if (!floodplain_cells.empty() && s.inland.h0_km > 0.0) {  // h0 + α·d, d inland from the nearest cell holding sea
    Timer t;
    std::vector<double> term = distance_to(grid, sea_cells);
    for (std::size_t k = 0; k < n; ++k)
      term[k] = floodplain_cells[k] != 0 ? s.inland.h0_km + s.inland.alpha * term[k] : kInf;
    st.terms["inland"] = summary(term, water);
    take_min(h, term);
    timings["inland"] = round3(t.wall_s());
  }
  const bool elevation_term = !floodplain_cells.empty() && s.elevation.h0_km > 0.0;
  std::vector<double> depth;  // H (m, >= min_depth) on water cells, NaN elsewhere
  std::vector<double> geo_lat(n, 0.0);
  const bool box_size_rules = any_size_rule(c.quadtree.box_rules);
  if (needs_depth(s) || depth_size_rules || box_size_rules || elevation_term) {
    Timer t;
    std::vector<double> lon(n), latv(n), elev(n);
    for (std::int64_t j = 0; j < grid.ny(); ++j)
      for (std::int64_t i = 0; i < grid.nx(); ++i) {
        const auto k = static_cast<std::size_t>(grid.index(i, j));
        rotation.to_geographic(grid.lon_deg(i), grid.lat_deg(j), lon[k], latv[k]);
        geo_lat[k] = latv[k];
      }
    if (box_size_rules) {  // quadtree.box_rules with size_km: a constant term inside each box (cell centres)
      std::vector<double> term(n, kInf);
      for (const config::BoxRule& r : c.quadtree.box_rules) {
        if (!(r.size_km > 0.0)) continue;
        for (std::size_t k = 0; k < n; ++k)
          if (in_box(r, lon[k], latv[k])) term[k] = std::min(term[k], r.size_km);
      }
      st.terms["box_rules"] = summary(term, water);
      take_min(h, term);
    }
    if (needs_depth(s) || depth_size_rules || elevation_term) {
      bathy->sample_points(lon.data(), latv.data(), static_cast<std::int64_t>(n), elev.data());
      if (elevation_term) {  // h0 + k·z on the floodplain cells, z the elevation at the centre (at least 0)
        std::vector<double> term(n, kInf);
        for (std::size_t k = 0; k < n; ++k)
          if (floodplain_cells[k] != 0)
            term[k] =
                s.elevation.h0_km + s.elevation.km_per_m * (std::isfinite(elev[k]) ? std::max(0.0, elev[k]) : 0.0);
        st.terms["elevation"] = summary(term, water);
        take_min(h, term);
      }
      if (depth_size_rules) {  // quadtree.depth_rules with size_km: a constant term in each depth band
        std::vector<double> term(n, kInf);
        for (const config::DepthRule& r : c.quadtree.depth_rules) {
          if (!(r.size_km > 0.0)) continue;
          for (std::size_t k = 0; k < n; ++k) {
            const double d = -elev[k];  // NaN: in no band
            if (d >= r.min_depth_m && d < r.max_depth_m) term[k] = std::min(term[k], r.size_km);
          }
        }
        st.terms["depth_rules"] = summary(term, water);
        take_min(h, term);
      }
      if (needs_depth(s)) {
        // A floodplain cell without sea has no depth at rest: the wavelength and slope terms are
        // the sea's (the floodplain terms size it), as on land (the CFL bound keeps it, below).
        depth.assign(n, std::numeric_limits<double>::quiet_NaN());
        for (std::size_t k = 0; k < n; ++k)
          if (water[k] != 0 && (sea_cells.empty() || sea_cells[k] != 0))
            depth[k] = std::max(std::isfinite(elev[k]) ? -elev[k] : 0.0, s.min_depth_m);
      }
    }
    timings["depth"] = round3(t.wall_s());
  }
  if (s.wavelength.wl > 0.0) {
    const std::vector<double> term = wavelength_term(depth, s.wavelength.period_h, s.wavelength.wl);
    st.terms["wavelength"] = summary(term, water);
    take_min(h, term);
  }
  if (s.slope.slp > 0.0) {
    Timer t;
    const std::vector<double> smooth = rossby_filter(grid, depth, geo_lat, s.slope.filter, s.slope.filter_max_km);
    const std::vector<double> term = slope_term(grid, smooth, s.slope.slp);
    st.terms["slope"] = summary(term, water);
    take_min(h, term);
    timings["slope"] = round3(t.wall_s());
  }
  if (!s.raster.empty()) {
    Timer t;
    raster::OpenOptions ro;
    ro.path = s.raster;
    const raster::Bathymetry sizes = raster::Bathymetry::open(ro, log);
    std::vector<double> lon(n), latv(n), v(n);
    for (std::int64_t j = 0; j < grid.ny(); ++j)
      for (std::int64_t i = 0; i < grid.nx(); ++i) {
        const auto k = static_cast<std::size_t>(grid.index(i, j));
        rotation.to_geographic(grid.lon_deg(i), grid.lat_deg(j), lon[k], latv[k]);
      }
    sizes.sample_points(lon.data(), latv.data(), static_cast<std::int64_t>(n), v.data());
    for (std::size_t k = 0; k < n; ++k) {
      if (std::isnan(v[k])) {
        v[k] = kInf;
      } else if (!(v[k] > 0.0) || !std::isfinite(v[k])) {
        throw InputError(fmt::format("size.raster = {}: value {} at lon {:.4f}, lat {:.4f} is not a size > 0 km",
                                     s.raster, v[k], lon[k], latv[k]));
      }
    }
    st.terms["raster"] = summary(v, water);
    take_min(h, v);
    timings["raster"] = round3(t.wall_s());
  }
  if (band_km > 0.0 && s.gradation > 0.0) {  // the band's size on the cells at the coast, to grade from
    for (std::int64_t j = 0; j < grid.ny(); ++j)
      for (std::int64_t i = 0; i < grid.nx(); ++i) {
        const auto k = static_cast<std::size_t>(grid.index(i, j));
        if (water[k] == 0) continue;
        bool near = false;
        for (std::int64_t dj = -1; dj <= 1 && !near; ++dj)
          for (std::int64_t di = -1; di <= 1 && !near; ++di) {
            const std::int64_t jj = j + dj;
            if (jj >= 0 && jj < grid.ny()) near = coast[static_cast<std::size_t>(grid.index(wrap_index(i + di, grid.nx()), jj))] != 0;
          }
        if (near) h[k] = std::min(h[k], band_km);
      }
  }
  if (s.h_max_km > 0.0)
    for (double& x : h) x = std::min(x, s.h_max_km);
  if (s.h_min_km > 0.0)
    for (double& x : h) x = std::isfinite(x) ? std::max(x, s.h_min_km) : x;
  summary(h, water, &st.min_km, &st.median_km, &st.max_km);
  Json combined = summary(h, water);
  if (s.gradation > 0.0) {
    Timer t;
    st.sweeps = limit_gradient(grid, h, s.gradation);
    timings["gradient_limit"] = round3(t.wall_s());
  }
  Json limited = summary(h, water);
  std::vector<float> cfl_edges;
  if (s.cfl.dt_s > 0.0) {
    Timer t;
    // The bound E is on the edges the mesh will have, whose nodes sit at pixel corners and whose
    // Courant number takes the deepest node: so H is the deepest raster value at the cell's
    // pixel corners (all of them up to 8 pixels a cell side, every (s/8)-th beyond), not the
    // centre's. A bound must also hold next to where it is large, because the 2:1 balance and
    // the grading only let sizes fall at the field's rate: E is spread as
    // E′(x) = max over cells s of E(s) − g/(2√2)·dist(s, x), so that the floor 2√2·E′ (the size
    // of a square whose transition triangles, legs a/4 of its parent, still meet E′ when the
    // parent is split at √2·h) keeps |∇h| <= g. The quadtree refuses any split whose children
    // could hold an edge below E′ (quadtree/leaves.hpp).
    const std::vector<double> hmax = max_corner_depth(grid, *bathy, rotation, water, s.min_depth_m);
    const std::vector<double> bound = cfl_bound(hmax, s.cfl.dt_s, s.cfl.courant_max, s.cfl.velocity_ms);
    st.terms["cfl_bound"] = summary(bound, water);
    double top = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      if (water[k] != 0 && std::isfinite(bound[k])) top = std::max(top, bound[k]);
    std::vector<double> spread(n, kInf);  // top − E, gradient-limited: top − E′
    for (std::size_t k = 0; k < n; ++k)
      if (water[k] != 0 && std::isfinite(bound[k])) spread[k] = top - bound[k];
    if (s.gradation > 0.0) limit_gradient(grid, spread, s.gradation / (2.0 * std::sqrt(2.0)));
    cfl_edges.assign(n, 0.0F);
    std::vector<double> graded(n, kInf);
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(spread[k])) continue;
      const double e = std::max(0.0, top - spread[k]);
      graded[k] = e;
      h[k] = std::max(h[k], 2.0 * std::sqrt(2.0) * e);
      // float rounding up, so that the float bound is never below the double one
      cfl_edges[k] = std::nextafter(static_cast<float>(e), std::numeric_limits<float>::infinity());
    }
    st.terms["cfl_bound_spread"] = summary(graded, water);
    timings["cfl"] = round3(t.wall_s());
  }
  Json final_summary = summary(h, water, &st.min_km, &st.median_km, &st.max_km);
  std::vector<float> hf(n);
  for (std::size_t k = 0; k < n; ++k) hf[k] = static_cast<float>(h[k]);
  st.grid_level = grid.level();
  st.nx = grid.nx();
  st.ny = grid.ny();
  st.cell_km_equator = kEarthRadiusKm * lat.step0_deg / static_cast<double>(std::int64_t{1} << grid.level()) * kDegToRad;
  const double total_s = t_total.wall_s();
  if (report != nullptr) {
    Json& r = (*report)["size"];
    r["grid_level"] = st.grid_level;
    r["grid_cells"] = Json::array({st.nx, st.ny});
    r["cell_km_at_equator"] = round3(st.cell_km_equator);
    r["terms"] = st.terms;
    r["combined"] = combined;
    r["gradation"] = s.gradation;
    r["gradient_limited"] = limited;
    r["limiter_sweeps"] = st.sweeps;
    r["field"] = final_summary;
    r["coast_band_km"] = band_km;
    timings["total"] = round3(total_s);
    r["timings_s"] = timings;
  }
  std::string names;
  for (const auto& [k, v] : st.terms.items()) names += (names.empty() ? "" : ", ") + k;
  stage.done(fmt::format("{} x {} cells of level {} ({:.1f} km at the equator); terms {}; g = {}{}; h {:.1f}/{:.1f}/{:.1f} km (min/median/max over water)",
                         st.nx, st.ny, st.grid_level, st.cell_km_equator, names.empty() ? "none" : names, s.gradation,
                         st.sweeps > 0 ? fmt::format(" ({} sweeps)", st.sweeps) : std::string(), st.min_km, st.median_km,
                         st.max_km));
  SizeField field(grid, std::move(hf), band_km, band_radius);
  field.set_gradation(s.gradation);
  field.set_cfl_edges(std::move(cfl_edges));
  return field;
}

}  // namespace aq::size

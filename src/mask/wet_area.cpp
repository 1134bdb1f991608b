// SPDX-License-Identifier: GPL-3.0-or-later
// The mask stage entry point: classify -> K-fill -> pinches -> passages, with stage lines,
// progress and the "mask" report section.
#include "mask/wet_area.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "mask/lattice_coords.hpp"

namespace aq::mask {

namespace {

Json lonlat_json(LonLat p) { return Json::array({p.lon_deg, p.lat_deg}); }

// Whether the pixels under the box's corners and centre are all inside the domain.
bool box_in_domain(const GeoBox& b, const Domain& d, const Lattice& lat, const PoleRotation& rot) {
  const double cx = 0.5 * (b.lon_min_deg + b.lon_max_deg), cy = 0.5 * (b.lat_min_deg + b.lat_max_deg);
  for (const auto& [x, y] : {std::pair{b.lon_min_deg, b.lat_min_deg},
                             {b.lon_max_deg, b.lat_min_deg},
                             {b.lon_min_deg, b.lat_max_deg},
                             {b.lon_max_deg, b.lat_max_deg},
                             {cx, cy}}) {
    double px = 0.0, py = 0.0;
    deg_to_lattice_xy(lat, geographic_to_lattice(rot, {x, y}), px, py);
    if (!on_lattice(lat, px, py)) return false;
    const auto i = static_cast<std::int64_t>(std::floor(px)), j = static_cast<std::int64_t>(std::floor(py));
    if (!d.contains(std::min(i, lat.nx - 1), std::min(j, lat.ny - 1))) return false;
  }
  return true;
}

// The sea pixels (wet at the datum, in Ω_L) not 4-connected through sea to a seed window: water
// below the datum the fill reached across the floodplain (WetArea::inland_sea_*).
void find_inland_sea(WetArea& area, const Lattice& lattice, const PoleRotation& rot, int k) {
  std::vector<PixelIJ> starts;
  for (const SeedInfo& s : area.seeds)
    for (std::int64_t dj = 0; dj < k; ++dj)
      for (std::int64_t di = 0; di < k; ++di) {
        const PixelIJ p{(s.window.i + di) % lattice.nx, s.window.j + dj};
        if (p.j < lattice.ny && area.sea.get(p.i, p.j)) starts.push_back(p);
      }
  Bitmap inland = area.sea;
  const Bitmap reached = flood_fill(area.sea, starts);
  auto& w = inland.words();
  for (std::size_t q = 0; q < w.size(); ++q) w[q] &= ~reached.words()[q];
  area.inland_sea_pixels = inland.count();
  if (area.inland_sea_pixels == 0) return;
  area.inland_sea_components = count_components(inland).count;
  double lon_min = 1e9, lon_max = -1e9, lat_min = 1e9, lat_max = -1e9;
  for (std::int64_t j = 0; j < inland.ny(); ++j)
    for (std::int64_t i = 0; i < inland.nx(); ++i) {
      if (!inland.get(i, j)) continue;
      const LonLat g = lattice_to_geographic(rot, pixel_center_lattice_deg(lattice, {i, j}));
      lon_min = std::min(lon_min, g.lon_deg);
      lon_max = std::max(lon_max, g.lon_deg);
      lat_min = std::min(lat_min, g.lat_deg);
      lat_max = std::max(lat_max, g.lat_deg);
    }
  area.inland_sea_lon_min = lon_min;
  area.inland_sea_lon_max = lon_max;
  area.inland_sea_lat_min = lat_min;
  area.inland_sea_lat_max = lat_max;
}

}  // namespace

PixelWindow classify_window(const Lattice& lattice, const Domain& domain) {
  // Only the domain's box and one level-0 square around it (the open-boundary typing looks one
  // pixel outside the domain): the rest of the lattice stays dry, unsampled. On a window lattice
  // that is the whole window (its padding is one level-0 square).
  PixelWindow w;
  const double pix = lattice.pixel_deg();
  const std::int64_t sq = lattice.pixels_per_square(0);
  const double x_lo =
      lattice.windowed() ? lattice.col_of_lon(domain.lon_min) : (domain.lon_min - lattice.lon0_deg) / pix;
  const double x_hi = x_lo + (domain.lon_max - domain.lon_min) / pix;
  auto i_lo = static_cast<std::int64_t>(std::floor(x_lo)) - sq;
  auto i_hi = static_cast<std::int64_t>(std::ceil(x_hi)) + sq;
  if (!lattice.periodic()) {
    i_lo = std::max<std::int64_t>(0, i_lo);
    i_hi = std::min(lattice.nx, i_hi);
  }
  const double y_s = lattice.row_of_lat(std::max(domain.lat_min, -lattice.lat_max_deg()));
  const double y_n = lattice.row_of_lat(std::min(domain.lat_max, lattice.lat_max_deg()));
  const std::int64_t j_lo = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(y_s)) - sq);
  const std::int64_t j_hi = std::min<std::int64_t>(lattice.ny, static_cast<std::int64_t>(std::ceil(y_n)) + sq);
  if (i_hi - i_lo < lattice.nx) {
    w.col_first = i_lo;
    w.col_count = i_hi - i_lo;
  }
  w.row_first = j_lo;
  w.row_count = std::max<std::int64_t>(0, j_hi - j_lo);
  return w;
}

void warn_inland_sea(const WetArea& area, const Logger& log) {
  if (area.inland_sea_pixels == 0) return;
  log.warn(
      "floodplain: {} pixels of water below the datum in {} piece(s) ({:.2f}..{:.2f}°E, {:.2f}..{:.2f}°N) "
      "are reached only across the floodplain (lakes, lagoons, depressions behind land above the datum): "
      "the models start them wet at 0 m; ADCIRC's fort.13 surface_submergence_state or SCHISM's initial "
      "elevation (elev.ic) starts them dry",
      area.inland_sea_pixels, area.inland_sea_components, area.inland_sea_lon_min, area.inland_sea_lon_max,
      area.inland_sea_lat_min, area.inland_sea_lat_max);
}

std::vector<Passage> passage_table(const Lattice& lattice, const PoleRotation& rot, const Domain* domain) {
  const bool regional = domain != nullptr && domain->regional();
  std::vector<Passage> table;
  for (const Passage& p : critical_passages())
    if (!regional || box_in_domain(p.box, *domain, lattice, rot)) table.push_back(p);
  return table;
}

void mark_carved(std::vector<PassageResult>& passages, const config::MaskOptions& options) {
  for (PassageResult& r : passages)
    for (const std::string& n : options.passages_open)
      if (const Passage* f = find_passage(n); f != nullptr && r.name == f->name) {
        r.carved = true;
        r.note =
            r.note.empty() ? std::string("carved (mask.passages_open)") : "carved (mask.passages_open), but " + r.note;
      }
}

WetArea compute_wet_area(const raster::Bathymetry& bathy, const Lattice& lattice, const PoleRotation& rot,
                         const config::MaskOptions& options, const Logger& log, Report* report,
                         const Domain* domain) {
  const bool regional = domain != nullptr && domain->regional();
  WetArea area;
  {
    StageScope stage("classify", report, log);
    ClassifyOptions co;
    co.min_depth_m = options.min_depth_m;
    co.sampling = options.sampling;
    co.progress = log.progress("classify");
    if (regional && rot.identity()) co.window = classify_window(lattice, *domain);
    if (!regional) check_mercator_caps(bathy, lattice, rot, options.min_depth_m);  // a region is inside the rows
    PixelClasses pc = classify_pixels(bathy, lattice, rot, co);
    area.wet_vertices = std::move(pc.wet_vertices);
    area.wet = std::move(pc.wet);
    area.coastal = std::move(pc.coastal);
    area.classes = {pc.wet_vertex_count, pc.wet_count, pc.coastal_count, pc.dry_count};
    std::string datum;
    if (options.min_depth_m < 0.0) {  // a floodplain: the same pixel rule at the datum, for the sea inside Ω_L
      ClassifyOptions at_datum = co;
      at_datum.min_depth_m = 0.0;
      at_datum.progress = {};
      area.datum_wet = std::move(classify_pixels(bathy, lattice, rot, at_datum).wet);
      area.datum_wet_pixels = area.datum_wet.count();
      datum = fmt::format("; {} wet at the datum", area.datum_wet_pixels);
    }
    stage.done(fmt::format("{}×{} {}pixels of {:g}°: {} wet, {} coastal, {} dry (h = {:g} m, {} rule){}", lattice.nx,
                           lattice.ny, lattice.mercator() ? "Mercator " : "", lattice.pixel_deg(), pc.wet_count,
                           pc.coastal_count, pc.dry_count, options.min_depth_m, options.sampling, datum));
  }
  {
    StageScope stage("fill", report, log);
    KFillResult kf;
    if (regional) {  // water outside the domain is not meshed: the fill sees wet ∩ domain only
      Bitmap wet_in = area.wet;
      auto& w = wet_in.words();
      const auto& d = domain->inside.words();
      for (std::size_t k = 0; k < w.size(); ++k) w[k] &= d[k];
      const auto seeds = regional_seeds(*domain, wet_in, lattice, rot, bathy, options.seeds, log);
      kf = k_cursor_fill(wet_in, lattice, rot, options.cursor, seeds, options.seed_radius_deg, log);
    } else {
      kf = k_cursor_fill(area.wet, lattice, rot, options.cursor, options.seeds, options.seed_radius_deg, log);
    }
    area.filled = std::move(kf.filled);
    area.fill = kf.stats;
    area.seeds = std::move(kf.seeds);
    area.filled_pixels = area.fill.filled_pixels;
    if (regional) {  // the water beyond the domain edge, at the datum: where the mesh is open
      const Bitmap& water = area.datum_wet.nx() > 0 ? area.datum_wet : area.wet;
      area.open = water;
      auto& o = area.open.words();
      const auto& d = domain->inside.words();
      for (std::size_t k = 0; k < o.size(); ++k) o[k] &= ~d[k];
    }
    stage.done(fmt::format("K = {}: {} filled pixels ({:.1f}% of wet), {} wet pixels left out, {} wet components",
                           options.cursor, area.fill.filled_pixels,
                           area.fill.wet_pixels > 0 ? 100.0 * static_cast<double>(area.fill.filled_pixels) /
                                                          static_cast<double>(area.fill.wet_pixels)
                                                    : 0.0,
                           area.fill.wet_left_out, area.fill.wet_components));
  }
  {
    StageScope stage("pinches", report, log);
    area.pinches.removal_requested = options.remove_pinches;
    if (options.remove_pinches) {
      std::vector<PixelIJ> seed_windows;
      for (const SeedInfo& s : area.seeds) seed_windows.push_back(s.window);
      area.pinches.removal = remove_pinches(area.filled, options.cursor, seed_windows);
      area.filled_pixels = area.filled.count();
    }
    if (area.datum_wet.nx() > 0) {  // the sea inside Ω_L (after pinch removal); the rest is floodplain
      area.sea = area.filled;
      auto& w = area.sea.words();
      const auto& d = area.datum_wet.words();
      for (std::size_t k = 0; k < w.size(); ++k) w[k] &= d[k];
      area.floodplain_pixels = area.filled_pixels - area.sea.count();
      find_inland_sea(area, lattice, rot, options.cursor);
      warn_inland_sea(area, log);
    }
    area.pinches.pinches = find_pinches(area.filled);
    locate_pinches(area.pinches.pinches, lattice, rot);
    area.pinches.total = static_cast<std::int64_t>(area.pinches.pinches.size());
    if (options.remove_pinches) {
      const PinchRemovalStats& r = area.pinches.removal;
      stage.done(fmt::format("{} pinch vertices found, {} pixels removed in {} rounds, {} left", r.pinches_found,
                             r.pixels_removed, r.rounds, area.pinches.total));
    } else {
      stage.done(fmt::format("{} pinch vertices (mask.remove_pinches = false)", area.pinches.total));
    }
  }
  // The table's passages (a regional run: those whose box lies in the domain), marked when carved.
  const std::vector<Passage> table = passage_table(lattice, rot, domain);
  if (options.passages && !table.empty()) {
    StageScope stage("passages", report, log);
    area.passages = judge_passages(table, area.filled, lattice, rot);
    mark_carved(area.passages, options);
    int open = 0, closed = 0;
    for (const PassageResult& p : area.passages) {
      open += p.status == PassageStatus::kOpen ? 1 : 0;
      closed += p.status == PassageStatus::kClosed ? 1 : 0;
    }
    stage.done(fmt::format("{} open, {} closed, {} not resolvable", open, closed,
                           static_cast<int>(area.passages.size()) - open - closed));
  }
  if (report != nullptr) (*report)["mask"] = wet_area_json(area, options);
  return area;
}

Json wet_area_json(const WetArea& area, const config::MaskOptions& options, std::size_t max_pinches) {
  Json j;
  j["min_depth_m"] = options.min_depth_m;
  j["cursor"] = options.cursor;
  j["sampling"] = std::string(name_of(options.sampling));
  j["lattice"] = {{"nx", area.wet.nx()}, {"ny", area.wet.ny()}};
  if (options.min_depth_m < 0.0)  // README "A storm-surge mesh"
    j["floodplain"] = {{"top_m", -options.min_depth_m},
                       {"datum_wet_pixels", area.datum_wet_pixels},
                       {"floodplain_pixels", area.floodplain_pixels},
                       {"sea_pixels", area.filled_pixels - area.floodplain_pixels},
                       {"inland_sea_pixels", area.inland_sea_pixels},
                       {"inland_sea_components", area.inland_sea_components}};
  if (area.inland_sea_pixels > 0)
    j["floodplain"]["inland_sea_box_deg"] = {area.inland_sea_lon_min, area.inland_sea_lon_max, area.inland_sea_lat_min,
                                             area.inland_sea_lat_max};
  j["classes"] = {{"wet_vertices", area.classes.wet_vertices},
                  {"wet", area.classes.wet},
                  {"coastal", area.classes.coastal},
                  {"dry", area.classes.dry}};
  const FillStats& f = area.fill;
  j["fill"] = {{"all_wet_windows", f.all_wet_windows},
               {"reached_windows", f.reached_windows},
               {"filled_pixels", f.filled_pixels},
               {"filled_pixels_final", area.filled_pixels},
               {"wet_pixels", f.wet_pixels},
               {"wet_left_out", f.wet_left_out},
               {"wet_components", f.wet_components},
               {"wet_components_filled", f.wet_components_filled},
               {"largest_wet_component", f.largest_wet_component}};
  Json seeds = Json::array();
  for (const SeedInfo& s : area.seeds) {
    seeds.push_back(Json{{"index", s.index},
                         {"requested", lonlat_json(s.requested)},
                         {"moved", s.moved},
                         {"moved_deg", s.moved_deg},
                         {"window", {s.window.i, s.window.j}},
                         {"window_center", lonlat_json(s.window_center)},
                         {"windows_reached", s.windows_reached},
                         {"same_fill_as", s.same_fill_as}});
  }
  j["seeds"] = seeds;
  Json pin;
  pin["total"] = area.pinches.total;
  Json list = Json::array();
  for (std::size_t k = 0; k < area.pinches.pinches.size() && k < max_pinches; ++k) {
    const Pinch& p = area.pinches.pinches[k];
    list.push_back(Json{{"vertex", {p.vertex.i, p.vertex.j}},
                        {"pattern", pinch_pattern_name(p.pattern)},
                        {"lattice", lonlat_json(p.lattice_pos)},
                        {"geographic", lonlat_json(p.geographic)}});
  }
  pin["listed"] = list;
  pin["remove_pinches"] = area.pinches.removal_requested;
  if (area.pinches.removal_requested) {
    const PinchRemovalStats& r = area.pinches.removal;
    pin["removal"] = {{"pinches_found", r.pinches_found},
                      {"rounds", r.rounds},
                      {"pixels_chosen", r.pixels_chosen},
                      {"pixels_removed", r.pixels_removed},
                      {"unresolved", r.unresolved}};
  }
  j["pinches"] = pin;
  j["passages"] = to_json(area.passages);
  return j;
}

}  // namespace aq::mask

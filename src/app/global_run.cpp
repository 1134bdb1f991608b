// SPDX-License-Identifier: GPL-3.0-or-later
// The global pipeline core (see global_run.hpp).
#include "app/global_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <unordered_map>

#include "core/error.hpp"
#include "core/timer.hpp"
#include "core/types.hpp"
#include "mask/carving.hpp"
#include "mask/domain.hpp"
#include "mask/dropped_seas.hpp"
#include "mask/global_run_file.hpp"
#include "mask/passages.hpp"
#include "mesh/boundaries.hpp"
#include "mesh/build_mesh.hpp"
#include "mesh/floodplain.hpp"
#include "mesh/open_snap.hpp"
#include "mesh/time_step.hpp"
#include "mesh_files/element_kinds.hpp"
#include "quadtree/build_leaves.hpp"
#include "size/size_field.hpp"
#ifdef AQ_HAVE_MPI
#include "forest/comm.hpp"
#include "forest/mpi_session.hpp"
#include "forest/pipeline.hpp"
#endif

namespace aq::app {

namespace {

// The memory model of a global run (README "Big rasters"; the estimate is printed before the run
// and written to the report beside the measured peak):
//   raster   held whole: 4 bytes per raster cell (16 with bicubic slopes) and a 64 MB read chunk;
//            streamed: two bands of rows (~64 MB each as float32) and their read buffers;
//   lattice  kLatticeBitsPerPixel: the wet-vertex, class, fill and quadtree bitmaps alive at the
//            fill/quadtree peak (about 7 full-lattice bitmaps measured at 15"; 8 bits = 1 byte per
//            lattice pixel);
//   mesh     kMeshBytesPerTriangle per triangle: the lattice mesh (about 90 bytes per triangle
//            with its nodes and squares) and, at the write stage's peak, the geographic copy of
//            an unrotated mesh (its pole cap; 64) and the shape quality's arrays (33), or the
//            statistics stage's edge arrays; 215 fits the 15" run with every size term
//            (29.3 million triangles: 6.58 GB measured at the quality step); a rotated mesh
//            (no copy) peaks lower, in the statistics stage.
// `aquatoria mesh` frees the bitmaps before the mesh stage (unless it writes the global run
// file), so its peak is the larger of the lattice and mesh parts; the other callers keep them
// beside the mesh (the sum). The triangle count is guessed before the run as
// kTrianglesPerSqrtPixel·√(nx·ny): the refinement follows the coast, whose length in pixels
// grows like the side of the lattice (1': 5.3 million triangles, 15": 20.1 million on ETOPO5
// resamples); the size field's terms move it (the 15" run with every term: 29.3 million).
// Tolerance: with the mesh's own triangle count (report memory.estimate_bytes_for_mesh) the
// measured peak is within 25 % of the model for runs whose mesh part exceeds 0.4 GB
// (StreamCli.EstimateForTheMeshIsWithinItsToleranceOfThePeak, ETOPO5 at 1.875': 0.80 GB
// measured, 0.80 modelled); the guessed count adds its own error (the 15" run with every size
// term has 37 % more triangles than the guess). Measured peak / estimate for the mesh's count
// (2026-11-28): 15" with every size term 6.58 / 6.80 GB (before the run, from the guessed count:
// 5.10); global_tides on the 1' raster (rotated: no copy) 2.94 / 3.09 GB.
//   forest   (quadtree.engine = "forest") instead of the lattice bitmaps, in two steps, because
//            what it holds follows the coast and the size field, which no header tells:
//            before the run, per rank, kForestBytesPerPatch for every patch of its trees (p4est's
//            quadrant, the patch's states and their ghosts) beside the raster and the program —
//            the part known from the lattice; the mesh's part is not guessed from the pixel count
//            (350·√pixels assumes a coast at the finest level across a global lattice: 34 million
//            triangles for the 1/9" coast, which made 8.5 million, 12 GB said for 2.65 GB used).
//            Once the leaves are known (rank 0 has gathered them; printed before the mesh),
//            every rank's estimate is what it holds then (its resident set: the program, the
//            raster, the tile cache, the patches' states, on rank 0 the gathered leaves at
//            kForestGatherBytesPerLeaf), or its peak so far if larger, and on rank 0
//            kMeshBytesPerTriangle for the triangles the leaves' templates make (an exact count:
//            forest::RankMemory); the run stops there if that is above the limit.
constexpr double kLatticeBitsPerPixel = 8.0;
constexpr double kForestBytesPerPatch = 200.0;
constexpr double kForestGatherBytesPerLeaf = 27.0;
// The forest reads a raster in tiles (raster::OpenOptions::tiles_above_bytes) above this.
constexpr std::int64_t kForestTilesAboveBytes = std::int64_t{1} << 30;
// A floodplain run (mask.min_depth_m < 0) keeps 3 bitmaps more: the pixels wet at the datum, the
// sea inside Ω_L and, regional, the open water (mask/wet_area.hpp).
constexpr double kFloodplainBitsPerPixel = 3.0;
constexpr double kMeshBytesPerTriangle = 215.0;
constexpr double kTrianglesPerSqrtPixel = 350.0;
constexpr std::int64_t kBaseBytes = 230'000'000;  // program, GDAL cache, the writers' chunk buffers, small tables

// Estimates are computed in floating point and saturate at 2^62 bytes (4.6 EB): a 1" lattice
// at L = 12 overflowed the old integer product into a negative estimate.
std::int64_t saturate(double x) { return x < 4.6e18 ? static_cast<std::int64_t>(x) : std::int64_t{1} << 62; }

double estimate_lattice_bytes_f(const Lattice& l) {
  const double words = std::ceil(static_cast<double>(l.nx) / 64.0) * (static_cast<double>(l.ny) + 1.0);
  return kLatticeBitsPerPixel * words * 8.0;
}

std::int64_t estimate_lattice_bytes(const Lattice& l) { return saturate(estimate_lattice_bytes_f(l)); }

std::int64_t estimate_triangles(const Lattice& l) {
  return saturate(kTrianglesPerSqrtPixel * std::sqrt(static_cast<double>(l.nx) * static_cast<double>(l.ny)));
}

double gb(std::int64_t bytes) { return static_cast<double>(bytes) / 1e9; }

// Hidden test knobs (not configuration keys): AQ_RASTER_STREAMING = always | never | auto,
// AQ_RASTER_BAND_ROWS = rows per band and AQ_RASTER_MAP = never (streamed through GDAL reads,
// not the file map), so that tests can compare the streamed and whole paths;
// AQ_RASTER_WHOLE=1 reads a regional run's rasters whole (tests compare with the window read);
// AQ_RASTER_TILES_ABOVE (below) reads them in tiles.
void apply_test_knobs(raster::OpenOptions& ro) {
  if (const char* s = std::getenv("AQ_RASTER_WHOLE"); s != nullptr && std::string(s) == "1")
    ro.lon_min = ro.lon_max = ro.lat_min = ro.lat_max = std::numeric_limits<double>::quiet_NaN();
  if (const char* s = std::getenv("AQ_RASTER_STREAMING")) {
    const std::string v = s;
    if (v == "always") ro.streaming = raster::OpenOptions::Streaming::kAlways;
    if (v == "never") ro.streaming = raster::OpenOptions::Streaming::kNever;
  }
  if (const char* s = std::getenv("AQ_RASTER_BAND_ROWS")) ro.band_rows = std::max<std::int64_t>(0, std::atoll(s));
  // AQ_RASTER_TILES_ABOVE = bytes: read rasters above that size in tiles (tests compare with held).
  if (const char* s = std::getenv("AQ_RASTER_TILES_ABOVE"))
    ro.tiles_above_bytes = std::max<std::int64_t>(0, std::atoll(s));
  if (const char* s = std::getenv("AQ_RASTER_MAP"); s != nullptr && std::string(s) == "never") ro.map_file = false;
}

// Level-0 squares of padding around the domain on a window lattice (never inside the domain, so
// never meshed: every wrap of I and every pole-row assumption of the global code lands there).
constexpr std::int64_t kWindowPadSquares = 1;

// The window lattice of a regional run (README "Regional FE meshes"): the domain's snapped box
// (or a polygon's bounding box snapped outward) and kWindowPadSquares level-0 squares on every
// side, in whole level-0 squares of the global lattice; all columns when that spans 360°. With
// pole rotation the global lattice stays (the rotated lattice's box is no lon/lat box), and so it
// does when AQ_GLOBAL_LATTICE=1 (a hidden test knob: tests compare the two).
Lattice window_lattice(const config::GlobalConfig& c, const Lattice& g, const PoleRotation& rot, std::string& note) {
  if (!c.domain.regional()) return g;
  if (!rot.identity()) {
    note = "rotation.enabled = true: the rotated lattice's box is no lon/lat box";
    return g;
  }
  if (const char* s = std::getenv("AQ_GLOBAL_LATTICE"); s != nullptr && std::string(s) == "1") {
    note = "AQ_GLOBAL_LATTICE=1";
    return g;
  }
  const mask::DomainExtent e = mask::domain_extent(c.domain, g);
  const std::int64_t sq = g.pixels_per_square(0), pad = kWindowPadSquares * sq;
  const double pix = g.pixel_deg(), fsq = static_cast<double>(sq);
  const double x_w = (e.lon_min - g.lon0_deg) / pix, x_e = (e.lon_max - g.lon0_deg) / pix;
  const std::int64_t i0 = static_cast<std::int64_t>(std::floor(x_w / fsq + 1e-9)) * sq - pad;
  const std::int64_t i1 = static_cast<std::int64_t>(std::ceil(x_e / fsq - 1e-9)) * sq + pad;
  const double y_s = g.row_of_lat(std::max(e.lat_min, -g.lat_max_deg()));
  const double y_n = g.row_of_lat(std::min(e.lat_max, g.lat_max_deg()));
  const std::int64_t j0 = static_cast<std::int64_t>(std::floor(y_s / fsq + 1e-9)) * sq - pad;
  const std::int64_t j1 = static_cast<std::int64_t>(std::ceil(y_n / fsq - 1e-9)) * sq + pad;
  return Lattice::window(g, i0, i1 - i0, j0, j1 - j0);
}

}  // namespace

// base + raster + bitmaps and mesh: their sum while the bitmaps stay, else the larger.
static double model_bytes(const GlobalSetup& s, double mesh_bytes) {
  const auto lattice = static_cast<double>(s.lattice_bytes);
  if (s.forest)  // before the leaves: the program, the raster and a rank's patches (the mesh comes later)
    return static_cast<double>(kBaseBytes) + static_cast<double>(s.raster.bytes) + lattice;
  return static_cast<double>(kBaseBytes) + static_cast<double>(s.raster.bytes) +
         (s.masks_kept ? lattice + mesh_bytes : std::max(lattice, mesh_bytes));
}

// The forest's patches on one of `ranks` ranks, known before the run (the memory model above).
static double forest_bytes(const Lattice& l, int ranks) {
  const int plog = std::min(l.levels, 7);
  const double p = static_cast<double>(std::int64_t{1} << plog);
  const double patches = std::ceil(static_cast<double>(l.nx) / p) * std::ceil(static_cast<double>(l.ny) / p);
  return kForestBytesPerPatch * patches / static_cast<double>(std::max(1, ranks));
}

// The lattice (a window lattice for a regional run), the rotation, the memory limit and the
// estimates of the lattice bitmaps and the mesh; refuses a dense lattice whose bitmaps alone pass
// the limit.
static void plan_lattice(GlobalSetup& s, const config::GlobalConfig& c, const SetupOptions& o) {
  s.masks_kept = o.keep_masks;
  s.lattice = c.quadtree.lattice == LatticeKind::kMercator
                  ? Lattice::make_mercator(c.quadtree.step_deg, c.quadtree.levels, c.quadtree.lon0_deg,
                                           c.quadtree.mercator_lat_max_deg)
                  : Lattice::make(c.quadtree.step_deg, c.quadtree.levels, c.quadtree.lon0_deg);
  s.rotation = c.rotation.enabled ? PoleRotation(c.rotation.pole_lon_deg, c.rotation.pole_lat_deg) : PoleRotation();
  s.global_lattice = s.lattice;
  if (o.allow_window) {
    s.lattice = window_lattice(c, s.global_lattice, s.rotation, s.lattice_note);
  } else if (c.domain.regional()) {
    s.lattice_note = "this command works on the global lattice";
  }
  // A tiny limit is a limit (at least 1 byte), not 0 = "80% of RAM".
  s.memory_limit_bytes = c.input.max_memory_gb > 0
                             ? std::max<std::int64_t>(1, saturate(c.input.max_memory_gb * 1e9))
                             : static_cast<std::int64_t>(0.8 * static_cast<double>(physical_memory_bytes()));
  s.forest = c.quadtree.engine == config::QuadtreeEngine::kForest;
  s.ranks = std::max(1, o.ranks);
  s.triangles_guess = estimate_triangles(s.lattice);
  s.lattice_bytes = estimate_lattice_bytes(s.lattice);
  if (c.mask.min_depth_m < 0.0)  // a floodplain: the pixels at the datum, the sea and (regional) the open water
    s.lattice_bytes = saturate(estimate_lattice_bytes_f(s.lattice) * (kLatticeBitsPerPixel + kFloodplainBitsPerPixel) /
                               kLatticeBitsPerPixel);
  if (s.forest) s.lattice_bytes = saturate(forest_bytes(s.lattice, s.ranks));
  s.mesh_bytes = saturate(kMeshBytesPerTriangle * static_cast<double>(s.triangles_guess));
  if (s.forest) s.triangles_guess = s.mesh_bytes = 0;  // no guess: estimated once the leaves are known
  const Lattice& lat = s.lattice;
  if (!s.forest && s.memory_limit_bytes > 0 && s.lattice_bytes > s.memory_limit_bytes) {
    throw ConfigError(fmt::format(
        "quadtree.levels = {} with quadtree.step_deg = {}: the {} x {} pixel lattice needs about {:.1f} GB of "
        "bitmaps, more than the {:.3g} GB allowed (input.max_memory_gb); use fewer levels or a larger Δ0",
        lat.levels, lat.step0_deg, lat.nx, lat.ny, estimate_lattice_bytes_f(lat) / 1e9,
        static_cast<double>(s.memory_limit_bytes) / 1e9));
  }
}

// The lon/lat box [lon_min, lon_max, lat_min, lat_max] the rasters are read over (NaN: whole).
static std::array<double, 4> raster_window(const GlobalSetup& s, const config::GlobalConfig& c) {
  // A regional run reads each raster over the window lattice (the domain's lon/lat box and one
  // level-0 square more on every side) and two pixels more (README "Regional FE meshes"): the
  // classification (mask/wet_area) samples the window, and nothing else samples outside the
  // domain. A box on a rotated lattice: its geographic box and a margin (below). Not a polygon on
  // a rotated lattice (read whole: its pixels are tested by their geographic centres), nor bicubic sampling (its C2 spline couples every cell of
  // a row: a window changes the slopes), nor a source above another one with input.blend_km > 0
  // (its distance field is computed over the whole raster grid).
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 4> window{kNaN, kNaN, kNaN, kNaN};
  if (c.domain.regional() && c.input.interpolation == config::Interpolation::kBilinear &&
      (s.rotation.identity() || c.domain.resolved == config::DomainKind::kBox)) {
    // The window lattice's extent (the domain and its padding, which the classification samples)
    // and two pixels more; on the global lattice (AQ_GLOBAL_LATTICE=1) the domain's extent and
    // one level-0 square and two pixels more, which is what it classifies.
    const Lattice& w = s.lattice;
    const double m = 2.0 * w.pixel_deg();
    if (w.windowed()) {
      window = {w.lon_of(0) - m, w.lon_of(w.nx) + m, std::max(-90.0, w.lat_of(0) - m),
                std::min(90.0, w.lat_of(w.ny) + m)};
    } else if (!s.rotation.identity()) {
      window = mask::rotated_box_window(c.domain.box, w, s.rotation);
    } else {
      const mask::DomainExtent d = mask::domain_extent(c.domain, w);
      const double mg = w.step0_deg + m;
      window = {d.lon_min - mg, d.lon_max + mg, std::max(-90.0, d.lat_min - mg), std::min(90.0, d.lat_max + mg)};
    }
    if (window[1] - window[0] >= 360.0) window[0] = window[1] = kNaN;
  }
  return window;
}

// The rasters: their headers only (nothing is read), whole or streamed, and the whole estimate.
// Several sources (input.paths) add up; a source above another with input.blend_km > 0 also
// holds its distance field (4 bytes per cell) and, while it is computed, 9 bytes per cell more.
static void plan_sources(GlobalSetup& s, const config::GlobalConfig& c, const std::array<double, 4>& window) {
  const std::vector<std::string> paths = c.input.sources();
  for (std::size_t k = 0; k < paths.size(); ++k) {
    raster::OpenOptions ro = raster_options(c.input, s.memory_limit_bytes);
    ro.path = paths[k];
    // The forest reads a raster too large to hold in tiles where it samples (a fine tile stack).
    if (s.forest) ro.tiles_above_bytes = kForestTilesAboveBytes;
    ro.allow_streaming = s.rotation.identity() && c.mask.sampling == config::Sampling::kVertex &&
                         c.quadtree.depth_rules.empty() && !c.domain.regional();
    if (!std::isnan(window[2]) && !(c.input.blend_km > 0.0 && k + 1 < paths.size())) {
      ro.lon_min = window[0];
      ro.lon_max = window[1];
      ro.lat_min = window[2];
      ro.lat_max = window[3];
    }
    apply_test_knobs(ro);
    raster::RasterPlan plan;
    try {
      plan = raster::plan_raster(ro);
    } catch (const InputError& e) {
      if (c.input.paths.empty()) throw;
      throw InputError(fmt::format("input.paths[{}]: {}", k, e.what()));
    }
    if (c.input.blend_km > 0.0 && k + 1 < paths.size())
      plan.bytes += 13 * raster::estimate_raster_bytes(plan.width, plan.height) / 4;
    if (k == 0) {
      s.raster = plan;
      s.raster_options = ro;
    } else {
      s.raster.bytes += plan.bytes;
      if (plan.streamed && !s.raster.streamed) {
        s.raster.streamed = true;
        s.raster.block_rows = plan.block_rows;
        s.raster.band_rows = plan.band_rows;
      }
    }
    s.source_options.push_back(ro);
    s.source_plans.push_back(plan);
  }
}

// The whole estimate against input.max_memory_gb (ConfigError naming the key and why the raster
// is held whole where it is).
static void check_memory_estimate(GlobalSetup& s, const config::GlobalConfig& c) {
  s.estimate_bytes = saturate(model_bytes(s, static_cast<double>(s.mesh_bytes)));
  if (s.memory_limit_bytes > 0 && s.estimate_bytes > s.memory_limit_bytes) {
    std::string why;
    if (!s.raster.streamed && s.raster.bytes > raster::kStreamAboveBytes) {
      why = !s.rotation.identity()                         ? " (rotation.enabled = true holds the raster whole)"
            : c.mask.sampling != config::Sampling::kVertex ? " (mask.sampling = \"area\" holds the raster whole)"
            : !c.quadtree.depth_rules.empty()              ? " (quadtree.depth_rules hold the raster whole)"
            : c.input.interpolation != config::Interpolation::kBilinear
                ? " (input.interpolation = \"bicubic\" holds the raster whole)"
                : "";
    }
    throw ConfigError(
        fmt::format("the run is estimated to need {:.2f} GB (raster {:.2f} GB {}{}, {} {:.2f} GB, {}), "
                    "more than input.max_memory_gb = {:.2f} GB; nothing was read",
                    gb(s.estimate_bytes), gb(s.raster.bytes), s.raster.streamed ? "streamed" : "held whole", why,
                    s.forest ? "the forest's patches per rank" : "lattice bitmaps", gb(s.lattice_bytes),
                    s.forest ? std::string("the mesh not yet counted: it follows the leaves")
                             : fmt::format("mesh {:.2f} GB", gb(s.mesh_bytes)),
                    gb(s.memory_limit_bytes)));
  }
}

GlobalSetup prepare_global_run(const config::GlobalConfig& c, const SetupOptions& o) {
  GlobalSetup s;
  mask::check_passage_names(c.mask);  // a misspelt passage fails before anything is read
  plan_lattice(s, c, o);
  plan_sources(s, c, raster_window(s, c));
  check_memory_estimate(s, c);
  return s;
}

std::int64_t estimate_bytes_for(const GlobalSetup& s, std::int64_t triangles) {
  if (s.forest)  // rank 0 with the mesh: the same model as the estimate once the leaves are known
    return saturate(model_bytes(s, 0.0) + kMeshBytesPerTriangle * static_cast<double>(triangles));
  return saturate(model_bytes(s, kMeshBytesPerTriangle * static_cast<double>(triangles)));
}

Json memory_json(const GlobalSetup& s, std::int64_t triangles) {
  Json j{{"estimate_bytes", s.estimate_bytes},        {"estimate_raster_bytes", s.raster.bytes},
         {"estimate_lattice_bytes", s.lattice_bytes}, {"estimate_mesh_bytes", s.mesh_bytes},
         {"estimate_triangles", s.triangles_guess},   {"limit_bytes", s.memory_limit_bytes},
         {"raster_streamed", s.raster.streamed},      {"raster_block_rows", s.raster.block_rows},
         {"raster_band_rows", s.raster.band_rows},    {"masks_kept", s.masks_kept},
         {"peak_rss_bytes", peak_rss_bytes()}};
  if (triangles > 0) j["estimate_bytes_for_mesh"] = estimate_bytes_for(s, triangles);
  return j;
}

void log_memory_estimate(const GlobalSetup& s, const Logger& log) {
  if (s.forest) {
    log.info(
        "memory: estimate before the data {:.2f} GB per rank ({} ranks) of {:.2f} GB allowed (input.max_memory_gb): "
        "raster {:.2f} GB {}, the forest's patches {:.2f} GB per rank; the leaves and the mesh on rank 0 follow "
        "the coast: estimated again once the leaves are known",
        gb(s.estimate_bytes), s.ranks, gb(s.memory_limit_bytes), gb(s.raster.bytes),
        s.raster.streamed ? fmt::format("streamed in bands of {} rows", s.raster.band_rows) : std::string("held whole"),
        gb(s.lattice_bytes));
    return;
  }
  log.info(
      "memory: estimate {:.2f} GB of {:.2f} GB allowed (input.max_memory_gb): raster {:.2f} GB {}, lattice "
      "bitmaps {:.2f} GB, mesh {:.2f} GB (~{} triangles){}",
      gb(s.estimate_bytes), gb(s.memory_limit_bytes), gb(s.raster.bytes),
      s.raster.streamed ? fmt::format("streamed in bands of {} rows", s.raster.band_rows) : std::string("held whole"),
      gb(s.lattice_bytes), gb(s.mesh_bytes), s.triangles_guess,
      s.masks_kept ? "" : "; the bitmaps go before the mesh, so the larger of the two counts");
}

raster::OpenOptions raster_options(const config::InputOptions& input, std::int64_t max_memory_bytes) {
  raster::OpenOptions ro;
  ro.path = input.path;
  ro.variable = input.variable;
  ro.band = input.band;
  ro.positive_down = input.positive_down;
  ro.max_abs_elevation_m = input.max_abs_elevation_m;
  ro.interpolation = input.interpolation;
  ro.max_memory_bytes = max_memory_bytes;
  return ro;
}

std::filesystem::path global_run_file_path(const config::GlobalConfig& c) {
  return std::filesystem::path(c.output.dir) / (c.output.name + ".tif");
}

static void warn_lattice_finer_than_data(const Lattice& lat, double dlon, double dlat, const config::GlobalConfig& c,
                                  const Logger& log, Report* report) {
  const double pixel = lat.pixel_deg(), cell = std::min(dlon, dlat);
  if (!(pixel < cell * (1.0 - 1e-9))) return;
  // The lattice's rows: on the Mercator lattice a pixel spans less latitude towards the poles, so
  // it is the longitude side that is compared (the longer one everywhere).
  const auto pixels = static_cast<double>(lat.nx) * static_cast<double>(lat.ny);
  log.warn("lattice finer than its data: {:.4g}' pixels on a {:.4g}' raster ({:.3g} pixels per raster cell side; all "
           "{:.4g} million pixels of the {} lattice, everywhere the raster covers): the finest quadtree levels "
           "resolve interpolation, not bathymetry. quadtree.levels = {} or quadtree.step_deg = {} set the pixel; "
           "input.path a finer raster",
           pixel * 60.0, cell * 60.0, cell / pixel, pixels / 1e6, lat.kind_name(), c.quadtree.levels,
           c.quadtree.step_deg);
  if (report != nullptr)
    (*report)["warnings"]["lattice_finer_than_data"] =
        Json{{"pixel_deg", pixel}, {"raster_deg", cell}, {"pixels_per_raster_cell", cell / pixel}, {"pixels", pixels}};
}

static void warn_threshold_depth_nodes(const mesh::Mesh& m, double h, const Logger& log, Report* report) {
  // Nodes whose elevation is exactly the threshold −h: "wet" only by the rule d ≤ −h. ETOPO-class
  // rasters give 0 m over ice shelves (Ross, Filchner–Ronne) and some flats: at h = 0 those are
  // meshed as ocean.
  std::int64_t at = 0, south = 0;
  double lon_min = 1e9, lon_max = -1e9, lat_min = 1e9, lat_max = -1e9;
  for (std::size_t k = 0; k < m.depth_m.size(); ++k) {
    if (m.depth_m[k] != -h) continue;
    ++at;
    if (m.lat_deg[k] < -77.0) ++south;
    lon_min = std::min(lon_min, m.lon_deg[k]);
    lon_max = std::max(lon_max, m.lon_deg[k]);
    lat_min = std::min(lat_min, m.lat_deg[k]);
    lat_max = std::max(lat_max, m.lat_deg[k]);
  }
  const auto n = static_cast<std::int64_t>(m.depth_m.size());
  if (report != nullptr)
    (*report)["warnings"]["nodes_at_threshold_depth"] = Json{{"h_m", h}, {"nodes", at}, {"south_of_77S", south}};
  // "Over large areas": at least 100 nodes and 0.1 % of the mesh.
  if (at < 100 || static_cast<double>(at) < 1e-3 * static_cast<double>(n)) return;
  log.warn("{} of {} mesh nodes ({:.2g} %) sit at exactly the threshold depth {} m (wet only by d <= -h), {} of them "
           "south of 77°S{}; they span {:.1f}..{:.1f}°E, {:.1f}..{:.1f}°N. mask.min_depth_m > {} leaves them dry",
           at, n, 100.0 * static_cast<double>(at) / static_cast<double>(n), h, south,
           h == 0.0 ? " (ice shelves have 0 m in ETOPO-class rasters)" : "", lon_min, lon_max, lat_min, lat_max, h);
}

// The carving of passages, channels and blockages (mask/carving.hpp): planned on the raw raster,
// then installed on it, so that every later sample (classification, node depths, size field,
// pictures) sees the carved bathymetry. Nothing to do (no stage line) when nothing is asked.
static void carve(GlobalRun& run, const config::GlobalConfig& c, const Logger& log, Report* report) {
  const config::MaskOptions& m = c.mask;
  if (m.passages_open.empty() && m.transects.empty() && m.channels.empty()) return;
  StageScope stage("carve", report, log);
  run.carving = mask::plan_carving(m, run.setup.lattice, run.setup.rotation, *run.bathy);
  run.bathy->set_edits(run.carving.edits);
  for (const std::string& line : mask::describe_carving(run.carving)) log.info("carve: {}", line);
  if (report != nullptr) (*report)["carving"] = mask::carving_json(run.carving);
  std::size_t passages = 0, channels = 0, blockages = 0;
  for (const mask::CarvedLine& l : run.carving.lines) {
    passages += l.kind == mask::LineKind::kPassage ? 1 : 0;
    channels += l.kind == mask::LineKind::kChannel ? 1 : 0;
    blockages += l.kind == mask::LineKind::kBlockage ? 1 : 0;
  }
  stage.done(
      fmt::format("{} passage(s) and {} channel(s) carved open, {} blockage(s) kept dry, before the "
                  "classification (K = {}, h = {:g} m)",
                  passages, channels, blockages, m.cursor, m.min_depth_m));
}

// Every wet component the fill left out above mask.warn_dropped_km2, named, with its area, what
// cut it and the key that keeps it (mask/dropped_seas.hpp); all of them in the report.
// `domain`: the run's domain with its pixel bitmap (default: run.domain).
static void warn_dropped_seas(GlobalRun& run, const config::GlobalConfig& c, const Logger& log, Report* report,
                              const mask::Domain* domain = nullptr) {
  StageScope stage("dropped", report, log);
  const mask::WetArea& a = run.area;
  const mask::DroppedSeas d =
      mask::find_dropped_seas(a.wet, a.filled, run.setup.lattice, run.setup.rotation, c.mask.cursor,
                              c.mask.warn_dropped_km2, c.mask.passages_open, domain != nullptr ? domain : &run.domain);
  for (const mask::DroppedSea& s : d.large) log.warn("dropped: {}", mask::describe(s, c.mask.cursor));
  if (report != nullptr) (*report)["mask"]["dropped"] = mask::dropped_json(d);
  double large = 0.0;
  for (const mask::DroppedSea& s : d.large) large += s.area_km2;
  stage.done(
      fmt::format("{} wet component(s) left out by the fill, {:.4g} km² in all; {} above mask.warn_dropped_km2 = "
                  "{:g} km² ({:.4g} km²) named above",
                  d.components, d.area_km2, d.large.size(), c.mask.warn_dropped_km2, large));
}

// A seed whose fill does not join the first seed's: the mesh has separate parts (each typed as a
// mesh of its own: its outer coast mainland, mesh/boundaries.hpp). Intended for a closed sea, an
// accident otherwise: said, with the pieces' sizes.
static void warn_separate_seeds(GlobalRun& run, const config::GlobalConfig& c, const Logger& log, Report* report) {
  const mask::WetArea& a = run.area;
  Json parts = Json::array();
  for (const mask::SeedInfo& s : a.seeds) {
    if (s.index == 0 || s.same_fill_as >= 0 || s.windows_reached == 0) continue;
    log.warn(
        "seeds: mask.seeds[{}] = ({}, {}) fills {} cursor window(s) not connected to the part of mask.seeds[0] "
        "at K = {}: the mesh has a separate part there (meshed apart, its own coast mainland); if it should join "
        "the rest, open the passage between them (mask.passages_open, mask.transects) or use a smaller mask.cursor",
        s.index, s.requested.lon_deg, s.requested.lat_deg, s.windows_reached, c.mask.cursor);
    parts.push_back(Json{{"seed", s.index}, {"windows", s.windows_reached}});
  }
  if (report != nullptr && !parts.empty()) (*report)["warnings"]["seeds_in_separate_parts"] = parts;
}

// One source for the log: "source 1 (highest priority) PATH: W x H, 0.5', whole (N MB), lon..lon, lat..lat".
static std::string source_line(const raster::Bathymetry& b, std::size_t k) {
  const auto& i = b.info();
  const double lon1 = i.lon_first + static_cast<double>(i.ncols - 1) * i.dlon;
  const double lat1 = i.lat_first + static_cast<double>(i.nrows - 1) * i.dlat;
  return fmt::format("source {}{} {}: {} x {}, {:.4g}' x {:.4g}', {} registration, {} ({} MB); {}, {:.4f}..{:.4f}°N",
                     k + 1, k == 0 ? " (highest priority)" : "", i.path, i.ncols, i.nrows, i.dlon * 60.0,
                     i.dlat * 60.0, i.registration,
                     i.tiled ? "in tiles on demand, cache" : i.streamed ? "streamed" : "held whole",
                     i.memory_bytes >> 20,
                     i.global_lon ? std::string("all longitudes") : fmt::format("{:.4f}..{:.4f}°E", i.lon_first, lon1),
                     i.lat_first, lat1);
}

// "window 1234 x 567 cells of 21600 x 10801 (2.7 MB)" for a raster read over a window, else "".
static std::string window_note(const raster::RasterInfo& i) {
  if (i.streamed || (i.held_cols >= i.ncols && i.held_rows >= i.nrows)) return {};
  return fmt::format("window {} x {} cells of {} x {} from column {} row {} ({} bytes)", i.held_cols, i.held_rows,
                     i.ncols, i.nrows, i.held_col_first, i.held_row_first, i.memory_bytes);
}

// One source for the report's input.sources (its node counts are added after the mesh).
static Json source_json(const raster::Bathymetry& b) {
  const auto& i = b.info();
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(i.path, ec);
  return Json{{"path", i.path},
              {"driver", i.driver},
              {"variable", i.variable},
              {"file_bytes", ec ? Json() : Json(static_cast<std::int64_t>(bytes))},
              {"columns", i.ncols},
              {"rows", i.nrows},
              {"resolution_deg", i.dlon},
              {"resolution_lat_deg", i.dlat},
              {"registration", i.registration},
              {"lon_first_deg", i.lon_first},
              {"lat_first_deg", i.lat_first},
              {"global_lon", i.global_lon},
              {"min_m", i.min_m},
              {"max_m", i.max_m},
              {"streamed", i.streamed},
              {"mapped", i.mapped},
              {"memory_bytes", i.memory_bytes}};
}

// The read stage, the lattice's and the domain's lines and report sections: what both engines do
// first.
static void open_inputs(GlobalRun& run, const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                        Report* report, bool dense_domain = true) {
  const Lattice& lat = setup.lattice;
  const PoleRotation& rot = setup.rotation;
  const std::int64_t limit = setup.memory_limit_bytes, need = setup.lattice_bytes;

  std::vector<raster::OpenOptions> ros = setup.source_options;
  for (raster::OpenOptions& ro : ros) ro.max_memory_bytes = limit > need ? limit - need : limit;
  StageScope read_stage("read", report, log);
  run.bathy.emplace(raster::Bathymetry::open_sources(ros, c.input.blend_km, log));
  const raster::Bathymetry& bathy = *run.bathy;
  const auto& ri = bathy.info();
  const std::size_t nsources = bathy.source_count();
  for (std::size_t k = 0; k < nsources; ++k) {
    const raster::RasterInfo& si = bathy.source(k).info();
    if (const std::string w = window_note(si); !w.empty()) {
      log.info("read: {}: {} (the domain's box and one level-0 square around it)", si.path, w);
      if (report != nullptr)
        (*report)["raster_windows"].push_back(Json{{"path", si.path},
                                                     {"columns", si.held_cols},
                                                     {"rows", si.held_rows},
                                                     {"first_column", si.held_col_first},
                                                     {"first_row", si.held_row_first},
                                                     {"bytes", si.memory_bytes}});
    }
  }
  for (std::size_t k = 0; k < nsources && nsources > 1; ++k) log.info("read: {}", source_line(bathy.source(k), k));
  read_stage.done(nsources > 1 ? fmt::format("{} sources, highest priority first{}", nsources,
                                             c.input.blend_km > 0.0
                                                 ? fmt::format(", blended over {} km at their data edges", c.input.blend_km)
                                                 : std::string(" (the first with data wins)"))
                  : ri.streamed ? fmt::format("{} x {} raster, {:.4g}', streamed in bands of {} rows ({} MB of "
                                            "buffers; read while classifying)",
                                            ri.ncols, ri.nrows, ri.dlon * 60.0, ri.band_rows, ri.memory_bytes >> 20)
                              : fmt::format("{} x {} raster, {:.4g}' ({} MB)", ri.ncols, ri.nrows, ri.dlon * 60.0,
                                            ri.memory_bytes >> 20));
  if (nsources == 1) warn_lattice_finer_than_data(lat, ri.dlon, ri.dlat, c, log, report);
  if (lat.windowed()) {
    log.info("lattice: window of {} x {} pixels of the {} x {} global lattice, from pixel column {} row {}: "
             "{:.6g}..{:.6g}°E, {:.6g}..{:.6g}°N (the domain and {} level-0 square(s) of padding; {:.3g} % of the "
             "global lattice's pixels; bitmaps about {:.3g} MB instead of {:.3g} MB)",
             lat.nx, lat.ny, lat.nx_global, lat.ny_global, lat.i_origin, lat.j_origin, lat.lon_of(0), lat.lon_of(lat.nx),
             lat.lat_of(0), lat.lat_of(lat.ny), kWindowPadSquares,
             100.0 * static_cast<double>(lat.pixel_count()) /
                 (static_cast<double>(lat.nx_global) * static_cast<double>(lat.ny_global)),
             static_cast<double>(setup.lattice_bytes) / 1e6, estimate_lattice_bytes_f(setup.global_lattice) / 1e6);
  } else if (!setup.lattice_note.empty()) {
    log.info("lattice: the regional run keeps the global lattice ({})", setup.lattice_note);
  }
  if (report != nullptr) {
    (*report)["lattice"] = Json{{"kind", lat.kind_name()},
                                {"lat_max_deg", lat.lat_max_deg()},
                                {"nx", lat.nx_global},
                                {"ny", lat.ny_global},
                                {"pixel_deg", lat.pixel_deg()},
                                {"step0_deg", lat.step0_deg},
                                {"levels", lat.levels},
                                {"lon0_deg", lat.lon0_deg}};
    if (lat.windowed())
      (*report)["lattice"]["window"] = Json{{"nx", lat.nx},
                                            {"ny", lat.ny},
                                            {"first_column", lat.i_origin},
                                            {"first_row", lat.j_origin},
                                            {"pixels", lat.pixel_count()},
                                            {"lon_min_deg", lat.lon_of(0)},
                                            {"lon_max_deg", lat.lon_of(lat.nx)},
                                            {"lat_min_deg", lat.lat_of(0)},
                                            {"lat_max_deg", lat.lat_of(lat.ny)},
                                            {"padding_squares", kWindowPadSquares},
                                            {"bitmap_bytes", setup.lattice_bytes}};
    else if (!setup.lattice_note.empty())
      (*report)["lattice"]["global_because"] = setup.lattice_note;
  }

  carve(run, c, log, report);
  run.domain = mask::make_domain(c.domain, lat, rot, dense_domain);
  if (run.domain.regional()) {
    if (dense_domain)  // (the forest counts its domain's pixels over its patches, and logs them)
      log.info("domain: {}: {} pixels of {} of the {} lattice ({:.2g} %)", run.domain.description, run.domain.pixels,
               lat.pixel_count(), lat.windowed() ? "window" : "global",
               100.0 * static_cast<double>(run.domain.pixels) / static_cast<double>(lat.pixel_count()));
    if (report != nullptr)
      (*report)["domain"] = Json{{"kind", c.domain.resolved == config::DomainKind::kBox ? "box" : "polygon"},
                                 {"description", run.domain.description},
                                 {"pixels", run.domain.pixels},
                                 {"lon_min_deg", run.domain.lon_min},
                                 {"lon_max_deg", run.domain.lon_max},
                                 {"lat_min_deg", run.domain.lat_min},
                                 {"lat_max_deg", run.domain.lat_max}};
  }
}

// The report's "input" section (after the classification: a streamed raster's statistics come from
// that pass).
static void input_json(const raster::Bathymetry& bathy, const config::GlobalConfig& c, Report* report) {
  if (report == nullptr) return;
  const auto& ri = bathy.info();
  const std::size_t nsources = bathy.source_count();
  if (nsources == 1) {
    (*report)["input"] = Json{{"path", ri.path},           {"driver", ri.driver},        {"variable", ri.variable},
                              {"columns", ri.ncols},       {"rows", ri.nrows},           {"resolution_deg", ri.dlon},
                              {"min_m", ri.min_m},         {"max_m", ri.max_m},          {"streamed", ri.streamed},
                              {"band_rows", ri.band_rows}, {"block_rows", ri.block_rows}};
  } else {
    (*report)["input"] = Json{{"path", ri.path}, {"blend_km", c.input.blend_km}, {"streamed", ri.streamed}};
  }
  Json sources = Json::array();
  for (std::size_t k = 0; k < nsources; ++k) sources.push_back(source_json(bathy.source(k)));
  (*report)["input"]["sources"] = sources;
}

GlobalRun run_global_leaves(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log, Report* report,
                            bool reuse) {
  if (c.quadtree.engine == config::QuadtreeEngine::kForest)  // refused at load (config::GlobalUse::kMask)
    throw InternalError("run_global_leaves: the forest engine makes no bitmaps");
  GlobalRun run;
  run.setup = setup;
  const Lattice& lat = setup.lattice;
  const PoleRotation& rot = setup.rotation;
  open_inputs(run, c, setup, log, report);
  if (run.domain.regional()) reuse = false;  // the global run file holds a global fill
  const raster::Bathymetry& bathy = *run.bathy;
  const std::size_t nsources = bathy.source_count();
  const std::filesystem::path file = global_run_file_path(c);
  if (reuse && std::filesystem::exists(file)) {
    StageScope stage("mask", report, log);
    mask::GlobalRunFile g = mask::read_global_run_file(file, c, lat);
    if (g.reused) {
      run.area = std::move(g.area);
      run.area_file = file.string();
      if (report != nullptr)
        (*report)["mask"] = Json{{"reused_file", run.area_file},
                                 {"inputs_fnv1a64", mask::mask_inputs_checksum(mask::mask_inputs(c))},
                                 {"filled_pixels", run.area.filled_pixels}};
      stage.done(fmt::format("reused {} (its mask inputs match this run): {} filled pixels, no global fill",
                             run.area_file, run.area.filled_pixels));
    } else {
      run.area_file_differs = fmt::format("{} was made from other inputs ({})", file.string(), g.differs);
      log.warn("mask: {}; running the global fill again", run.area_file_differs);
    }
  }
  if (run.area_file.empty()) run.area = mask::compute_wet_area(bathy, lat, rot, c.mask, log, report, &run.domain);
  // A streamed raster counts its implausible values in the classification's pass (one held whole
  // said so when it was read).
  for (std::size_t k = 0; k < nsources; ++k) {
    const auto& si = bathy.source(k).info();
    if (si.streamed && run.area_file.empty())
      if (const std::string note = raster::implausible_note(si); !note.empty()) log.warn("{}: {}", si.path, note);
  }
  input_json(bathy, c, report);
  const mask::WetArea& area = run.area;
  if (c.mask.passages && !area.passages.empty()) {
    log.info("critical passages{} (open = the filled ocean connects both sides):",
             run.domain.regional() ? " inside the domain" : "");
    for (const auto& line : mask::format_passage_table(area.passages)) log.info("  {}", line);
  }
  warn_dropped_seas(run, c, log, report);
  warn_separate_seeds(run, c, log, report);
  // The coast beyond Ω_L's edge (mask/coast.hpp): not the open water beyond a regional domain,
  // and with a floodplain the shoreline at the datum.
  const mask::CoastSources coast = area.coast();
  run.size_field = size::build_size_field(area.filled, lat, c, rot, &bathy, log, report, coast);
  run.leaves = quadtree::build_leaves(area.filled, lat, c.quadtree, rot, &bathy, log, report, &run.size_field, coast);
  return run;
}

// Which source supplied each mesh node's depth (the counts of GlobalRun and of the report's
// input.sources), and, with several sources, the lattice-finer-than-data warning per source: a
// node on a square (of the finest level around it) smaller than the cells of the source that
// supplies its depth (alone or as the dominant, higher-priority side of a blend).
static void count_source_nodes(GlobalRun& run, const config::GlobalConfig& c, const Logger& log, Report* report) {
  const raster::Bathymetry& b = *run.bathy;
  const mesh::Mesh& m = run.mesh;
  const std::size_t ns = b.source_count();
  const auto n = static_cast<std::int64_t>(m.depth_m.size());
  run.source_nodes.assign(ns, 0);
  run.source_blended_nodes.assign(ns, 0);
  run.no_source_nodes = 0;
  std::vector<int> code(static_cast<std::size_t>(n), 0);
  if (ns == 1) {
    for (std::int64_t i = 0; i < n; ++i)
      if (std::isnan(m.depth_m[static_cast<std::size_t>(i)])) code[static_cast<std::size_t>(i)] = raster::Bathymetry::kNoSource;
  } else {
    b.supplying_sources(m.lon_deg.data(), m.lat_deg.data(), n, code.data());
  }
  for (const int k : code) {
    if (k == raster::Bathymetry::kNoSource)
      ++run.no_source_nodes;
    else if (k >= raster::Bathymetry::kBlended)
      ++run.source_blended_nodes[static_cast<std::size_t>(k - raster::Bathymetry::kBlended)];
    else
      ++run.source_nodes[static_cast<std::size_t>(k)];
  }
  std::vector<std::int64_t> finer(ns, 0);
  if (ns > 1) {
    std::vector<int> level(static_cast<std::size_t>(n), -1);
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (const auto v : m.triangles[t])
        level[static_cast<std::size_t>(v)] = std::max<int>(level[static_cast<std::size_t>(v)], m.triangle_level[t]);
    for (std::size_t q = 0; q < m.squares.size(); ++q)
      for (const auto v : m.squares[q])
        level[static_cast<std::size_t>(v)] = std::max<int>(level[static_cast<std::size_t>(v)], m.square_level[q]);
    const double step0 = run.setup.lattice.step0_deg;
    for (std::int64_t i = 0; i < n; ++i) {
      const int k = code[static_cast<std::size_t>(i)];
      const int l = level[static_cast<std::size_t>(i)];
      if (k == raster::Bathymetry::kNoSource || l < 0) continue;
      const auto src = static_cast<std::size_t>(k >= raster::Bathymetry::kBlended ? k - raster::Bathymetry::kBlended : k);
      const auto& si = b.source(src).info();
      if (step0 / static_cast<double>(1 << l) < std::min(si.dlon, si.dlat) * (1.0 - 1e-9)) ++finer[src];
    }
  }
  Json finer_json = Json::array();
  for (std::size_t k = 0; k < ns; ++k) {
    const auto& si = b.source(k).info();
    if (ns > 1)
      log.info("sources: {} supplied {} of {} mesh nodes ({:.3g} %){}", si.path, run.source_nodes[k], n,
               n > 0 ? 100.0 * static_cast<double>(run.source_nodes[k]) / static_cast<double>(n) : 0.0,
               c.input.blend_km > 0.0 && k + 1 < ns ? fmt::format(", and {} blended with the sources below", run.source_blended_nodes[k])
                                      : std::string());
    if (finer[k] > 0) {
      const double cell = std::min(si.dlon, si.dlat);
      log.warn("lattice finer than its data where {} supplies the depths: {} mesh nodes on squares smaller than its "
               "{:.4g}' cells (the finest quadtree levels there resolve interpolation, not bathymetry); a finer source "
               "above it in input.paths covering them, or fewer quadtree levels there",
               si.path, finer[k], cell * 60.0);
      finer_json.push_back(Json{{"path", si.path}, {"raster_deg", cell}, {"nodes", finer[k]}});
    }
    if (report != nullptr && (*report)["input"].contains("sources")) {
      Json& sj = (*report)["input"]["sources"][k];
      sj["nodes"] = run.source_nodes[k];
      sj["blended_nodes"] = run.source_blended_nodes[k];
    }
  }
  if (report != nullptr) {
    (*report)["input"]["no_data_nodes"] = run.no_source_nodes;
    if (!finer_json.empty()) (*report)["warnings"]["lattice_finer_than_data_sources"] = finer_json;
  }
}

// Open boundary where the domain edge meets water at the datum outside it (`open_water`), the rest
// mainland or island (mesh/boundaries.hpp).
static void type_regional_boundaries(GlobalRun& run, const std::function<bool(const mask::PixelIJ&)>& open_water,
                                     const Logger& log, Report* report) {
  StageScope stage("boundaries", report, log);
  // A river inflow: an open edge whose outside pixel's centre lies in the corridor of a channel
  // line (mask.channels) that crosses the domain's edge there.
  const raster::ElevationEdits* edits = run.bathy->edits();
  const PoleRotation& rot = run.setup.rotation;
  const Lattice& lattice = run.mesh.lattice;
  const auto river = [&](const mask::PixelIJ& px) {
    if (edits == nullptr) return false;
    const mask::LonLat g = mask::lattice_to_geographic(rot, mask::pixel_center_lattice_deg(lattice, px));
    const int k = edits->corridor_at(g.lon_deg, g.lat_deg);
    return k >= 0 && run.carving.lines[static_cast<std::size_t>(k)].kind == mask::LineKind::kChannel;
  };
  const mesh::BoundaryCounts counts = mesh::type_domain_boundaries(run.mesh, open_water, &log, river);
  if (report != nullptr) (*report)["boundaries"] = mesh::boundaries_json(run.mesh, counts);
  stage.done(mesh::describe(counts));
}

// The dense engine's: WetArea::open, the water at the datum outside the domain (wet at max(h, 0), so
// the floodplain of a surge mesh meets the domain edge with land).
static void type_regional_boundaries_dense(GlobalRun& run, const Logger& log, Report* report) {
  const Bitmap& open = run.area.open;
  type_regional_boundaries(
      run, [&](const mask::PixelIJ& px) { return open.get(px.i, px.j); }, log, report);
}

// A polygon domain: the open-boundary nodes moved onto the polygon where the triangles stay valid
// (mesh/open_snap.hpp). Only when the files hold triangles alone: a moved corner would bend the
// squares of mesh.elements = "squares" / "both", which the snapping does not check.
static void snap_polygon_open_boundary(GlobalRun& run, const config::GlobalConfig& c, const Logger& log,
                                       Report* report) {
  StageScope stage("open_snap", report, log);
  if (c.mesh.elements != config::ElementKinds::kTriangles) {
    stage.done(fmt::format("the open boundary stays on the lattice: mesh.elements = \"{}\" writes squares",
                           c.mesh.elements));
    return;
  }
  mesh::OpenSnapOptions o;
  o.wet_max_elevation_m = -std::max(c.mask.min_depth_m, 0.0);  // an open node stays in water at the datum
  const raster::Bathymetry& bathy = *run.bathy;
  const mesh::OpenSnapResult r = mesh::snap_open_boundary(
      run.mesh, run.domain.rings, run.setup.rotation,
      [&bathy](double lon, double lat) {
        double z = 0.0;
        bathy.sample_points(&lon, &lat, 1, &z);
        return z;
      },
      o);
  if (report != nullptr) (*report)["open_boundary_snap"] = r.json();
  stage.done(r.describe());
}

// A floodplain mesh (mask.min_depth_m < 0; README "A storm-surge mesh"): its nodes and area above
// the datum (mesh/floodplain.hpp), the "floodplain" stage line and report section.
static void report_floodplain(const GlobalRun& run, const Logger& log, Report* report) {
  StageScope stage("floodplain", report, log);
  const mesh::Floodplain f = mesh::floodplain(run.mesh, run.mesh.floodplain_top_m);
  if (report != nullptr) {
    Json j = mesh::floodplain_json(f);
    j["pixels"] = run.area.floodplain_pixels;
    (*report)["floodplain"] = j;
  }
  stage.done(
      fmt::format("{} of {} nodes above the datum (dry at rest; highest {:.1f} m), {:.1f} km² (WGS84) of land up "
                  "to +{:g} m in {} triangles; {} of the {} land-boundary nodes are above the datum",
                  f.nodes, run.mesh.node_count(), f.highest_node_m, f.area_km2, f.top_m, f.triangles,
                  f.land_boundary_nodes_above, f.land_boundary_nodes));
}

// The statistics and checks of the lattice mesh (conforming, its area that of the filled pixels):
// before a polygon's open boundary moves off the lattice (the moved nodes change the area by
// design).
static void check_lattice_mesh(GlobalRun& run, const Logger& log, Report* report) {
  StageScope stat_stage("statistics", report, log);
  run.statistics = mesh::compute_statistics(run.mesh);
  const mesh::MeshStatistics& st = run.statistics;
  if (report != nullptr) (*report)["statistics"] = mesh::statistics_json(st);
  const auto failed = st.failed_checks();
  if (!failed.empty()) {
    std::string list;
    for (const auto& f : failed) list += " " + f;
    throw InternalError("mesh checks failed:" + list + "; no files were written (please report this)");
  }
  stat_stage.done(fmt::format("all checks passed; wet area {:.4g} million km²", st.triangle_area_km2 / 1e6));
}

// The stages after the lattice mesh, on the process that holds it (rank 0 of a forest run): the
// lattice mesh's checks, a polygon's open boundary, the sources' node counts, the threshold depth
// warning and the time step.
static void finish_mesh(GlobalRun& run, const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                        Report* report, bool statistics, bool keep_masks) {
  if (statistics) check_lattice_mesh(run, log, report);
  if (run.domain.kind == config::DomainKind::kPolygon) snap_polygon_open_boundary(run, c, log, report);
  count_source_nodes(run, c, log, report);
  warn_threshold_depth_nodes(run.mesh, c.mask.min_depth_m, log, report);
  if (!keep_masks) run.area.open = Bitmap();
  if (!statistics) return;

  {  // the explicit barotropic time step (and the Courant numbers at size.cfl.dt_s)
    StageScope dt_stage("time_step", report, log);
    const mesh::TimeStep ts = mesh::time_step(run.mesh, c.size.min_depth_m, c.size.cfl.dt_s, c.size.cfl.courant_max,
                                              run.mesh.floodplain_top_m);
    if (report != nullptr) (*report)["time_step"] = mesh::time_step_json(ts);
    if (ts.wetting_drying.flood_level_m > 0.0) {
      const mesh::TimeStep::WettingDrying& w = ts.wetting_drying;
      log.info(
          "time_step: with wetting and drying, water up to {:g} m above the datum over every node (H = {:g} m - "
          "elevation, at least {} m): dt {:.2f} s (edge {:.0f} m, H {:.1f} m at {:.3f}, {:.3f}, whose highest "
          "node is at {:.1f} m); {:.2f} s at Courant {}",
          w.flood_level_m, w.flood_level_m, ts.min_depth_m, w.max_stable_dt_s, w.limiting_edge_m, w.limiting_depth_m,
          w.limiting_lon_deg, w.limiting_lat_deg, w.limiting_elevation_m, w.max_stable_dt_s * ts.courant_max,
          ts.courant_max);
    }
    std::string courant;
    if (ts.dt_s > 0.0 && ts.courant_percentiles.size() == 5)
      courant = fmt::format("; at dt = {} s Courant min/median/p99/max {:.3f}/{:.3f}/{:.3f}/{:.3f}, {} triangles above {}",
                            ts.dt_s, ts.courant_percentiles[0], ts.courant_percentiles[1], ts.courant_percentiles[3],
                            ts.courant_percentiles[4], ts.above_courant_max, ts.courant_max);
    dt_stage.done(fmt::format("largest stable explicit barotropic dt {:.2f} s (edge {:.0f} m, H {:.0f} m at {:.3f}, {:.3f}; "
                              "min over triangles of edge/sqrt(gH), H >= {} m){}",
                              ts.max_stable_dt_s, ts.limiting_edge_m, ts.limiting_depth_m, ts.limiting_lon_deg,
                              ts.limiting_lat_deg, ts.min_depth_m, courant));
    if (ts.dt_s > 0.0 && ts.above_courant_max > 0) {
      std::string levels;
      for (std::size_t l = 0; l < ts.above_by_level.size(); ++l)
        if (ts.above_by_level[l] > 0) levels += fmt::format("{}{}: {}", levels.empty() ? "" : ", ", l, ts.above_by_level[l]);
      log.warn("time_step: {} of {} triangles exceed Courant {} at dt = {} s (by level {}; {} touch the coast): the "
               "quadtree refuses every split the size field or the grading asks below the CFL bound, but the D_l rule "
               "keeps the squares on the coast at level {} and the 2:1 balance steps one level per square away from "
               "them, whatever the depth; dt <= {:.2f} s keeps every triangle at Courant <= {}",
               ts.above_courant_max, ts.triangles, ts.courant_max, ts.dt_s, levels, ts.above_touching_coast,
               setup.lattice.levels, ts.max_stable_dt_s * ts.courant_max, ts.courant_max);
    }
  }
  if (run.mesh.floodplain_top_m > 0.0) report_floodplain(run, log, report);
}

#ifdef AQ_HAVE_MPI
// The forest's estimate per rank once the leaves are known (the memory model above), logged and
// in the report's "forest" section; above input.max_memory_gb the run stops there, before the
// mesh (every rank holds every rank's figures, so every rank stops alike).
static void check_forest_memory(const GlobalSetup& s, const std::vector<forest::RankMemory>& ranks,
                                const forest::Comm& comm, const Logger& log, Report* report) {
  // What each rank holds now, the forest's stages done: the raster, the tile cache, the patches.
  const std::vector<std::int64_t> rss = comm.allgatherv(std::vector<std::int64_t>{current_rss_bytes()});
  std::int64_t leaves = 0, elements = 0;
  for (const forest::RankMemory& r : ranks) {
    leaves += r.leaves;
    elements += r.elements;
  }
  const double gather = kForestGatherBytesPerLeaf * static_cast<double>(leaves);  // in rank 0's resident set
  const double mesh = kMeshBytesPerTriangle * static_cast<double>(elements);
  std::vector<std::int64_t> est(ranks.size());
  Json per = Json::array();
  for (std::size_t k = 0; k < ranks.size(); ++k) {
    const forest::RankMemory& r = ranks[k];
    const double e = static_cast<double>(rss[k]) + (k == 0 ? mesh : 0.0);
    est[k] = saturate(std::max(e, static_cast<double>(r.peak_bytes)));
    per.push_back(Json{{"rank", k},
                       {"resident_bytes", rss[k]},
                       {"peak_bytes_so_far", r.peak_bytes},
                       {"leaves", r.leaves},
                       {"triangles", r.elements},
                       {"estimate_bytes", est[k]}});
  }
  std::string others;
  for (std::size_t k = 1; k < est.size() && k < 8; ++k) others += fmt::format(", rank {} {:.2f} GB", k, gb(est[k]));
  if (est.size() > 8) {
    const auto [lo, hi] = std::minmax_element(est.begin() + 1, est.end());
    others += fmt::format(", ranks 8..{} {:.2f}-{:.2f} GB", est.size() - 1, gb(*lo), gb(*hi));
  }
  log.info(
      "memory: estimate with the leaves known ({} leaves, {} triangles): rank 0 {:.2f} GB (resident {:.2f} GB with "
      "the gathered leaves' {:.2f} GB, the mesh {:.2f} GB){} of {:.2f} GB allowed (input.max_memory_gb)",
      leaves, elements, gb(est[0]), gb(rss[0]), gather / 1e9, mesh / 1e9, others, gb(s.memory_limit_bytes));
  if (report != nullptr)
    (*report)["forest"]["memory"] = Json{{"estimate_bytes_before_data", s.estimate_bytes},
                                         {"mesh_bytes_per_triangle", kMeshBytesPerTriangle},
                                         {"gather_bytes_per_leaf", kForestGatherBytesPerLeaf},
                                         {"per_rank", per}};
  const auto worst = std::max_element(est.begin(), est.end());
  if (s.memory_limit_bytes > 0 && *worst > s.memory_limit_bytes)
    throw ConfigError(fmt::format(
        "the run is estimated to need {:.2f} GB on rank {} once its {} leaves are known ({} triangles, the mesh "
        "{:.2f} GB on rank 0), more than input.max_memory_gb = {:.2f} GB; no file was written (more ranks share the "
        "forest, not the mesh: a larger quadtree.step_deg or a coarser size field makes fewer triangles)",
        gb(*worst), worst - est.begin(), leaves, elements, mesh / 1e9, gb(s.memory_limit_bytes)));
}

// The forest's passage table, dropped seas and separate seeds, on rank 0: the dense engine's lines
// and report entries, from the wet and filled pixels gathered there (forest/pipeline.hpp
// kDroppedSeasMaxPixels; beyond it the dropped components are counted, not named).
static void report_forest_mask(GlobalRun& run, const forest::ForestLeaves& fl, const config::GlobalConfig& c,
                               const Logger& log, Report* report) {
  if (c.mask.passages && !run.area.passages.empty()) {
    log.info("critical passages{} (open = the filled ocean connects both sides):",
             run.domain.regional() ? " inside the domain" : "");
    for (const auto& line : mask::format_passage_table(run.area.passages)) log.info("  {}", line);
  }
  if (fl.dropped_components < 0) {
    mask::Domain dense = run.domain;
    if (dense.regional()) dense.inside = dense.window(0, 0, run.setup.lattice.nx, run.setup.lattice.ny);
    warn_dropped_seas(run, c, log, report, &dense);
  } else {
    StageScope stage("dropped", report, log);
    log.warn(
        "dropped: {} wet component(s) left out by the fill ({} pixels); the forest names and measures them on "
        "lattices up to {} pixels, this one has {}: quadtree.engine = \"dense\" names them",
        fl.dropped_components, fl.dropped_pixels, forest::kDroppedSeasMaxPixels, run.setup.lattice.pixel_count());
    if (report != nullptr)
      (*report)["mask"]["dropped"] = Json{{"components", fl.dropped_components},
                                          {"pixels", fl.dropped_pixels},
                                          {"named", false},
                                          {"threshold_km2", c.mask.warn_dropped_km2}};
    stage.done(fmt::format("{} wet component(s) left out by the fill, {} pixels; not named above {} lattice pixels",
                           fl.dropped_components, fl.dropped_pixels, forest::kDroppedSeasMaxPixels));
  }
  warn_separate_seeds(run, c, log, report);
  run.area.wet = Bitmap();  // (gathered for the dropped seas only)
  run.area.filled = Bitmap();
}
#endif

// The forest engine (README "The forest engine"): the same stages on every MPI rank; rank 0
// gathers the leaves, builds the mesh and runs the stages after it (the other ranks return a run
// without a mesh and answer the open boundary's questions).
static GlobalRun run_forest_pipeline(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                                     Report* report, bool statistics, bool keep_masks) {
#ifdef AQ_HAVE_MPI
  forest::start_mpi();  // (config::load_global refuses output.formats "tif" on the forest)
  GlobalRun run;
  run.setup = setup;
  const Lattice& lat = setup.lattice;
  const forest::Comm comm;
  forest::collective(comm, [&] { open_inputs(run, c, setup, log, report, false); });
  forest::ForestLeaves fl =
      forest::run_forest_leaves(c, lat, setup.rotation, *run.bathy, run.domain, log, comm.root() ? report : nullptr);
  run.area = std::move(fl.area);
  run.size_field = std::move(fl.size_field);
  if (run.domain.regional()) {
    run.domain.pixels = fl.area_domain_pixels;
    log.info("domain: {}: {} pixels of {} of the {} lattice ({:.2g} %)", run.domain.description, run.domain.pixels,
             lat.pixel_count(), lat.windowed() ? "window" : "global",
             100.0 * static_cast<double>(run.domain.pixels) / static_cast<double>(lat.pixel_count()));
    if (report != nullptr) (*report)["domain"]["pixels"] = run.domain.pixels;
  }
  input_json(*run.bathy, c, report);
  if (comm.root()) report_forest_mask(run, fl, c, log, report);
  // The estimate per rank before the mesh (the dropped seas' gathered bitmaps are gone).
  forest::collective(comm,
                     [&] { check_forest_memory(setup, fl.rank_memory, comm, log, comm.root() ? report : nullptr); });
  forest::collective(comm, [&] {  // the mesh, on rank 0
    if (!comm.root()) return;
    StageScope stage("mesh", report, log);
    Timer t;
    quadtree::QuadNodes qn = quadtree::build_nodes_from_neighbourhoods(
        fl.leaves, fl.neighbourhoods, lat, quadtree::NodeOptions{mesh::mesh_needs_centres(c.mesh)});
    run.mesh = mesh::build_mesh(fl.leaves, std::move(qn), t.wall_s(), lat, setup.rotation, *run.bathy, c.mesh, log,
                                report, stage);
    run.mesh.floodplain_top_m = std::max(-c.mask.min_depth_m, 0.0);
    fl.neighbourhoods = {};
    run.leaves = std::move(fl.leaves);
  });
  if (run.domain.regional()) {  // the open boundary: whether the pixel outside each edge is wet water outside
    std::vector<mask::PixelIJ> queries;
    for (const auto& e : run.mesh.boundary_edges) {
      mask::PixelIJ px{-1, -1};
      if (mesh::edge_right_pixel(run.mesh, e[0], e[1], px)) queries.push_back(px);
    }
    const std::vector<char> answers = forest::wet_outside_domain(*fl.state, run.domain, queries);
    forest::collective(comm, [&] {
      if (!comm.root()) return;
      std::unordered_map<std::int64_t, bool> open;
      for (std::size_t k = 0; k < queries.size(); ++k) open[queries[k].j * lat.nx + queries[k].i] = answers[k] != 0;
      type_regional_boundaries(
          run, [&](const mask::PixelIJ& px) { return open.at(px.j * lat.nx + px.i); }, log, report);
    });
  }
  if (comm.root()) finish_mesh(run, c, setup, log, report, statistics, keep_masks);
  return run;
#else
  (void)setup;
  (void)log;
  (void)report;
  (void)statistics;
  (void)keep_masks;
  // config::load_global refuses quadtree.engine = "forest" in this build (forest_engine_built).
  throw InternalError(fmt::format("quadtree.engine = \"{}\" in a build without the forest engine",
                                  config::engine_name(c.quadtree.engine)));
#endif
}

GlobalRun run_global_pipeline(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                              Report* report, bool statistics, bool reuse, bool keep_masks) {
  if (c.quadtree.engine == config::QuadtreeEngine::kForest)
    return run_forest_pipeline(c, setup, log, report, statistics, keep_masks);
  GlobalRun run = run_global_leaves(c, setup, log, report, reuse);
  if (!keep_masks) {  // a moved-in empty bitmap frees the words (clear() would keep their capacity)
    run.area.wet_vertices = Bitmap();
    run.area.coastal = Bitmap();
    run.area.filled = Bitmap();
    run.area.datum_wet = Bitmap();
    run.area.sea = Bitmap();
    run.area.wet = Bitmap();  // a regional run types its boundaries with `open`
  }
  run.mesh = mesh::build_mesh(run.leaves, setup.lattice, setup.rotation, *run.bathy, c.mesh, log, report);
  run.mesh.floodplain_top_m = std::max(-c.mask.min_depth_m, 0.0);
  // The leaves go with the bitmaps (184 MB at 15", alive at the write stage's peak) unless a file
  // reads them after the mesh (mesh_run.cpp): the global run file, which keeps the masks, or the
  // preview's size colours, whose range is taken over the leaves.
  const bool png = c.output.writes(config::OutputFormat::kPng);
  if (!keep_masks && !(png && run.size_field.has_grid())) std::vector<quadtree::Leaf>().swap(run.leaves);
  if (run.domain.regional()) type_regional_boundaries_dense(run, log, report);
  finish_mesh(run, c, setup, log, report, statistics, keep_masks);
  return run;
}

}  // namespace aq::app

// The global pipeline core (see global_run.hpp).
#include "app/global_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/error.hpp"
#include "mask/global_run_file.hpp"
#include "mask/passages.hpp"
#include "mesh/build_mesh.hpp"
#include "quadtree/build_leaves.hpp"

namespace aq::app {

namespace {

// The memory model of a global run (README "Big rasters"; the estimate is printed before the run
// and written to the report beside the measured peak):
//   raster   held whole: 4 bytes per raster cell (16 with bicubic slopes) and a 64 MB read chunk;
//            streamed: two bands of rows (~64 MB each as float32) and their read buffers;
//   lattice  kLatticeBitsPerPixel: the wet-vertex, class, fill and quadtree bitmaps alive at the
//            fill/quadtree peak (about 7 full-lattice bitmaps measured at 15"; 8 bits = 1 byte per
//            lattice pixel);
//   mesh     kMeshBytesPerTriangle per triangle (nodes, squares, triangles, statistics, writers;
//            120 measured at 15", 130 at 1'), with the triangle count guessed before the run as
//            kTrianglesPerSqrtPixel·√(nx·ny): the refinement follows the coast, whose length in
//            pixels grows like the side of the lattice (1': 5.3 million triangles, 15": 20.1 million
//            on ETOPO5 resamples).
// Measured peak / estimate: 1' whole 2.07 / 2.04 GB, 1' streamed 1.17 / 1.32 GB, 15" streamed
// 5.76 / 7.06 GB.
constexpr double kLatticeBitsPerPixel = 8.0;
constexpr double kMeshBytesPerTriangle = 140.0;
constexpr double kTrianglesPerSqrtPixel = 350.0;
constexpr std::int64_t kBaseBytes = 64LL << 20;  // program, GDAL cache, small tables

std::int64_t estimate_lattice_bytes(const Lattice& l) {
  const double words = static_cast<double>((l.nx + 63) / 64) * static_cast<double>(l.ny + 1);
  return static_cast<std::int64_t>(kLatticeBitsPerPixel * words * 8.0);
}

std::int64_t estimate_triangles(const Lattice& l) {
  return static_cast<std::int64_t>(kTrianglesPerSqrtPixel *
                                   std::sqrt(static_cast<double>(l.nx) * static_cast<double>(l.ny)));
}

double gb(std::int64_t bytes) { return static_cast<double>(bytes) / 1e9; }

// Hidden test knobs (not configuration keys): AQ_RASTER_STREAMING = always | never | auto and
// AQ_RASTER_BAND_ROWS = rows per band, so that tests can compare the streamed and whole paths.
void apply_test_knobs(raster::OpenOptions& ro) {
  if (const char* s = std::getenv("AQ_RASTER_STREAMING")) {
    const std::string v = s;
    if (v == "always") ro.streaming = raster::OpenOptions::Streaming::kAlways;
    if (v == "never") ro.streaming = raster::OpenOptions::Streaming::kNever;
  }
  if (const char* s = std::getenv("AQ_RASTER_BAND_ROWS")) ro.band_rows = std::max<std::int64_t>(0, std::atoll(s));
}

}  // namespace

GlobalSetup prepare_global_run(const config::GlobalConfig& c) {
  GlobalSetup s;
  s.lattice = c.quadtree.lattice == "mercator"
                  ? Lattice::make_mercator(c.quadtree.step_deg, c.quadtree.levels, c.quadtree.lon0_deg,
                                           c.quadtree.mercator_lat_max_deg)
                  : Lattice::make(c.quadtree.step_deg, c.quadtree.levels, c.quadtree.lon0_deg);
  s.rotation = c.rotation.enabled ? PoleRotation(c.rotation.pole_lon_deg, c.rotation.pole_lat_deg) : PoleRotation();
  s.memory_limit_bytes = c.input.max_memory_gb > 0
                             ? static_cast<std::int64_t>(c.input.max_memory_gb * 1e9)
                             : static_cast<std::int64_t>(0.8 * static_cast<double>(physical_memory_bytes()));
  s.lattice_bytes = estimate_lattice_bytes(s.lattice);
  s.triangles_guess = estimate_triangles(s.lattice);
  s.mesh_bytes = static_cast<std::int64_t>(kMeshBytesPerTriangle * static_cast<double>(s.triangles_guess));
  const Lattice& lat = s.lattice;
  if (s.memory_limit_bytes > 0 && s.lattice_bytes > s.memory_limit_bytes) {
    throw ConfigError(fmt::format(
        "quadtree.levels = {} with quadtree.step_deg = {}: the {} x {} pixel lattice needs about {:.1f} GB of "
        "bitmaps, more than the {:.1f} GB allowed (input.max_memory_gb); use fewer levels or a larger Δ0",
        lat.levels, lat.step0_deg, lat.nx, lat.ny, static_cast<double>(s.lattice_bytes) / 1e9,
        static_cast<double>(s.memory_limit_bytes) / 1e9));
  }
  // The raster: its header only (nothing is read), whole or streamed, and the whole estimate.
  raster::OpenOptions ro = raster_options(c.input, s.memory_limit_bytes);
  ro.allow_streaming = s.rotation.identity() && c.mask.sampling == "vertex" && c.quadtree.depth_rules.empty();
  apply_test_knobs(ro);
  s.raster = raster::plan_raster(ro);
  s.raster_options = ro;
  s.estimate_bytes = kBaseBytes + s.raster.bytes + s.lattice_bytes + s.mesh_bytes;
  if (s.memory_limit_bytes > 0 && s.estimate_bytes > s.memory_limit_bytes) {
    std::string why;
    if (!s.raster.streamed && s.raster.bytes > raster::kStreamAboveBytes) {
      why = !s.rotation.identity()                ? " (rotation.enabled = true holds the raster whole)"
            : c.mask.sampling != "vertex"         ? " (mask.sampling = \"area\" holds the raster whole)"
            : !c.quadtree.depth_rules.empty()     ? " (quadtree.depth_rules hold the raster whole)"
            : c.input.interpolation != "bilinear" ? " (input.interpolation = \"bicubic\" holds the raster whole)"
                                                  : "";
    }
    throw ConfigError(fmt::format(
        "the run is estimated to need {:.2f} GB (raster {:.2f} GB {}{}, lattice bitmaps {:.2f} GB, mesh {:.2f} GB), "
        "more than input.max_memory_gb = {:.2f} GB; nothing was read",
        gb(s.estimate_bytes), gb(s.raster.bytes), s.raster.streamed ? "streamed" : "held whole", why,
        gb(s.lattice_bytes), gb(s.mesh_bytes), gb(s.memory_limit_bytes)));
  }
  return s;
}

Json memory_json(const GlobalSetup& s) {
  return Json{{"estimate_bytes", s.estimate_bytes},        {"estimate_raster_bytes", s.raster.bytes},
              {"estimate_lattice_bytes", s.lattice_bytes}, {"estimate_mesh_bytes", s.mesh_bytes},
              {"estimate_triangles", s.triangles_guess},   {"limit_bytes", s.memory_limit_bytes},
              {"raster_streamed", s.raster.streamed},      {"raster_block_rows", s.raster.block_rows},
              {"raster_band_rows", s.raster.band_rows},    {"peak_rss_bytes", peak_rss_bytes()}};
}

void log_memory_estimate(const GlobalSetup& s, const Logger& log) {
  log.info(
      "memory: estimate {:.2f} GB of {:.2f} GB allowed (input.max_memory_gb): raster {:.2f} GB {}, lattice "
      "bitmaps {:.2f} GB, mesh {:.2f} GB (~{} triangles)",
      gb(s.estimate_bytes), gb(s.memory_limit_bytes), gb(s.raster.bytes),
      s.raster.streamed ? fmt::format("streamed in bands of {} rows", s.raster.band_rows) : std::string("held whole"),
      gb(s.lattice_bytes), gb(s.mesh_bytes), s.triangles_guess);
}

raster::OpenOptions raster_options(const config::InputOptions& input, std::int64_t max_memory_bytes) {
  raster::OpenOptions ro;
  ro.path = input.path;
  ro.variable = input.variable;
  ro.band = input.band;
  ro.positive_down = input.positive_down;
  ro.interpolation =
      input.interpolation == "bicubic" ? raster::Interpolation::kBicubic : raster::Interpolation::kBilinear;
  ro.max_memory_bytes = max_memory_bytes;
  return ro;
}

std::filesystem::path global_run_file_path(const config::GlobalConfig& c) {
  return std::filesystem::path(c.output.dir) / (c.output.name + ".tif");
}

GlobalRun run_global_leaves(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log, Report* report,
                            bool reuse) {
  GlobalRun run;
  run.setup = setup;
  const Lattice& lat = setup.lattice;
  const PoleRotation& rot = setup.rotation;
  const std::int64_t limit = setup.memory_limit_bytes, need = setup.lattice_bytes;

  raster::OpenOptions ro = setup.raster_options;
  ro.max_memory_bytes = limit > need ? limit - need : limit;
  StageScope read_stage("read", report, log);
  run.bathy.emplace(raster::Bathymetry::open(ro, log));
  const raster::Bathymetry& bathy = *run.bathy;
  const auto& ri = bathy.info();
  read_stage.done(ri.streamed ? fmt::format("{} x {} raster, {:.4g}', streamed in bands of {} rows ({} MB of "
                                            "buffers; read while classifying)",
                                            ri.ncols, ri.nrows, ri.dlon * 60.0, ri.band_rows, ri.memory_bytes >> 20)
                              : fmt::format("{} x {} raster, {:.4g}' ({} MB)", ri.ncols, ri.nrows, ri.dlon * 60.0,
                                            ri.memory_bytes >> 20));
  if (report != nullptr) {
    (*report)["lattice"] = Json{{"kind", lat.kind_name()},
                                {"lat_max_deg", lat.lat_max_deg()},
                                {"nx", lat.nx},
                                {"ny", lat.ny},
                                {"pixel_deg", lat.pixel_deg()},
                                {"step0_deg", lat.step0_deg},
                                {"levels", lat.levels},
                                {"lon0_deg", lat.lon0_deg}};
  }

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
  if (run.area_file.empty()) run.area = mask::compute_wet_area(bathy, lat, rot, c.mask, log, report);
  if (report != nullptr) {  // after the classification: a streamed raster's statistics come from that pass
    (*report)["input"] = Json{{"path", ri.path},           {"driver", ri.driver},        {"variable", ri.variable},
                              {"columns", ri.ncols},       {"rows", ri.nrows},           {"resolution_deg", ri.dlon},
                              {"min_m", ri.min_m},         {"max_m", ri.max_m},          {"streamed", ri.streamed},
                              {"band_rows", ri.band_rows}, {"block_rows", ri.block_rows}};
  }
  const mask::WetArea& area = run.area;
  if (c.mask.passages && !area.passages.empty()) {
    log.info("critical passages (open = the filled ocean connects both sides):");
    for (const auto& line : mask::format_passage_table(area.passages)) log.info("  {}", line);
  }
  run.leaves = quadtree::build_leaves(area.filled, lat, c.quadtree, rot, &bathy, log, report);
  return run;
}

GlobalRun run_global_pipeline(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                              Report* report, bool statistics, bool reuse) {
  GlobalRun run = run_global_leaves(c, setup, log, report, reuse);
  run.mesh = mesh::build_mesh(run.leaves, setup.lattice, setup.rotation, *run.bathy, c.mesh, log, report);
  if (!statistics) return run;

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
  return run;
}

}  // namespace aq::app

// The global pipeline core (see global_run.hpp).
#include "app/global_run.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "mask/passages.hpp"
#include "mesh/build_mesh.hpp"
#include "quadtree/build_leaves.hpp"

namespace aq::app {

namespace {

// Bytes the bitmaps of the mask and quadtree stages need (about 12 full-lattice bitmaps at peak).
std::int64_t estimate_lattice_bytes(const Lattice& l) { return 12 * (l.nx / 8 + 8) * (l.ny + 1); }

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
  const Lattice& lat = s.lattice;
  if (s.memory_limit_bytes > 0 && s.lattice_bytes > s.memory_limit_bytes) {
    throw ConfigError(fmt::format(
        "quadtree.levels = {} with quadtree.step_deg = {}: the {} x {} pixel lattice needs about {:.1f} GB of "
        "bitmaps, more than the {:.1f} GB allowed (input.max_memory_gb); use fewer levels or a larger Δ0",
        lat.levels, lat.step0_deg, lat.nx, lat.ny, static_cast<double>(s.lattice_bytes) / 1e9,
        static_cast<double>(s.memory_limit_bytes) / 1e9));
  }
  return s;
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

GlobalRun run_global_pipeline(const config::GlobalConfig& c, const GlobalSetup& setup, const Logger& log,
                              Report* report, bool statistics) {
  GlobalRun run;
  run.setup = setup;
  const Lattice& lat = setup.lattice;
  const PoleRotation& rot = setup.rotation;
  const std::int64_t limit = setup.memory_limit_bytes, need = setup.lattice_bytes;

  const raster::OpenOptions ro = raster_options(c.input, limit > need ? limit - need : limit);
  StageScope read_stage("read", report, log);
  run.bathy.emplace(raster::Bathymetry::open(ro, log));
  const raster::Bathymetry& bathy = *run.bathy;
  const auto& ri = bathy.info();
  read_stage.done(
      fmt::format("{} x {} raster, {:.4g}' ({} MB)", ri.ncols, ri.nrows, ri.dlon * 60.0, ri.memory_bytes >> 20));
  if (report != nullptr) {
    (*report)["input"] =
        Json{{"path", ri.path},  {"driver", ri.driver},       {"variable", ri.variable}, {"columns", ri.ncols},
             {"rows", ri.nrows}, {"resolution_deg", ri.dlon}, {"min_m", ri.min_m},       {"max_m", ri.max_m}};
    (*report)["lattice"] = Json{{"kind", lat.kind_name()},
                                {"lat_max_deg", lat.lat_max_deg()},
                                {"nx", lat.nx},
                                {"ny", lat.ny},
                                {"pixel_deg", lat.pixel_deg()},
                                {"step0_deg", lat.step0_deg},
                                {"levels", lat.levels},
                                {"lon0_deg", lat.lon0_deg}};
  }

  run.area = mask::compute_wet_area(bathy, lat, rot, c.mask, log, report);
  const mask::WetArea& area = run.area;
  if (c.mask.passages && !area.passages.empty()) {
    log.info("critical passages (open = the filled ocean connects both sides):");
    for (const auto& line : mask::format_passage_table(area.passages)) log.info("  {}", line);
  }
  const auto leaves = quadtree::build_leaves(area.filled, lat, c.quadtree, rot, &bathy, log, report);
  run.mesh = mesh::build_mesh(leaves, lat, rot, bathy, c.mesh, log, report);
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

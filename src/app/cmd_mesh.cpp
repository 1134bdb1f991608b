// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria mesh`: the global discretizer end to end (ARCHITECTURE §4): bathymetry → wet
// pixels → K-cursor fill → quadtree leaves → 2:1 smoothing → nodes → triangle templates →
// depths → statistics → mesh files, pictures and the run report. With no -c it runs the seed's
// reference configuration (Δ0 = 4°, L = 3, K = 2, h = 0) on the installed ETOPO5.
#include <fmt/format.h>

#include <filesystem>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/global_run.hpp"
#include "app/key_list.hpp"
#include "app/mesh_run.hpp"
#include "app/provenance.hpp"
#include "config/load.hpp"
#include "core/error.hpp"
#include "core/lattice.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "mesh/statistics.hpp"
#include "raster/bathymetry.hpp"
#ifdef AQ_HAVE_MPI
#include "forest/mpi_session.hpp"
#endif

namespace aq::app {

namespace {

int world_rank() {
#ifdef AQ_HAVE_MPI
  return aq::forest::world_rank();
#else
  return 0;
#endif
}

struct MeshArgs {
  std::optional<std::string> config;
  std::vector<std::string> sets;
  std::string out_dir;
  bool keys = false;
};

// The seed's published counts for its reference runs on ETOPO2 (seed 002 Figs. 6, 7, 10).
struct SeedFigure {
  bool rotated;
  double h;
  std::int64_t triangles, nodes;
  const char* figure;
};
constexpr SeedFigure kSeedFigures[] = {{false, 0.0, 65777, 36834, "Fig. 6"},
                                       {false, 30.0, 70365, 39046, "Fig. 7"},
                                       {true, 0.0, 66714, 37284, "Fig. 10"},
                                       {true, 200.0, 69480, 38650, "Fig. 10"}};

std::optional<SeedFigure> seed_figure(const config::GlobalConfig& c) {
  if (c.quadtree.step_deg != 4.0 || c.quadtree.levels != 3 || c.mask.cursor != 2) return std::nullopt;
  for (const auto& f : kSeedFigures)
    if (f.rotated == c.rotation.enabled && f.h == c.mask.min_depth_m) return f;
  return std::nullopt;
}

// The run's summary in the log: counts per level, the wet area, the seed's figure when the run is
// the seed's, the geographic files' counts, the outputs.
void log_mesh_summary(const config::GlobalConfig& c, const GlobalRun& run, const std::optional<SeedFigure>& seed,
                      Report& report, std::size_t files, const std::string& report_name, const Timer& total,
                      const Logger& log) {
  const Lattice& lat = run.setup.lattice;
  const mask::WetArea& area = run.area;
  const mesh::Mesh& m = run.mesh;
  const mesh::MeshStatistics& st = run.statistics;
  log.info("");
  log.info("mesh: {} nodes, {} triangles, {} squares, {} boundary loops, {} pinch vertices", m.node_count(),
           m.triangle_count(), m.square_count(), m.loops.size(), m.pinch_nodes.size());
  std::vector<std::int64_t> sq(static_cast<std::size_t>(lat.levels + 1), 0), tr(sq.size(), 0);
  for (const auto l : m.square_level) ++sq[l];
  for (const auto l : m.triangle_level) ++tr[l];
  for (int l = 0; l <= lat.levels; ++l) {
    log.info("  level {} ({:>7.4g}°): {:>9} squares {:>10} triangles", l, lat.step0_deg / static_cast<double>(1 << l),
             sq[static_cast<std::size_t>(l)], tr[static_cast<std::size_t>(l)]);
  }
  log.info("wet area {:.4g} million km² (WGS84); filled {} of {} wet pixels ({} left out: lakes, cut-off seas)",
           st.triangle_area_km2 / 1e6, area.filled_pixels, area.classes.wet, area.fill.wet_left_out);
  if (seed) {
    log.info("seed ({}, ETOPO2): {} triangles / {} nodes; ours on {}: {} / {} ({:+.1f}% / {:+.1f}%)", seed->figure,
             seed->triangles, seed->nodes, std::filesystem::path(c.input.path).filename().string(), m.triangle_count(),
             m.node_count(),
             100.0 * (static_cast<double>(m.triangle_count()) / static_cast<double>(seed->triangles) - 1.0),
             100.0 * (static_cast<double>(m.node_count()) / static_cast<double>(seed->nodes) - 1.0));
  }
  if (report.root().contains("geographic_mesh") && !report["geographic_mesh"]["poles"].empty()) {
    const Json& g = report["geographic_mesh"];
    std::string elements = fmt::format("{} triangles", g["triangles"].get<std::int64_t>());
    if (g.contains("squares")) {
      elements = g["triangles"].get<std::int64_t>() > 0
                     ? fmt::format("{} and {} squares", elements, g["squares"].get<std::int64_t>())
                     : fmt::format("{} squares", g["squares"].get<std::int64_t>());
    }
    log.info(
        "written in geographic coordinates: {} nodes, {} (the pole rows {}; the counts above are the lattice "
        "mesh's)",
        g["nodes"].get<std::int64_t>(), elements, g.contains("squares") ? "merged" : "re-templated");
  }
  log.info("outputs in {}/: {} files + {} ({:.2f} s, peak {:.0f} MB)", c.output.dir, files, report_name, total.wall_s(),
           static_cast<double>(peak_rss_bytes()) / 1048576.0);
}

int run_mesh(const MeshArgs& a, const Logger& main_log) {
  Timer total;
  auto loaded = config::load_global(a.config ? a.config : std::optional<std::string>(), a.sets);
  // The forest engine runs on every MPI rank (under mpirun, or a single rank started here); only
  // rank 0 logs and writes. The dense engine is one process.
  const bool forest = loaded.options.quadtree.engine == config::QuadtreeEngine::kForest;
#ifdef AQ_HAVE_MPI
  if (forest) aq::forest::start_mpi();
  if (!forest && aq::forest::world_size() > 1)
    throw ConfigError(
        fmt::format("quadtree.engine = \"dense\" runs in one process, but this run has {} MPI ranks: "
                    "set quadtree.engine = \"forest\" (--set quadtree.engine=forest) or run without mpirun",
                    aq::forest::world_size()));
#endif
  const bool writer = !forest || world_rank() == 0;
  const Logger& log = writer ? main_log : Logger::null();
  if (!a.config) {
    // No config file: the base name says what was run (the seed's reference run, or the
    // parameters that differ from it).
    bool name_set = false;
    for (const auto& s : a.sets) name_set = name_set || s.rfind("output.name=", 0) == 0;
    if (!name_set) {
      const config::RunName rn = config::default_run_name(loaded.options);
      loaded.options.output.name = rn.name;
      if (!rn.changed.empty())
        log.info("name: {} (no -c and no output.name; differs from the seed's reference run in {})", rn.name,
                 fmt::join(rn.changed, ", "));
      if (!rn.unnamed.empty())
        log.warn(
            "name: {} does not show {}: a run differing only there writes the same files; set output.name to "
            "keep both",
            rn.name, fmt::join(rn.unnamed, ", "));
    }
  }
  if (!a.out_dir.empty()) loaded.options.output.dir = a.out_dir;
  const config::GlobalConfig& c = loaded.options;

  Report report;
  start_report(report, "mesh", loaded.source, loaded.echo);
  report["config"]["output"]["name"] = c.output.name;
  report["config"]["output"]["dir"] = c.output.dir;
  warn_if_overwriting(c.output.dir, c.output.name + "_report.json", report["config"], Json::object(),
                      "set output.name (or -o DIR) to keep both", log);

  // The lattice bitmaps go once the quadtree has its leaves unless the global run file is written.
  const bool tif = c.output.writes(config::OutputFormat::kTif);
#ifdef AQ_HAVE_MPI
  const int ranks = aq::forest::world_size();
#else
  const int ranks = 1;
#endif
  const GlobalSetup setup = prepare_global_run(c, {.keep_masks = tif, .ranks = ranks});
  const Lattice& lat = setup.lattice;
  log.info("aquatoria mesh: {} ({}); lattice {} x {} pixels of {:.6g}' (Δ0 = {:.6g}°, L = {}), K = {}, h = {} m{}",
           loaded.source, fmt::join(c.input.sources(), " over "), lat.nx, lat.ny, lat.pixel_deg() * 60.0, lat.step0_deg, lat.levels,
           c.mask.cursor, c.mask.min_depth_m,
           c.rotation.enabled ? fmt::format(", pole at ({}, {})", c.rotation.pole_lon_deg, c.rotation.pole_lat_deg)
                              : std::string());

  log_memory_estimate(setup, log);

  // Fail on an unwritable output folder before the work, not after (rank 0 writes).
  std::optional<OutputSet> out_set;
  if (writer) out_set.emplace(c.output.dir, log);

  const GlobalRun run = run_global_pipeline(c, setup, log, &report, true, false, tif);
  if (!writer) return 0;
  OutputSet& out = *out_set;
  const raster::Bathymetry& bathy = *run.bathy;
  const auto& ri = bathy.info();
  const mesh::Mesh& m = run.mesh;

  // Outputs.
  StageScope write_stage("write", &report, log);
  const auto files = write_global_mesh_files(c, run, out, log, report);
  write_stage.done(fmt::format("{} files in {}", files.size(), c.output.dir));

  report["mesh_counts"] = mesh_counts_json(m);
  const auto seed = seed_figure(c);
  if (seed) {
    report["seed_reference"] =
        Json{{"figure", seed->figure},
             {"data", "ETOPO2 (ours: " + ri.path + ")"},
             {"triangles", seed->triangles},
             {"nodes", seed->nodes},
             {"triangles_ratio", static_cast<double>(m.triangle_count()) / static_cast<double>(seed->triangles)},
             {"nodes_ratio", static_cast<double>(m.node_count()) / static_cast<double>(seed->nodes)}};
  }
  report["memory"] = memory_json(setup, m.triangle_count());
  report.finish();
  report["total"]["wall_s"] = std::round(total.wall_s() * 1000.0) / 1000.0;
  const std::string report_name = write_global_report(c, report, out);
  out.commit();

  log_mesh_summary(c, run, seed, report, files.size(), report_name, total, log);
  return 0;
}

}  // namespace

void add_mesh_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd =
      app.add_subcommand("mesh", "Build a global finite-element mesh (with no -c: the seed's reference run on ETOPO5)");
  cmd->add_option_function<std::string>(
      "-c,--config", [args](const std::string& s) { args->config = s; },
      "Configuration file (TOML); see configs/example.toml");
  cmd->add_option("--set", args->sets, "Override a key: --set section.key=value (repeatable)");
  cmd->add_option("-o,--output", args->out_dir, "Output folder (overrides output.dir)");
  cmd->add_flag("--keys", args->keys, "List every configuration key with its default and values, and exit");
  cmd->callback([&ctx, args] {
    ctx.run = [&ctx, args] {
      if (!args->keys) return run_mesh(*args, ctx.log);
      print_keys(config::global_key_info(), stdout);
      return 0;
    };
  });
}

}  // namespace aq::app

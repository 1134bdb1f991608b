// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional`: a regional orthogonal curvilinear grid by the izogrid method (seed 000,
// ARCHITECTURE §5): map -> contour -> uniform boundary nodes -> inverse conformal problem ->
// Laplace fill, or by a seed-004 method (regional.method; curvilinear/regional_methods.hpp),
// stopping after any stage with a picture of what was built; or, with [nesting]
// refine_factor, a refinement grid cut from a parent ROMS grid (app/regional_refine.hpp). The
// full run writes the planar grid netCDF (<name>_xygrid.nc) with the quality fields, the ROMS
// files and the run report.
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <optional>

#include "app/commands.hpp"
#include "app/global_run.hpp"
#include "app/key_list.hpp"
#include "app/provenance.hpp"
#include "app/regional_nesting.hpp"
#include "app/regional_refine.hpp"
#include "app/regional_roms.hpp"
#include "config/load.hpp"
#include "config/regional.hpp"
#include "core/error.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "curvilinear/regional.hpp"
#include "grid_files/contact_netcdf.hpp"
#include "grid_files/xygrid_netcdf.hpp"
#include "io/file_writer.hpp"
#include "pictures/regional_pictures.hpp"
#include "raster/bathymetry.hpp"

namespace aq::app {

namespace {

struct RegionalArgs {
  std::string file;    // positional: .toml or .izogrid
  std::string config;  // -c
  std::string stop_after;
  std::vector<std::string> sets;
  std::string out_dir;
  bool no_coastline = false;
  bool force = false;  // --force: build although an input changed since the earlier outputs
  bool keys = false;   // --keys: list the configuration keys and exit
};

// The files this run reads that another aquatoria run may have written, with their checksums and
// (for aquatoria's own files) the configuration that made them: the report's "inputs".
Json regional_inputs(const config::RegionalConfig& c) {
  Json in = Json::object();
  if (!c.roms.global_config.empty() && std::filesystem::exists(c.roms.global_config)) {
    Json echo;
    try {
      echo = config::load_global(c.roms.global_config, {}).echo;
    } catch (const Error&) {
      // the run itself reports an unusable global config
    }
    in["roms.global_config"] = input_record(c.roms.global_config, echo);
  }
  if (!c.contour_file.empty() && std::filesystem::exists(c.contour_file))
    in["regional.contour_file"] = input_record(c.contour_file);
  if (c.nesting.refinement() && std::filesystem::exists(c.nesting.parent)) {
    Json made_with;
    try {
      const auto f = io::read_roms_grid_fields(c.nesting.parent);
      const Json j = Json::parse(f.aquatoria_config, nullptr, false);
      if (!j.is_discarded()) made_with = j;
    } catch (const Error&) {
      // build_refinement names an unreadable parent
    }
    in["nesting.parent"] = input_record(c.nesting.parent, made_with);
  }
  return in;
}

// A block config names the global run it was ranked on by checksum (roms.global_config_checksum):
// refuse when that file has changed since.
void check_global_config_checksum(const config::RegionalConfig& c, const std::string& source) {
  if (c.roms.global_config_checksum.empty() || c.roms.global_config.empty()) return;
  if (!std::filesystem::exists(c.roms.global_config))
    throw InputError(fmt::format("{}: roms.global_config {} does not exist", source, c.roms.global_config));
  const std::string now = file_checksum(c.roms.global_config);
  if (now == c.roms.global_config_checksum) return;
  throw InputError(fmt::format(
      "{}: the global run {} has changed since this config was written from it: roms.global_config_checksum = "
      "\"{}\" but the file's checksum is now {} (a later `aquatoria blocks` rewrote it for another global run; "
      "this block was ranked and cut for the earlier one). Run `aquatoria blocks` again for blocks of the current "
      "global run, or set roms.global_config_checksum = \"\" to use this block with it anyway",
      source, c.roms.global_config, c.roms.global_config_checksum, now));
}

// A refinement grid cut from nesting.parent: refuse when the parent has changed since the earlier
// outputs of this grid were cut from it (unless --force), naming both files and what differs.
void check_parent_unchanged(const config::RegionalConfig& c, const Json& inputs, const Json* old_report, bool force,
                            const std::string& source, const Logger& log) {
  if (!c.nesting.refinement() || old_report == nullptr || !inputs.contains("nesting.parent")) return;
  if (!old_report->contains("inputs") || !(*old_report)["inputs"].contains("nesting.parent")) return;
  const Json& was = (*old_report)["inputs"]["nesting.parent"];
  const Json& now = inputs["nesting.parent"];
  if (was.value("file", "") != now.value("file", "") || was.value(kChecksumKey, "") == now.value(kChecksumKey, ""))
    return;
  std::string what;
  if (was.contains("config") && now.contains("config")) {
    const auto d = config_differences(was["config"], now["config"]);
    if (!d.empty()) what = "; the parent is now made with " + join_some(d, 4);
  }
  const std::string grd = (std::filesystem::path(c.output_dir) / (c.name + "_grd.nc")).string();
  const std::string msg =
      fmt::format("{}: the parent {} has changed since {} was cut from it (checksum {} -> {}){}", source,
                  now.value("file", ""), grd, was.value(kChecksumKey, ""), now.value(kChecksumKey, ""), what);
  if (!force)
    throw InputError(msg + ". Make the parent again as it was, or pass --force to cut this grid from the new parent");
  log.warn("{}; --force: cutting this grid from the new parent", msg);
}

// Longitude/latitude box of the picture: the edges given, else the contour's extent padded.
// Raster options reading only the rows of [lat_min, lat_max] with a 0.5° margin.
raster::OpenOptions window_options(const config::InputOptions& input, double lat_min, double lat_max) {
  raster::OpenOptions o = raster_options(input, 0);
  o.lat_min = std::max(-90.0, lat_min - 0.5);
  o.lat_max = std::min(90.0, lat_max + 0.5);
  return o;
}

std::array<double, 4> picture_box(const curvilinear::RegionalResult& r) {
  const auto& p = r.params;
  if (std::isfinite(p.west_edge) && std::isfinite(p.east_edge) && std::isfinite(p.south_edge) &&
      std::isfinite(p.north_edge))
    return {p.west_edge, p.east_edge, p.south_edge, p.north_edge};
  double w = 1e9, e = -1e9, s = 1e9, n = -1e9;
  const auto add = [&](double x, double y) {
    const auto g = r.projection->inverse(x, y);
    if (!std::isfinite(g.lon_deg) || !std::isfinite(g.lat_deg)) return;
    double lon = g.lon_deg;
    if (lon < p.projection.rlon_deg - 180.0) lon += 360.0;
    w = std::min(w, lon);
    e = std::max(e, lon);
    s = std::min(s, g.lat_deg);
    n = std::max(n, g.lat_deg);
  };
  for (const auto& q : r.contour_samples) add(q.x, q.y);
  for (std::size_t k = 0; k < r.control_x.size(); ++k) add(r.control_x[k], r.control_y[k]);
  const double pad_lon = 0.15 * (e - w) + 0.5, pad_lat = 0.15 * (n - s) + 0.5;
  return {w - pad_lon, e + pad_lon, std::max(-89.0, s - pad_lat), std::min(89.0, n + pad_lat)};
}

// The stage a regional run stops after: --stop-after (checked against the configuration), else
// regional.stop_after or the seed's mode (config::stop_stage), logged when the mode stops early.
curvilinear::Stage regional_stage(const RegionalArgs& a, const config::RegionalConfig& c, const std::string& path,
                                  const Logger& log) {
  std::optional<curvilinear::Stage> cli_stage;
  if (!a.stop_after.empty()) {
    cli_stage = parse_name<curvilinear::Stage>(a.stop_after);
    if (!cli_stage)
      throw ConfigError(fmt::format("--stop-after: {} (or the seed's mode 0..5)",
                                    unknown_name_message<curvilinear::Stage>(a.stop_after)));
  }
  const curvilinear::Stage stage = config::stop_stage(c, cli_stage);
  if (cli_stage) {
    std::string why;
    for (const config::KeyProblem& bad : config::stop_stage_problems(c, stage)) why += "; " + bad.text;
    if (!why.empty()) throw ConfigError(fmt::format("--stop-after {}: {}", a.stop_after, why.substr(2)));
  }
  if (!cli_stage && !c.stop_after && stage != curvilinear::Stage::kGrid) {
    log.info("{}: mode={} stops after the {} stage (the seed's modes); --stop-after grid builds the grid", path,
             c.params.mode, std::string(name_of(stage)));
  }
  return stage;
}

// The picture's coastline: the [input] raster's contour at coast_level_m around the grid.
std::vector<std::vector<curvilinear::GeoPoint>> regional_coastlines(const config::RegionalConfig& c,
                                                                    const curvilinear::RegionalResult& result,
                                                                    Report& report, const Logger& log) {
  std::vector<std::vector<curvilinear::GeoPoint>> lines_out;
  StageScope cs("coastline", &report, log);
  const auto box = picture_box(result);
  const auto bathy = raster::Bathymetry::open(window_options(c.input, box[2], box[3]), log);
  const auto lines = raster::contour_lines(bathy, c.coast_level_m, box[0], box[1], box[2], box[3]);
  std::size_t points = 0;
  for (const auto& l : lines) {
    std::vector<curvilinear::GeoPoint> g(l.lon_deg.size());
    for (std::size_t k = 0; k < g.size(); ++k) g[k] = {l.lon_deg[k], l.lat_deg[k]};
    points += g.size();
    lines_out.push_back(std::move(g));
  }
  cs.done(fmt::format("{} polylines, {} points at {} m from {}", lines.size(), points, c.coast_level_m, c.input.path));
  return lines_out;
}

// The plane grid <name>_xygrid.nc with its checks (curvilinear::check_grid; NumericalError for
// non-finite fields) and the report's "quality" section.
void write_xygrid_stage(const config::RegionalConfig& c, const std::string& source,
                        const curvilinear::RegionalResult& result, OutputSet& out, Json& outputs, Report& report,
                        const Logger& log) {
  StageScope ws("xygrid", &report, log);
  curvilinear::CheckOptions co;
  co.dxi_over_deta = result.dxi_over_deta;
  const curvilinear::GridQuality q = curvilinear::check_grid(result.grid, co);
  if (!q.non_finite.empty()) {
    std::string list;
    for (const auto& f : q.non_finite) list += "; " + f;
    throw NumericalError("grid checks failed" + list);
  }
  io::XyGrid xy;
  xy.grid = result.grid;
  xy.units = "1";  // plane units: unit-sphere radians divided by uscale
  xy.dxi = result.aspect_ratio / static_cast<double>(result.grid.nx_pts - 1);
  xy.deta = 1.0 / static_cast<double>(result.grid.ny_pts - 1);
  xy.title = fmt::format("aquatoria regional grid {}", c.name);
  xy.history = fmt::format("aquatoria regional {}", source);
  xy.residual_history = result.inverse.residual_history;
  const auto& p = result.params;
  xy.attributes = {{"proj", std::string(p.projection.kind == curvilinear::ProjectionKind::kMercator       ? "ME"
                                        : p.projection.kind == curvilinear::ProjectionKind::kLambertConic ? "LC"
                                                                                                          : "ST")},
                   {"rlat", p.projection.rlat_deg},
                   {"rlon", p.projection.rlon_deg},
                   {"rota", p.projection.rota_deg},
                   {"uscale", p.projection.uscale},
                   {"radius", p.projection.radius_m},
                   {"spline_type", static_cast<std::int64_t>(p.spline_type)},
                   {"nx", static_cast<std::int64_t>(result.nx)},
                   {"ny", static_cast<std::int64_t>(result.ny)},
                   {"aspect_ratio", result.aspect_ratio},
                   {"source", source}};
  const std::string nc = c.name + "_xygrid.nc";
  io::write_xygrid(out.temp_path(nc), xy, &q);
  outputs.push_back(Json{{"file", nc}, {kChecksumKey, file_checksum(out.pending_path(nc))}});
  Json qj = Json::object();
  for (const auto* f : q.fields())
    qj[f->name] =
        Json{{"worst", f->worst}, {"average", f->average}, {"rms", f->rms}, {"worst_cell", {f->worst_i, f->worst_j}}};
  report["quality"] = qj;
  ws.done(fmt::format("{} ({} x {} supergrid, nx = {}, ny = {}); orthogonality (50) worst {:.3g}, rms {:.3g}", nc,
                      result.grid.nx_pts, result.grid.ny_pts, result.nx, result.ny, q.ortho_50.worst, q.ortho_50.rms));
}

// The configuration of a regional run (-c FILE.toml or a seed-format FILE.izogrid, --set, -o),
// checked against the run's earlier outputs and its parent; `inputs` gets the input files'
// checksums (regional_inputs).
config::Loaded<config::RegionalConfig> load_regional_run(const RegionalArgs& a, Json& inputs, const Logger& log) {
  const std::string path = !a.config.empty() ? a.config : a.file;
  if (path.empty()) throw ConfigError("regional: give a configuration (-c FILE.toml) or a seed-format FILE.izogrid");
  if (!a.config.empty() && !a.file.empty())
    throw ConfigError(fmt::format("regional: give either -c {} or {}, not both", a.config, a.file));
  auto loaded = config::load_regional(path, a.sets);
  auto& c = loaded.options;
  if (!a.out_dir.empty()) c.output_dir = a.out_dir;
  check_global_config_checksum(c, loaded.source);
  inputs = regional_inputs(c);
  {
    const auto old = read_report(std::filesystem::path(c.output_dir) / (c.name + "_report.json"));
    check_parent_unchanged(c, inputs, old ? &*old : nullptr, a.force, loaded.source, log);
    warn_if_overwriting(c.output_dir, c.name + "_report.json", loaded.echo, inputs,
                        "set regional.name (or -o DIR) to keep both", log);
  }
  if (!a.sets.empty()) {
    bool named = false;
    for (const auto& s : a.sets) named = named || s.rfind("regional.name=", 0) == 0;
    if (!named)
      log.info(
          "outputs named {} (regional.name of {}); the --set overrides are not in the name: set regional.name to "
          "keep the runs apart",
          c.name, loaded.source);
  }
  return loaded;
}

// The grid up to `stage`: a refinement grid is cut from its parent (app/regional_refine.hpp) into
// `refined` (and `c.params` becomes the parent's plane, for the files' attributes); any other is
// built from its contour and returned.
curvilinear::RegionalResult build_regional_grid(config::RegionalConfig& c, const std::string& source,
                                                const std::string& path, curvilinear::Stage stage,
                                                std::optional<RefinedGrid>& refined, Report& report,
                                                const Logger& log) {
  if (c.nesting.refinement()) {
    if (!c.params.x.empty() || !c.contour_file.empty())
      log.warn(
          "{}: a refinement grid is cut from nesting.parent; the contour (regional.control_points{}) is not "
          "used",
          path, c.contour_file.empty() ? "" : ", regional.contour_file = " + c.contour_file);
    refined = build_refinement(c, source, log, &report);
    c.params = refined->result.params;  // the parent's plane, for the files' attributes
    return {};
  }
  // A bathymetry-weighted control function (regional.weight_depth) samples the [input] raster.
  std::optional<raster::Bathymetry> bathy;
  curvilinear::DepthSampler depth;
  if (c.params.weight_depth > 0.0 && curvilinear::uses_weight(c.params.method) && !c.input.path.empty()) {
    bathy.emplace(raster::Bathymetry::open(raster_options(c.input, 0), log));
    depth = [&bathy](double lon, double lat) { return -bathy->sample(lon, lat); };
  }
  return curvilinear::run_regional(c.params, stage, log, &report, bathy ? &depth : nullptr);
}

// The picture of the completed stage, <name>_<stage>.png (not for the seed's mode 5 run to the
// grid), its coastline the bathymetry's contour at coast_level_m.
void write_regional_picture(const RegionalArgs& a, const config::RegionalConfig& c,
                            const curvilinear::RegionalResult& result, curvilinear::Stage stage, OutputSet& out,
                            Json& outputs, Report& report, const Logger& log) {
  io::RegionalPictureOptions po;
  po.line_width = c.params.lwidth;
  po.title = fmt::format("{}: {}", c.name, std::string(name_of(result.completed)));
  if (!a.no_coastline && !c.input.path.empty() && result.projection)
    po.coastlines = regional_coastlines(c, result, report, log);
  const std::string png = fmt::format("{}_{}.png", c.name, std::string(name_of(result.completed)));
  if (c.params.mode != 5 || stage != curvilinear::Stage::kGrid) {
    StageScope ps("picture", &report, log);
    io::write_regional_png(out.temp_path(png), result, result.completed, po);
    outputs.push_back(Json{{"file", png}, {kChecksumKey, file_checksum(out.pending_path(png))}});
    ps.done(png);
  }
}

int run_regional_cmd(const RegionalArgs& a, const Logger& log) {
  Timer total;
  const std::string path = !a.config.empty() ? a.config : a.file;
  Json inputs;
  auto loaded = load_regional_run(a, inputs, log);
  auto& c = loaded.options;

  const curvilinear::Stage stage = regional_stage(a, c, path, log);

  Report report;
  start_report(report, "regional", loaded.source, loaded.echo);
  report["inputs"] = inputs;
  OutputSet out(c.output_dir, log);

  std::optional<RefinedGrid> refined;
  const curvilinear::RegionalResult built = build_regional_grid(c, loaded.source, path, stage, refined, report, log);
  const curvilinear::RegionalResult& result = refined ? refined->result : built;

  Json outputs = Json::array();
  write_regional_picture(a, c, result, stage, out, outputs, report, log);
  if (result.completed == curvilinear::Stage::kGrid)
    write_xygrid_stage(c, loaded.source, result, out, outputs, report, log);

  // Stage 5 on the sphere: the ROMS grid file <name>_grd.nc and <name>_roms.png (app/regional_roms.hpp),
  // and the nesting data beside it, boundary points in the global mesh (app/regional_nesting.hpp),
  // both from one run of the global configuration.
  if (result.completed == curvilinear::Stage::kGrid && c.roms.enabled) {
    const curvilinear::CGrid cg = curvilinear::build_cgrid(result.grid, *result.projection, roms_cgrid_options(c));
    const RegionalGlobal global = run_regional_global(c, log, &report);
    write_regional_roms(c, loaded.source, result, cg, global, out, outputs, report, log, refined ? &*refined : nullptr);
    if (wants_regional_nesting(c, result))
      write_regional_nesting(c, loaded.source, result, cg, global, out, outputs, report, log);
  }
  // The parent made consistent with a refinement grid, and the ROMS contact points of the two
  // (app/regional_refine.hpp).
  if (refined) write_refinement_contact(c, loaded.source, *refined, out, outputs, report, log);

  report["outputs"] = outputs;
  report.finish();
  report["total"]["wall_s"] = std::round(total.wall_s() * 1000.0) / 1000.0;
  const std::string report_name = c.name + "_report.json";
  {
    // Through FileWriter: a full disk is an error naming the file and errno, not a short report.
    io::FileWriter rf(out.temp_path(report_name));
    rf.text(report.dump());
    rf.text("\n");
    rf.close();
  }
  out.commit();
  log.info("regional {}: stopped after {}; {} files + {} in {}/ ({:.2f} s)", c.name,
           std::string(name_of(result.completed)), outputs.size(), report_name, c.output_dir, total.wall_s());
  return 0;
}

}  // namespace

void add_regional_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<RegionalArgs>();
  CLI::App* cmd = app.add_subcommand(
      "regional",
      "Build a regional curvilinear grid (the conformal izogrid method, or regional.method = bvp, tfi, star, ed2, rl, "
      "best) from a TOML config or a .izogrid file, or a ROMS refinement grid of a parent grid ([nesting] "
      "refine_factor, parent_box)");
  cmd->add_option("file", args->file, "A seed-format .izogrid file (or a .toml config)");
  cmd->add_option("-c,--config", args->config, "Configuration file (TOML); see configs/example_regional.toml");
  cmd->add_option(
      "--stop-after", args->stop_after,
      fmt::format("Stop after: {} (or the seed's mode 0..5; 4 and 5 are grid)", name_list<curvilinear::Stage>("")));
  cmd->add_option("--set", args->sets, "Override a key: --set section.key=value (repeatable)");
  cmd->add_option("-o,--output", args->out_dir, "Output folder (overrides output.dir)");
  cmd->add_flag("--no-coastline", args->no_coastline, "Do not draw the bathymetry's coastline on the pictures");
  cmd->add_flag("--force", args->force,
                "Cut a refinement grid from nesting.parent although the parent changed since this grid's earlier "
                "outputs were cut from it");
  cmd->add_flag("--keys", args->keys, "List every configuration key with its default and values, and exit");
  cmd->callback([&ctx, args] {
    ctx.run = [&ctx, args] {
      if (!args->keys) return run_regional_cmd(*args, ctx.log);
      print_keys(config::regional_key_info(), stdout);
      return 0;
    };
  });
}

}  // namespace aq::app

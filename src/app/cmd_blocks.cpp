// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria blocks`: the hand-off from the global mesh to regional grids (ARCHITECTURE §6). Runs
// the global pipeline (app/global_run.hpp, the same as `aquatoria mesh`), ranks the candidate
// coastal blocks (handoff/coastal_blocks.hpp) and writes, for the best `blocks.top` of them, a
// regional config and contour (handoff/block_files.hpp, block_contour.hpp) into <dir>/blocks/:
//
//   global.toml            the effective global configuration (--set overrides included) that
//                          every block config names as roms.global_config
//   block_NNN.toml         regional config:  aquatoria regional -c <dir>/blocks/block_NNN.toml
//   block_NNN.izogrid      projection + contour (plane units), counter-clockwise from SW
//   block_NNN.png          the global mesh around the block with its outline
//   blocks.png             the global mesh with every written block outlined and numbered
//   blocks.json            the ranked list, parameters and the run report
//
// block_NNN.toml records global.toml's checksum (roms.global_config_checksum), and the block files
// of an earlier run numbered above this run's count are removed, so no stale block survives.
//
// The ranked table goes to stdout; stage lines to stderr.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/global_run.hpp"
#include "app/provenance.hpp"
#include "config/load.hpp"
#include "config/regional.hpp"
#include "core/error.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/common/spline_contour.hpp"
#include "handoff/block_contour.hpp"
#include "handoff/block_files.hpp"
#include "handoff/coastal_blocks.hpp"
#include "io/file_writer.hpp"
#include "mesh_files/element_kinds.hpp"
#include "pictures/preview_png.hpp"

namespace aq::app {

namespace {

// A text output through FileWriter: a full disk is an error naming the file and errno.
void write_text(OutputSet& out, const std::string& name, const std::string& text) {
  io::FileWriter f(out.temp_path(name));
  f.text(text);
  f.close();
}

namespace fs = std::filesystem;

struct BlocksArgs {
  std::optional<std::string> config;
  std::vector<std::string> sets;
  std::string out_dir;
  int top = 0;
};

// Graticule step for a block's pictures: the largest "nice" step giving at least 3 lines.
double latlongrid_for(const handoff::BlockBox& b) {
  const double h = std::min(b.lat_max_deg - b.lat_min_deg, b.lon_max_deg - b.lon_min_deg);
  double best = 0.01;
  for (const double s : {0.01, 0.02, 0.05, 0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0})
    if (s <= h / 3.0) best = s;
  return best;
}

// The block's box as a closed polygon in the lattice system (λ′, φ′; the preview draws φ′ at its
// plane ordinate), λ continuous.
std::vector<std::array<double, 2>> map_outline(const handoff::BlockBox& b, const PoleRotation& rot) {
  std::vector<std::array<double, 2>> pts;
  const int n = 16;
  const auto add = [&](double s, double t) {
    double lon = b.lon_min_deg + s * (b.lon_max_deg - b.lon_min_deg);
    double lat = b.lat_min_deg + t * (b.lat_max_deg - b.lat_min_deg);
    if (!b.lattice_system && !rot.identity()) {
      double rl = 0.0, rp = 0.0;
      rot.to_rotated(lon, lat, rl, rp);
      lon = rl;
      lat = rp;
    }
    if (!pts.empty()) {
      while (lon - pts.back()[0] > 180.0) lon -= 360.0;
      while (lon - pts.back()[0] < -180.0) lon += 360.0;
    }
    pts.push_back({lon, lat});
  };
  for (int k = 0; k < n; ++k) add(static_cast<double>(k) / n, 0.0);
  for (int k = 0; k < n; ++k) add(1.0, static_cast<double>(k) / n);
  for (int k = 0; k < n; ++k) add(1.0 - static_cast<double>(k) / n, 1.0);
  for (int k = 0; k < n; ++k) add(0.0, 1.0 - static_cast<double>(k) / n);
  return pts;
}

std::string box_text(const handoff::BlockBox& b) {
  return fmt::format("[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]{}", b.lon_min_deg, b.lon_max_deg, b.lat_min_deg,
                     b.lat_max_deg, b.lattice_system ? "" : " (geographic)");
}

// Files block_NNN.{toml,izogrid,png} in `dir` with NNN > count (the earlier run's blocks this run did
// not write again): removed; their names, sorted.
std::vector<std::string> remove_stale_blocks(const fs::path& dir, std::size_t count) {
  std::vector<std::string> removed;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.size() < 10 || n.rfind("block_", 0) != 0) continue;
    const std::string num = n.substr(6, 3), ext = n.substr(9);
    if (num.find_first_not_of("0123456789") != std::string::npos) continue;
    if (ext != ".toml" && ext != ".izogrid" && ext != ".png") continue;
    if (static_cast<std::size_t>(std::stoi(num)) <= count) continue;
    removed.push_back(n);
  }
  std::sort(removed.begin(), removed.end());
  for (const auto& n : removed) {
    fs::remove(dir / n, ec);
    if (ec)
      throw OutputError(fmt::format("{}: cannot remove this stale block file: {}", (dir / n).string(), ec.message()));
  }
  return removed;
}

std::size_t stale_block_count(const std::vector<std::string>& names) {
  std::vector<std::string> stems;
  for (const auto& n : names) stems.push_back(n.substr(0, 9));
  std::sort(stems.begin(), stems.end());
  return static_cast<std::size_t>(std::unique(stems.begin(), stems.end()) - stems.begin());
}

// The echo of the global run's configuration as the blocks' regional runs must see it: the raster
// paths and output.dir absolute, blocks.top as run. One raster: input.path alone (input.paths
// echoes it); several: input.paths alone.
Json effective_global_echo(const Json& loaded_echo, const config::GlobalConfig& c) {
  Json echo = loaded_echo;
  if (c.input.paths.empty()) {
    echo["input"]["path"] = fs::absolute(c.input.path).lexically_normal().string();
    echo["input"].erase("paths");
  } else {
    Json paths = Json::array();
    for (const std::string& p : c.input.paths) paths.push_back(fs::absolute(p).lexically_normal().string());
    echo["input"]["paths"] = paths;
    echo["input"].erase("path");
  }
  echo["output"]["dir"] = fs::absolute(c.output.dir).lexically_normal().string();
  echo["blocks"]["top"] = c.blocks.top;
  return echo;
}

// The picture of one block: the mesh around its outline (half the block's larger side on each
// side), the outline drawn.
void write_block_picture(const GlobalRun& run, const Lattice& lat, const io::PreviewOutline& outline,
                         const std::string& title, int png_width, config::ElementKinds elements, const fs::path& path) {
  io::PreviewOptions zoom;
  zoom.width_px = std::min(png_width, 1000);
  zoom.elements = elements;
  zoom.title = title;
  double w = 1e9, e = -1e9, s = 1e9, n = -1e9;
  for (const auto& q : outline.points) {
    w = std::min(w, q[0]);
    e = std::max(e, q[0]);
    s = std::min(s, q[1]);
    n = std::max(n, q[1]);
  }
  // Half the block's larger side around it, measured in the map plane (on the Mercator
  // lattice its rows are Mercator ordinates, so a latitude pad would stretch the picture).
  const double cap = lat.mercator() ? lat.lat_max_deg() : 90.0;  // the Mercator rows' reach
  const double ys = lat.plane_y_of_lat(std::max(s, -cap)), yn = lat.plane_y_of_lat(std::min(n, cap));
  const double pad = 0.5 * std::max(e - w, yn - ys);
  const auto lat_of_plane = [&](double y) { return lat.mercator() ? mercator_lat_deg(y) : y; };
  zoom.zoom = {w - pad, e + pad, std::max(-90.0, lat_of_plane(ys - pad)), std::min(90.0, lat_of_plane(yn + pad))};
  zoom.outlines.push_back(outline);
  io::write_preview_zoom_png(run.mesh, *run.bathy, path, zoom);
}

// The entry of one block in blocks.json (`g`: its centre, `p`: its contour's projection).
Json block_json(const handoff::BlockCandidate& b, std::size_t k, const std::string& name,
                const curvilinear::GeoPoint& g, const curvilinear::ProjectionParams& p,
                const handoff::SideInsets& insets, bool shrink_to_wet, const OutputSet& out) {
  return Json{{"rank", k + 1},
              {"name", name},
              {"block", b.describe()},
              {"square", b.box_index < 0 ? Json::array({b.square_a, b.square_b}) : Json(nullptr)},
              {"box_index", b.box_index < 0 ? Json(nullptr) : Json(b.box_index)},
              {"box", {b.box.lon_min_deg, b.box.lon_max_deg, b.box.lat_min_deg, b.box.lat_max_deg}},
              {"box_system", b.box.lattice_system ? "lattice" : "geographic"},
              {"centre_lon_deg", g.lon_deg},
              {"centre_lat_deg", g.lat_deg},
              {"coastal_pixels", b.coastal_pixels},
              {"filled_pixels", b.filled_pixels},
              {"wet_fraction", b.wet_fraction},
              {"ny", b.suggested_ny},
              {"projection", std::string(name_of(p.kind))},
              {"rota_deg", p.rota_deg},
              {"uscale", p.uscale},
              {"shrink_to_wet", shrink_to_wet},
              {"max_inset", {insets.max(0), insets.max(1), insets.max(2), insets.max(3)}},
              {"config", out.final_path(name + ".toml").string()},
              {"contour", out.final_path(name + ".izogrid").string()}};
}

// The contour of a block inside `insets`, checked usable now (its spline: corners, orientation,
// self-intersection); a shrunk contour that is not falls back to the block's outline, warned.
handoff::BlockContour usable_contour(const handoff::BoxFrame& frame, const handoff::SideInsets& insets,
                                     const config::BlocksOptions& blocks, const std::string& name, const Logger& log) {
  handoff::BlockContour contour = handoff::block_contour(frame, insets, blocks.points_per_side);
  // The contour must be usable: build its spline now (corners, orientation, self-intersection).
  try {
    std::vector<bool> corner(contour.x.size(), false);
    for (const int q : contour.corners) corner[static_cast<std::size_t>(q)] = true;
    curvilinear::ContourOptions co;
    co.source = name;
    (void)curvilinear::SplineContour(contour.x, contour.y, corner, co);
  } catch (const InputError& e) {
    if (!blocks.shrink_to_wet) throw;
    log.warn("{}: the shrunk contour is not usable ({}); writing the block's outline instead", name, e.what());
    contour = handoff::block_contour(frame, handoff::SideInsets{}, blocks.points_per_side);
  }
  return contour;
}

// The regional config of one block (handoff::regional_config_text): its contour file, the global
// run's raster and coast level, and global.toml (`global_path`, with its checksum) as
// roms.global_config when the regional keys have it.
std::string block_config_text(const config::GlobalConfig& c, const std::string& name, const std::string& description,
                              int ny, const fs::path& dir, const std::string& global_path, bool has_global_key,
                              const std::string& global_checksum) {
  handoff::BlockConfigInfo info;
  info.name = name;
  info.izogrid_file = name + ".izogrid";
  info.description = description;
  info.ny = ny;
  // A regional grid reads one raster: the first source (the highest priority) of several.
  info.input_path = fs::absolute(c.input.sources().front()).lexically_normal().string();
  info.input_variable = c.input.variable;
  info.positive_down = c.input.positive_down;
  info.coast_level_m = -c.mask.min_depth_m;
  info.output_dir = dir.string();
  info.global_config = global_path;
  info.write_global_config = has_global_key;
  info.global_config_checksum = global_checksum;
  return handoff::regional_config_text(info);
}

// No block of an earlier run survives beside this run's: its config would name this global.toml.
// remove_stale_blocks, logging what went.
void remove_stale_blocks_logged(const fs::path& dir, std::size_t count, const Logger& log) {
  const std::vector<std::string> removed = remove_stale_blocks(dir, count);
  if (!removed.empty())
    log.info("blocks: removed {} file{} of {} block{} of an earlier run ({}{})", removed.size(),
             removed.size() == 1 ? "" : "s", stale_block_count(removed), stale_block_count(removed) == 1 ? "" : "s",
             removed.front(), removed.size() > 1 ? " … " + removed.back() : std::string());
}

// The global configuration of `aquatoria blocks`: the file and --set, then -o and --top.
config::Loaded<config::GlobalConfig> load_blocks_config(const BlocksArgs& a) {
  auto loaded =
      config::load_global(a.config ? a.config : std::optional<std::string>(), a.sets, config::GlobalUse::kBlocks);
  if (!a.out_dir.empty()) loaded.options.output.dir = a.out_dir;
  if (a.top > 0) loaded.options.blocks.top = a.top;
  const config::GlobalConfig& c = loaded.options;
  if (a.top < 0 || c.blocks.top < 1 || c.blocks.top > 999)
    throw ConfigError(fmt::format("--top {}: must be between 1 and 999", a.top < 0 ? a.top : c.blocks.top));
  return loaded;
}

// global.toml: the effective global configuration, so each block's regional run sees this very
// global run. Its final path and the checksum every block config records (a block outliving this
// run is refused).
std::pair<std::string, std::string> write_global_toml(OutputSet& out,
                                                      const config::Loaded<config::GlobalConfig>& loaded) {
  const std::string global_name = "global.toml";
  write_text(out, global_name,
             handoff::config_text_from_echo(
                 effective_global_echo(loaded.echo, loaded.options),
                 fmt::format("The effective global configuration of `aquatoria blocks` from {} (--set overrides "
                             "included).\nEvery block_NNN.toml names it as roms.global_config.",
                             loaded.source)));
  return {out.final_path(global_name).string(), file_checksum(out.pending_path(global_name))};
}

// What the written blocks add up to: their blocks.json entries, the overview picture's outlines
// and the table printed on stdout.
struct BlockRows {
  Json list = Json::array();
  io::PreviewOptions overview;
  std::vector<std::string> table;
};

// Writes the files of the ranked blocks (block_NNN.izogrid, .toml, .png) into `out`.
struct BlockWriter {
  const config::GlobalConfig& c;
  const std::string& source;  // the configuration's file
  const GlobalRun& run;
  const Lattice& lat;
  const PoleRotation& rot;
  const fs::path& dir;
  OutputSet& out;
  std::string global_path, global_checksum;
  bool has_global_key = false;
  std::size_t candidates = 0;
  const Logger& log;

  void write(std::size_t k, const handoff::BlockCandidate& b, BlockRows& rows) const {
    const std::string name = fmt::format("block_{:03d}", k + 1);
    const handoff::BoxFrame frame(b.box, rot);
    handoff::SideInsets insets;
    if (c.blocks.shrink_to_wet) insets = handoff::shrink_to_wet(frame, run.area.filled, lat, rot, c.blocks.max_inset);
    const handoff::BlockContour contour = usable_contour(frame, insets, c.blocks, name, log);
    if (contour.trimmed)
      log.warn("{}: a side on a pole was moved off it (a box cannot have a side of zero length)", name);
    const auto& p = contour.projection;
    const std::string description = fmt::format(
        "aquatoria regional config of {} (written by `aquatoria blocks`): {} {}, rank {} of {} by coastal "
        "pixels\n({} coastal pixels, wet fraction {:.3f}) of the global run from {}",
        name, b.describe(), box_text(b.box), k + 1, candidates, b.coastal_pixels, b.wet_fraction, source);
    write_text(out, name + ".izogrid",
               handoff::izogrid_text(contour, b.suggested_ny, latlongrid_for(frame.box()), description));
    write_text(
        out, name + ".toml",
        block_config_text(c, name, description, b.suggested_ny, dir, global_path, has_global_key, global_checksum));

    io::PreviewOutline outline{map_outline(b.box, rot), fmt::format("{}", k + 1)};
    rows.overview.outlines.push_back(outline);
    write_block_picture(run, lat, outline, fmt::format("{}: {}", name, b.describe()), c.output.png_width,
                        rows.overview.elements, out.temp_path(name + ".png"));

    const auto g = frame.geographic(0.5, 0.5);
    rows.list.push_back(block_json(b, k, name, g, contour.projection, insets, c.blocks.shrink_to_wet, out));
    rows.table.push_back(fmt::format("{:>4}  {:<10} {:<22} {:<44} {:>9} {:>6.1f} {:>5}  {} ({:.4g}, {:.4g})", k + 1,
                                     name, b.describe(), box_text(b.box), b.coastal_pixels, 100.0 * b.wet_fraction,
                                     b.suggested_ny, std::string(name_of(p.kind)), g.lon_deg, g.lat_deg));
  }
};

int run_blocks(const BlocksArgs& a, const Logger& log) {
  Timer total;
  const auto loaded = load_blocks_config(a);
  const config::GlobalConfig& c = loaded.options;

  Report report;
  start_report(report, "blocks", loaded.source, loaded.echo);
  report["config"]["output"]["dir"] = c.output.dir;
  report["config"]["blocks"]["top"] = c.blocks.top;

  const GlobalSetup setup = prepare_global_run(c, {.allow_window = false});  // blocks rank the global lattice's squares
  log_memory_estimate(setup, log);
  const Lattice& lat = setup.lattice;
  const PoleRotation& rot = setup.rotation;
  log.info(
      "aquatoria blocks: {} ({}); {} lattice {} x {} pixels of {:.6g}' (Δ0 = {:.6g}°, L = {}); top {} blocks{}",
      loaded.source, fmt::join(c.input.sources(), " over "), lat.kind_name(), lat.nx, lat.ny, lat.pixel_deg() * 60.0,
      lat.step0_deg, lat.levels, c.blocks.top,
      c.blocks.boxes.empty() ? " of the level-0 squares" : fmt::format(" of {} user boxes", c.blocks.boxes.size()));
  const fs::path dir = fs::absolute(fs::path(c.output.dir) / "blocks").lexically_normal();
  OutputSet out(dir, log);

  const GlobalRun run = run_global_pipeline(c, setup, log, &report, true, true);

  StageScope rank_stage("rank", &report, log);
  const auto ranked = handoff::rank_blocks(run.area.filled, lat, rot, c.blocks);
  const std::size_t count = std::min(ranked.size(), static_cast<std::size_t>(c.blocks.top));
  rank_stage.done(fmt::format("{} candidate blocks with coast, writing the best {}", ranked.size(), count));

  const auto [global_path, global_checksum] = write_global_toml(out, loaded);
  const auto keys = config::regional_keys();
  const bool has_global_key = std::find(keys.begin(), keys.end(), "roms.global_config") != keys.end();
  const BlockWriter w{
      c, loaded.source, run, lat, rot, dir, out, global_path, global_checksum, has_global_key, ranked.size(), log};

  StageScope write_stage("write", &report, log);
  BlockRows rows;
  rows.overview.width_px = c.output.png_width;
  rows.overview.elements = c.mesh.elements;
  rows.overview.title = fmt::format("aquatoria blocks: the {} best of {} coastal block{}", count, ranked.size(),
                                    ranked.size() == 1 ? "" : "s");
  rows.table.push_back(fmt::format("{:>4}  {:<10} {:<22} {:<44} {:>9} {:>6} {:>5}  {}", "rank", "name", "block",
                                   "box (lon x lat, degrees)", "coast px", "wet %", "ny", "projection"));
  for (std::size_t k = 0; k < count; ++k) w.write(k, ranked[k], rows);
  io::write_preview_png(run.mesh, *run.bathy, out.temp_path("blocks.png"), rows.overview);
  write_stage.done(fmt::format("{} blocks (config, contour, picture) + blocks.png in {}", count, dir.string()));

  report["blocks"] = Json{{"lattice", lat.kind_name()},
                          {"candidates", ranked.size()},
                          {"written", count},
                          {"coastal_pixel", "filled pixel with a non-filled pixel among its 8 neighbours"},
                          {"global_config", global_path},
                          {"list", rows.list}};
  report.finish();
  report["total"]["wall_s"] = std::round(total.wall_s() * 1000.0) / 1000.0;
  write_text(out, "blocks.json", report.dump() + "\n");
  out.commit();
  remove_stale_blocks_logged(dir, count, log);

  for (const auto& line : rows.table) fmt::print("{}\n", line);
  std::fflush(stdout);
  log.info("blocks: {} configs in {}/ (global.toml, block_NNN.toml/.izogrid/.png, blocks.png, blocks.json; {:.2f} s)",
           count, dir.string(), total.wall_s());
  if (count > 0) log.info("next: aquatoria regional -c {}", out.final_path("block_001.toml").string());
  return 0;
}

}  // namespace

void add_blocks_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<BlocksArgs>();
  CLI::App* cmd = app.add_subcommand(
      "blocks", "Rank the coastal blocks of a global run and write a regional config + contour for each");
  cmd->add_option_function<std::string>(
      "-c,--config", [args](const std::string& s) { args->config = s; },
      "Global configuration file (TOML); see configs/example.toml [blocks]");
  cmd->add_option("--set", args->sets, "Override a key: --set section.key=value (repeatable)");
  cmd->add_option("-o,--output", args->out_dir, "Output folder (overrides output.dir); files go to DIR/blocks/");
  cmd->add_option("--top", args->top, "How many blocks to write (overrides blocks.top)");
  cmd->callback([&ctx, args] { ctx.run = [&ctx, args] { return run_blocks(*args, ctx.log); }; });
}

}  // namespace aq::app

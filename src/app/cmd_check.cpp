// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria check GRID.nc [-o OUT.nc] [--png FILE] [--json FILE]`: the izogrid `checkort`
// (seed 000 Sec. 2.6, eqs. (46)–(52)) plus the seed-004 cell criteria f1–f4 on a planar grid file,
// a ROMS grid or a MOM6 supergrid (grid_files/any_grid.hpp).
// Prints a table (worst, average, RMS, where the worst is) to stdout and writes the per-cell and
// per-node fields as netCDF (default GRID_check.nc next to the input) and a PNG heat map of the
// orthogonality error (50) (default GRID_check.png). All outputs appear together or not at all.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/output_files.hpp"
#include "core/timer.hpp"
#include "curvilinear/common/grid_checks.hpp"
#include "grid_files/any_grid.hpp"
#include "grid_files/xygrid_netcdf.hpp"
#include "pictures/grid_quality_png.hpp"

namespace aq::app {

namespace {

namespace fs = std::filesystem;

struct CheckArgs {
  std::string grid;
  std::string out_nc;
  std::string png;
  std::string json;
  bool no_png = false;
  bool five_point = false;
};

/// One OutputSet per destination folder; committed together at the end.
class Outputs {
 public:
  fs::path reserve(const fs::path& final_path) {
    const fs::path dir = final_path.parent_path().empty() ? fs::path(".") : final_path.parent_path();
    auto& set = sets_[dir];
    if (!set) set = std::make_unique<OutputSet>(dir);
    return set->temp_path(final_path.filename().string());
  }
  void commit() {
    for (auto& [dir, set] : sets_) set->commit();
  }

 private:
  std::map<fs::path, std::unique_ptr<OutputSet>> sets_;
};

std::string number(double v) {
  if (std::isnan(v)) return "-";
  return fmt::format("{:.3e}", v);
}

std::string where(const curvilinear::QualityField& f) {
  if (f.worst_i < 0) return "-";
  return fmt::format("{} ({}, {})", f.location == curvilinear::FieldLocation::kCell ? "cell" : "node", f.worst_i,
                     f.worst_j);
}

void print_table(const std::string& path, const curvilinear::GridQuality& q, bool rho_from_file) {
  std::printf("grid:     %s\n", path.c_str());
  std::printf("size:     %d x %d points (%d x %d cells)\n", q.nx_pts, q.ny_pts, q.nx_pts - 1, q.ny_pts - 1);
  std::printf("dxi/deta: %.8g (%s)\n", q.dxi_over_deta, rho_from_file ? "from the file" : "estimated from the grid");
  std::printf("\n%-17s %-64s %11s %11s %11s  %s\n", "criterion", "meaning", "worst", "average", "rms", "worst at");
  for (const curvilinear::QualityField* f : q.fields()) {
    std::printf("%-17s %-64s %11s %11s %11s  %s\n", f->name.c_str(), f->long_name.c_str(), number(f->worst).c_str(),
                number(f->average).c_str(), number(f->rms).c_str(), where(*f).c_str());
  }
  std::printf("\nerrors (ortho, isotropy, residual): worst = max |v|, ideal 0; f1..f4: worst = min, ideal 1\n");
  std::printf("isotropy ratio |l_xi|/|l_eta| (51): %.6g .. %.6g (target %.6g)\n", q.isotropy_ratio_min,
              q.isotropy_ratio_max, q.dxi_over_deta);
  std::printf("non-convex cells (f1 <= 0): %d\n", q.non_convex_cells);
}

nlohmann::ordered_json to_json(const std::string& path, const curvilinear::GridQuality& q) {
  nlohmann::ordered_json j;
  j["grid"] = path;
  j["nx_pts"] = q.nx_pts;
  j["ny_pts"] = q.ny_pts;
  j["dxi_over_deta"] = q.dxi_over_deta;
  auto finite_or_null = [](double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
  };
  for (const curvilinear::QualityField* f : q.fields()) {
    nlohmann::ordered_json c;
    c["long_name"] = f->long_name;
    c["location"] = f->location == curvilinear::FieldLocation::kCell ? "cell" : "node";
    c["worst"] = finite_or_null(f->worst);
    c["average"] = finite_or_null(f->average);
    c["rms"] = finite_or_null(f->rms);
    c["worst_i"] = f->worst_i;
    c["worst_j"] = f->worst_j;
    c["count"] = f->count;
    j["criteria"][f->name] = c;
  }
  j["isotropy_ratio"] = {finite_or_null(q.isotropy_ratio_min), finite_or_null(q.isotropy_ratio_max)};
  j["non_convex_cells"] = q.non_convex_cells;
  return j;
}

int run_check(const CheckArgs& a, const Logger& log) {
  const Timer timer;
  const fs::path input(a.grid);
  const io::AnyGrid any = io::read_any_grid(input);
  const io::XyGrid& xy = any.xy;
  if (any.kind != io::GridFileKind::kXygrid)
    log.info(
        "{}: a {} grid file: its {} x {} supergrid on a stereographic plane centred on the grid (conformal: the "
        "angles are those on the sphere)",
        input.string(), any.kind == io::GridFileKind::kRoms ? "ROMS" : "MOM6", xy.grid.nx_pts, xy.grid.ny_pts);
  curvilinear::CheckOptions options;
  options.dxi_over_deta = xy.has_steps ? xy.dxi / xy.deta : 0.0;
  options.five_point = a.five_point;
  if (!xy.has_steps) log.warn("{}: no dxi/deta attributes; estimating the step ratio from the grid", input.string());
  const curvilinear::GridQuality q = curvilinear::check_grid(xy.grid, options);
  print_table(input.string(), q, xy.has_steps);
  if (!q.non_finite.empty()) {
    std::string list;
    for (const auto& f : q.non_finite) list += "; " + f;
    throw NumericalError(fmt::format("{}: grid checks failed{}; no files were written", input.string(), list));
  }

  const fs::path stem = input.parent_path() / input.stem();
  const fs::path nc_path = a.out_nc.empty() ? fs::path(stem.string() + "_check.nc") : fs::path(a.out_nc);
  const fs::path png_path = a.png.empty() ? fs::path(stem.string() + "_check.png") : fs::path(a.png);
  Outputs outputs;

  io::XyGrid copy = xy;
  copy.title = fmt::format("aquatoria check of {}", input.filename().string());
  copy.history = fmt::format("aquatoria check {}", input.filename().string());
  io::write_xygrid(outputs.reserve(nc_path), copy, &q);
  if (!a.no_png) {
    io::QualityPngOptions png;
    png.title = fmt::format("{}: orthogonality error (50), worst {:.2e} at cell ({}, {})", input.filename().string(),
                            q.ortho_50.worst, q.ortho_50.worst_i, q.ortho_50.worst_j);
    png.value_label = "log10 |cos angle(l_xi, l_eta)|, length-weighted form (50)";
    io::write_quality_png(outputs.reserve(png_path), xy.grid, q.ortho_50.values, png);
  }
  if (!a.json.empty()) {
    const fs::path tmp = outputs.reserve(a.json);
    std::ofstream out(tmp);
    out << to_json(input.string(), q).dump(2) << '\n';
    out.close();
    if (!out) throw OutputError(fmt::format("{}: cannot write", a.json));
  }
  outputs.commit();
  log.info("check: done {}x{} grid, worst orthogonality error (50) {:.3e} ({:.2f} s); wrote {}{}{}", q.nx_pts, q.ny_pts,
           q.ortho_50.worst, timer.wall_s(), nc_path.string(), a.no_png ? "" : ", " + png_path.string(),
           a.json.empty() ? "" : ", " + a.json);
  return 0;
}

}  // namespace

void add_check_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Orthogonality, isotropy, Laplace residual and seed-004 cell criteria of a planar grid file");
  cmd->add_option("grid", args->grid,
                  "A grid file aquatoria writes: planar grid netCDF (_xygrid.nc: x, y), ROMS grid (_grd.nc) or MOM6 "
                  "supergrid (_ocean_hgrid.nc)")
      ->required();
  cmd->add_option("-o,--output", args->out_nc, "Per-cell/per-node quality netCDF (default GRID_check.nc)");
  CLI::Option* png =
      cmd->add_option("--png", args->png, "Heat map of the orthogonality error (default GRID_check.png)");
  cmd->add_flag("--no-png", args->no_png, "Do not draw the heat map")->excludes(png);
  cmd->add_option("--json", args->json, "Also write the statistics as JSON");
  cmd->add_flag("--five-point", args->five_point, "Laplace residual of the 5-point instead of the 9-point operator");
  cmd->callback([&ctx, args] { ctx.run = [&ctx, args] { return run_check(*args, ctx.log); }; });
}

}  // namespace aq::app

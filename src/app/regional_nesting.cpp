// SPDX-License-Identifier: GPL-3.0-or-later
// The nesting step of `aquatoria regional` (see regional_nesting.hpp).
#include "app/regional_nesting.hpp"

#include <fmt/format.h>

#include <cmath>

#include "app/global_run.hpp"
#include "config/load.hpp"
#include "core/error.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "grid_files/nesting_netcdf.hpp"
#include "handoff/nesting.hpp"

namespace aq::app {

bool wants_regional_nesting(const config::RegionalConfig& c, const curvilinear::RegionalResult& result) {
  return result.completed == curvilinear::Stage::kGrid && result.projection && c.roms.enabled &&
         !c.roms.global_config.empty();
}

void write_regional_nesting(const config::RegionalConfig& c, const std::string& config_source,
                            const curvilinear::RegionalResult& result, const curvilinear::CGrid& cg,
                            const RegionalGlobal& global, OutputSet& out, Json& outputs, Report& report,
                            const Logger& log) {
  if (!wants_regional_nesting(c, result)) return;
  const config::GlobalConfig& g = global.loaded.options;
  const GlobalRun& run = global.run;
  log.info("nesting: the global mesh of {} ({} lattice, Δ0 = {}°, L = {})", global.loaded.source,
           run.setup.lattice.kind_name(), g.quadtree.step_deg, g.quadtree.levels);

  StageScope stage("nesting", &report, log);
  handoff::NestingSummary sum;
  io::NestingFile f = handoff::global_nesting(result.grid, cg, run.mesh, &sum);
  f.history = fmt::format("aquatoria {} regional {}", AQ_VERSION, config_source);
  f.attributes.emplace(f.attributes.begin(), "regional_grid", c.name + "_grd.nc");
  f.attributes.emplace(f.attributes.begin() + 1, "global_config", global.loaded.source);
  const std::string name = c.name + "_nesting.nc";
  io::write_nesting(out.temp_path(name), f);
  outputs.push_back(Json{{"file", name}, {kChecksumKey, file_checksum(out.pending_path(name))}});
  const auto num = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  report["nesting"] =
      Json{{"global_config", global.loaded.source},
           {"global_mesh", {{"nodes", run.mesh.node_count()}, {"triangles", run.mesh.triangle_count()}}},
           {"boundary_points", sum.points},
           {"outside_global_mesh", sum.outside},
           {"refinement_ratio_median", num(sum.ratio_median)},
           {"refinement_ratio_min", num(sum.ratio_min)},
           {"refinement_ratio_max", num(sum.ratio_max)}};
  if (sum.outside > 0) {
    log.warn(
        "nesting: {} of {} boundary points lie outside the global wet mesh (over its land); they are flagged "
        "with element = -1 in {}",
        sum.outside, sum.points, name);
  }
  stage.done(
      fmt::format("{}: {} boundary ρ/u/v points, {} outside the global wet mesh; refinement ratio "
                  "{:.3g} (median, {:.3g}..{:.3g})",
                  name, sum.points, sum.outside, sum.ratio_median, sum.ratio_min, sum.ratio_max));
}

}  // namespace aq::app

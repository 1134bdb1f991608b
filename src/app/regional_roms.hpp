// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional`, stage 5 on the sphere (ARCHITECTURE §5): the ROMS grid file
// <name>_grd.nc and its picture <name>_roms.png from a complete regional grid. The global run
// named by roms.global_config supplies the bathymetry (with its sampling), the threshold h, the
// lattice and the K-fill Ω_L, so depth and land mask are those of the global mesh.
#pragma once

#include <string>
#include <vector>

#include "app/global_run.hpp"
#include "app/regional_refine.hpp"
#include "config/load.hpp"
#include "config/regional.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/common/cgrid.hpp"
#include "curvilinear/regional.hpp"

namespace aq::app {

/// The global run a regional grid shares its ocean with (roms.global_config, or the built-in
/// defaults when empty), run once per regional run for the ROMS file's mask and depth and the
/// nesting data's mesh.
struct RegionalGlobal {
  config::Loaded<config::GlobalConfig> loaded;  ///< as used ("squares" elements become triangles)
  GlobalRun run;
};

/// The C-grid options of the ROMS file: roms.earth_radius_m and roms.distances (ConfigError
/// naming roms.distances for an unknown model).
curvilinear::CGridOptions roms_cgrid_options(const config::RegionalConfig& c);

/// Loads and runs roms.global_config up to its mesh (without the statistics stage), logging one
/// summary line as the report stage "global run". Throws ConfigError prefixed with
/// "roms.global_config = ...", and what the pipeline throws.
RegionalGlobal run_regional_global(const config::RegionalConfig& c, const Logger& log, Report* report);

/// From `cg`, the C-grid of `result` (completed = grid; built with roms_cgrid_options), builds the
/// depths (curvilinear/roms_depth.hpp) and masks (mask/regional_mask.hpp) and writes <name>_grd.nc and
/// <name>_roms.png through `out`; appends both to `outputs` (file and checksum), adds a "roms"
/// report section and logs "roms: done ...". `config_source` names the regional config in
/// messages and file attributes. Throws ConfigError for a bad roms.* value or global config,
/// InputError when the grid leaves the bathymetry or contains no water of the global ocean
/// (naming both configs), and what the writers throw. `refined`, for a refinement grid, is its
/// parent: the masks and depths of both grids are then made consistent
/// (handoff/nested_bathymetry.hpp: the outer ring's mask from the parent, the depth blended into
/// the parent's over nesting.blend_cells rows, the parent's h over the footprint the grid's block
/// averages, both r-factor bounds kept; hraw in the file stays the bathymetry's), a "nested"
/// report section is added, and the updated parent and this grid's values are stored in
/// `refined` for write_refinement_contact.
/// Extreme metrics found by write_regional_roms (warned about in the log).
struct MetricWarnings {
  bool isotropy = false;
  double area_jump = 1.0;  ///< largest area ratio of neighbouring interior ρ cells
  int area_jump_i = 0, area_jump_j = 0;
};

/// The reference vertical grid rx1 is measured on, as one line for the log and report.
std::string rx1_grid_text();

void write_regional_roms(const config::RegionalConfig& c, const std::string& config_source,
                         const curvilinear::RegionalResult& result, const curvilinear::CGrid& cg,
                         const RegionalGlobal& global, OutputSet& out, Json& outputs, Report& report, const Logger& log,
                         RefinedGrid* refined = nullptr);

}  // namespace aq::app

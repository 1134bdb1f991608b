// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional`, after the ROMS grid file: the nesting data of the regional grid in the
// global mesh it is handed off from (ARCHITECTURE §6; handoff/nesting.hpp), <name>_nesting.nc
// beside <name>_grd.nc. Written when the grid is complete, the ROMS file is enabled and
// roms.global_config names the global run (as every config `aquatoria blocks` writes does).
#pragma once

#include <string>

#include "app/regional_roms.hpp"
#include "config/regional.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/regional.hpp"

namespace aq::app {

/// Whether write_regional_nesting() has work for this config and result.
bool wants_regional_nesting(const config::RegionalConfig& c, const curvilinear::RegionalResult& result);

/// Takes the global mesh of roms.global_config from `global` (run once, shared with the ROMS
/// step: the same pipeline as `aquatoria mesh`, with triangles), builds the C-grid of `result` as the ROMS file does
/// (roms.earth_radius_m, roms.distances), locates every boundary ρ/u/v point and writes
/// <name>_nesting.nc through `out`; appends it to `outputs`, adds a "nesting" report section and
/// logs "nesting: done ...", with a warning when points fall outside the global wet mesh.
/// Throws what the writer throws.
void write_regional_nesting(const config::RegionalConfig& c, const std::string& config_source,
                            const curvilinear::RegionalResult& result, const curvilinear::CGrid& cg,
                            const RegionalGlobal& global, OutputSet& out, Json& outputs, Report& report,
                            const Logger& log);

}  // namespace aq::app

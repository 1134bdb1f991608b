// `aquatoria regional`, after the ROMS grid file: the ROMS contact points of this grid (the child,
// receiver) in the parent regional ROMS grid named by [nesting] parent (handoff/contact_points.hpp),
// <name>_contact.nc beside <name>_grd.nc (io/contact_netcdf.hpp; ROMS nesting.cdl).
#pragma once

#include <string>

#include "config/regional.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/regional.hpp"

namespace aq::app {

/// Whether write_regional_contact() has work: a complete grid and nesting.parent set.
bool wants_regional_contact(const config::RegionalConfig& c, const curvilinear::RegionalResult& result);

/// Reads the parent grid, builds the C-grid of `result` as the ROMS file does (roms.earth_radius_m,
/// roms.distances), computes the contact points and writes <name>_contact.nc through `out`;
/// appends it to `outputs`, adds a "contact" report section and logs "contact: done N points ...".
/// Throws ConfigError naming `config_source` when a child point lies outside the parent, InputError
/// for an unreadable parent file.
void write_regional_contact(const config::RegionalConfig& c, const std::string& config_source,
                            const curvilinear::RegionalResult& result, OutputSet& out, Json& outputs, Report& report,
                            const Logger& log);

}  // namespace aq::app

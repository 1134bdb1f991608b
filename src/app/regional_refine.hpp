// `aquatoria regional` for a refinement grid ([nesting] refine_factor, parent_box): the grid is not
// built from a contour but cut from the parent's ROMS grid file, the parent's ψ cells
// parent_box split refine_factor × refine_factor in the parent's own conformal plane
// (curvilinear/refine.hpp), as ROMS's coarse2fine.m lays a refinement grid over its parent; then
// the usual outputs (xygrid, ROMS grid file with depth and mask from roms.global_config, pictures,
// global nesting data) and <name>_contact.nc, the ROMS contact points of both contact regions
// (handoff/contact_points.hpp).
#pragma once

#include <string>
#include <vector>

#include "config/regional.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/refine.hpp"
#include "curvilinear/regional.hpp"
#include "io/contact_netcdf.hpp"

namespace aq::app {

/// Padding, in fine cells, of the fine grid the contact points are taken from (ROMS's band reaches
/// 3 fine rows past the grid; one more keeps its metrics centred).
inline constexpr int kRefinePad = 4;

struct RefinedGrid {
  curvilinear::RegionalResult result;  ///< completed = grid: the fine supergrid and the parent's projection
  curvilinear::Grid2D padded;          ///< the fine supergrid kRefinePad cells wider on every side
  curvilinear::Grid2D parent_plane;    ///< the parent's supergrid in the same plane
  curvilinear::RefineBox box;
  io::RomsGridFields parent;
  std::vector<double> parent_h_on_grid;  ///< the parent's h at the fine ρ points (depth blending)
  std::string projection_source;         ///< where the plane came from (the parent's attributes, or a fallback)
};

/// Reads nesting.parent and cuts the refinement grid. Throws InputError for an unreadable parent,
/// ConfigError naming `config_source` and nesting.parent_box when the box does not fit the parent.
RefinedGrid build_refinement(const config::RegionalConfig& c, const std::string& config_source, const Logger& log,
                             Report* report);

/// Writes <name>_contact.nc and <name>_in_parent.png (the parent's ROMS grid with this grid outlined)
/// for `grid` through `out`, appends it to `outputs`, adds a "contact"
/// report section and logs "contact: done ...".
void write_refinement_contact(const config::RegionalConfig& c, const std::string& config_source,
                              const RefinedGrid& grid, OutputSet& out, Json& outputs, Report& report,
                              const Logger& log);

}  // namespace aq::app

// SPDX-License-Identifier: GPL-3.0-or-later
// `aquatoria regional` for a refinement grid ([nesting] refine_factor, parent_box): the grid is not
// built from a contour but cut from the parent's ROMS grid file, the parent's ψ cells
// parent_box split refine_factor × refine_factor in the parent's own conformal plane
// (curvilinear/refine.hpp), as ROMS's coarse2fine.m lays a refinement grid over its parent; then
// the usual outputs (xygrid, ROMS grid file with depth and mask from roms.global_config, pictures,
// global nesting data) and <name>_contact.nc, the ROMS contact points of both contact regions
// (handoff/contact_points.hpp). The parent's h and masks over the refinement are made consistent
// with the fine grid's (handoff/nested_bathymetry.hpp: the order of operations) and written as a
// new parent grid file, <name>_parent_grd.nc; the input parent file is never changed.
#pragma once

#include <string>
#include <vector>

#include "config/regional.hpp"
#include "core/log.hpp"
#include "core/output_files.hpp"
#include "core/report.hpp"
#include "curvilinear/common/refine.hpp"
#include "curvilinear/regional.hpp"
#include "curvilinear/common/roms_depth.hpp"
#include "grid_files/contact_netcdf.hpp"
#include "handoff/contact_points.hpp"
#include "mask/regional_mask.hpp"

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
  std::string projection_source;  ///< where the plane came from (the parent's attributes, or a fallback)
  // Set by write_regional_roms (handoff/nested_bathymetry.hpp): the parent with its h and masks made
  // consistent with this grid (written as <name>_parent_grd.nc), and this grid file's h and masks.
  bool nested = false;
  io::RomsGridFields parent_nested;
  handoff::ReceiverValues receiver;
  double parent_rmax = 0.0;    ///< the r-factor bound the parent was smoothed to
  std::string nested_summary;  ///< for the parent file's attributes
};

/// The updated parent grid a refinement run writes beside its own files: <name>_parent_grd.nc.
std::string nested_parent_file(const config::RegionalConfig& c);

/// Reads nesting.parent and cuts the refinement grid. Throws InputError for an unreadable parent,
/// ConfigError naming `config_source` and nesting.parent_box when the box does not fit the parent,
/// or naming nesting.parent when <name>_parent_grd.nc in output.dir would be that file.
RefinedGrid build_refinement(const config::RegionalConfig& c, const std::string& config_source, const Logger& log,
                             Report* report);

/// The masks and depths of a refinement grid and of its parent made consistent
/// (handoff/nested_bathymetry.hpp): `masks` (this grid's, from the global ocean) get the parent's
/// mask on the outer ring, the depth is the blended, smoothed and block-averaged one, and the
/// updated parent and this grid's h and masks are stored in `g` for write_refinement_contact.
/// The parent keeps its own r-factor where it is rougher than roms.rmax. Warns when the rounds do
/// not settle.
struct NestedDepths {
  curvilinear::DepthResult depth;  ///< this grid's h and the clip/smoothing counts
  double blend_change_m = 0.0;     ///< largest change the blend made to hraw
  Json report;                     ///< the report's "nested" section
  std::string line;                ///< for the roms stage's log line
};
NestedDepths nest_in_parent(const config::RegionalConfig& c, const curvilinear::CGrid& cg,
                            const std::vector<double>& hraw, const curvilinear::DepthOptions& dopt,
                            mask::RomsMasks& masks, RefinedGrid& g, const Logger& log);

/// Writes <name>_parent_grd.nc (the parent grid file with the h and masks write_regional_roms made
/// consistent with this grid; build_refinement made sure it is not the parent file itself),
/// <name>_contact.nc (its receiver values those of the two grid files) and <name>_in_parent.png
/// (the parent's ROMS grid with this grid outlined) for `grid` through `out`, appends them to
/// `outputs`, adds a "contact" report section and logs "contact: done ...". Without the ROMS
/// file (roms.enabled = false) only the contact points and the picture are written, from the
/// parent as it is.
void write_refinement_contact(const config::RegionalConfig& c, const std::string& config_source,
                              const RefinedGrid& grid, OutputSet& out, Json& outputs, Report& report,
                              const Logger& log);

}  // namespace aq::app

// SPDX-License-Identifier: GPL-3.0-or-later
// Configuration of a regional grid run (`aquatoria regional -c FILE.toml`, ARCHITECTURE §5, §7).
// The [regional] keys are exactly the izogrid file's keys (curvilinear/izogrid_file.hpp), set by
// the same function, so a TOML config and a seed-format .izogrid file mean the same thing;
// `contour_file` may name an .izogrid file whose preamble and points are read first (TOML keys
// then override its preamble). [input] names the bathymetry for the coastline (and ROMS depths).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "config/load.hpp"
#include "config/options.hpp"
#include "grid_params/regional_params.hpp"

namespace aq::config {

/// [roms] The ROMS grid file (<name>_grd.nc) of a complete grid (app/regional_roms.hpp).
struct RomsOptions {
  bool enabled = true;  ///< write <name>_grd.nc and <name>_roms.png after the grid
  /// The global run's TOML (resolved path) whose input, mask, quadtree and rotation define the
  /// bathymetry, the lattice, the threshold h and the K-fill Ω_L; "" = the built-in defaults (the
  /// seed's reference run on ETOPO5).
  std::string global_config;
  /// XXH64 (file_checksum) of global_config as `aquatoria blocks` wrote it beside this block's
  /// config; a run refuses when the file now differs. "" = not checked (hand-written configs).
  std::string global_config_checksum;
  double hmin_m = 10.0;  ///< minimum depth h is clipped to (m, (0, 12000])
  /// r-factor bound of the depth smoothing, [0, 1); 0 = none. The default 0.2 gives the rx0 ≤ 0.2
  /// ROMS users expect of a model-ready grid.
  double rmax = 0.2;
  curvilinear::DistanceModel distances = curvilinear::DistanceModel::kSphere;  ///< how pm, pn measure lengths
  double earth_radius_m = 6371000.0;  ///< sphere radius of the ROMS metrics and x/y (m, > 0)
  /// Elevation of a ρ cell from the raster (mask/cell_elevation.hpp); kAuto = mean when the
  /// raster is finer than the cells, else point.
  CellStatistic depth_statistic = CellStatistic::kAuto;
};

/// [nesting] A parent regional ROMS grid this grid is a refinement of (ROMS refinement nesting,
/// app/regional_refine.hpp). With refine_factor > 0 the grid is not built from a contour: it is
/// the parent's ψ-cell box parent_box split refine_factor × refine_factor (as ROMS's
/// coarse2fine.m lays a refinement grid over its parent), and <name>_contact.nc holds the ROMS
/// contact points of both contact regions (nesting.cdl).
struct NestingOptions {
  /// The parent's ROMS grid file (<parent>_grd.nc, resolved path); "" = none.
  std::string parent;
  /// Odd refinement factor r, 3..55 (ROMS's fine-to-coarse averaging needs odd r); 0 = none.
  int refine_factor = 0;
  /// Parent ψ-point indices (ROMS's 1-based I, J of ψ) of the refinement grid's corners:
  /// I_left, I_right, J_bottom, J_top; all 0 = not set.
  std::array<int, 4> parent_box{0, 0, 0, 0};
  /// Fine ρ rows next to the boundary over which the model depth h blends from the parent's h
  /// (interpolated; what ROMS copies onto the outer ring) into the grid's own; 0 = no blending.
  int blend_cells = 6;

  [[nodiscard]] bool refinement() const { return refine_factor > 0; }
};

struct RegionalConfig {
  curvilinear::RegionalParams params;  ///< [regional] izogrid keys, control_points, corners
  std::string name = "regional";       ///< [regional] name: base name of the output files
  std::string contour_file;            ///< [regional] contour_file: .izogrid file read first (resolved path)
  std::optional<curvilinear::Stage> stop_after;  ///< [regional] stop_after; none ("") = from regional.mode
  std::vector<int> corners;            ///< [regional] corners: 1-based point numbers of the 4 corners
  std::vector<int> corners2;           ///< [regional] block2_corners: the same for block2_points
  InputOptions input;                  ///< [input] bathymetry for the coastline and depths
  double coast_level_m = 0.0;          ///< [input] coast_level_m: elevation of the drawn coastline
  std::string output_dir = "out";      ///< [output] dir
  RomsOptions roms;                    ///< [roms]
  NestingOptions nesting;              ///< [nesting]
};

/// Reads a regional TOML config (or, when `path` ends in .izogrid, the seed's file format alone)
/// and applies `overrides` (section.key=value). Throws ConfigError listing every problem, or
/// InputError for an unreadable/malformed izogrid file.
Loaded<RegionalConfig> load_regional(const std::string& path, const std::vector<std::string>& overrides);

/// Every key of the regional TOML configuration as "section.key".
std::vector<std::string> regional_keys();
/// Every key of the regional configuration, in documentation order.
std::vector<KeyInfo> regional_key_info();

/// The stage a run of `c` stops after: `command_line` (--stop-after) when given, else
/// regional.stop_after, else the one of regional.mode.
curvilinear::Stage stop_stage(const RegionalConfig& c, std::optional<curvilinear::Stage> command_line = {});
/// Why a run of `c` cannot stop after `stage` (none when it can): a method without a conformal
/// stage asked to stop after it, a refinement grid (cut from its parent in one step) asked to stop
/// before the grid. load_regional() reports these for regional.stop_after / regional.mode; the
/// command line checks --stop-after with it.
std::vector<KeyProblem> stop_stage_problems(const RegionalConfig& c, curvilinear::Stage stage);

}  // namespace aq::config

// SPDX-License-Identifier: GPL-3.0-or-later
// The files `aquatoria blocks` writes for one block (ARCHITECTURE §6): a seed-format contour file
// (.izogrid, digest izogrid.md §2: key=value preamble, a dash line, control points
// counter-clockwise from the SW corner with the corners labelled) holding the projection and the
// contour, and a regional TOML config (configs/example_regional.toml) that names it and holds the
// run settings, loadable by `aquatoria regional -c`. src/handoff does not include TOML: the text
// is generated here with TOML's basic-string escaping.
#pragma once

#include <string>

#include "core/report.hpp"
#include "handoff/block_contour.hpp"

namespace aq::handoff {

/// Run settings of a block's regional config.
struct BlockConfigInfo {
  std::string name;          ///< block_NNN: base name of the regional outputs
  std::string izogrid_file;  ///< the contour file's name, relative to the config's folder
  std::string description;   ///< one line: what the block is and how it ranked
  int ny = 50;               ///< cells along η
  std::string input_path;    ///< bathymetry of the global run (absolute)
  std::string input_variable;
  bool positive_down = false;
  double coast_level_m = 0.0;       ///< −h of the global run: the coastline the global mask uses
  std::string output_dir;           ///< where the regional outputs go (absolute)
  std::string global_config;        ///< absolute path of the global config; written as [roms] global_config
  bool write_global_config = true;  ///< false when the regional schema has no such key (a comment then)
  /// XXH64 of the global config file as written (roms.global_config_checksum); "" = none.
  std::string global_config_checksum;
};

/// TOML basic string (quoted, with \, " and control characters escaped).
std::string toml_string(const std::string& text);

/// The .izogrid text of a block contour: `comment` lines (prefixed with '#'), the preamble
/// (proj, rlat, rlon, rota, uscale, ny, nx = 0, spline_type = 5, latlongrid), the dash line and
/// the points with the corner labels south-west, < south-east, < north-east, < north-west.
std::string izogrid_text(const BlockContour& contour, int ny, double latlongrid_deg, const std::string& comment);

/// The regional TOML config of a block (see BlockConfigInfo).
std::string regional_config_text(const BlockConfigInfo& info);

/// A TOML config from an effective configuration echo ({section: {key: value}}, as
/// config::load_global gives it): strings, numbers, booleans, arrays and arrays of tables (as
/// inline tables), with `comment` lines first. Loading it gives the same configuration, so the
/// blocks' regional runs see exactly the global run `aquatoria blocks` ranked, --set overrides
/// included. Throws InternalError for a JSON value TOML cannot hold (null).
std::string config_text_from_echo(const Json& echo, const std::string& comment);

}  // namespace aq::handoff

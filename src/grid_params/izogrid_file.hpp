// SPDX-License-Identifier: GPL-3.0-or-later
// Reader of the seed's izogrid input file (seed 000 Appendix 1 and Fig. 3; digest izogrid.md
// §2.1–2.3; ARCHITECTURE §5 "Input compatibility").
//
//   mode=1 latlongrid=2 spline_type=4 npass=4      <- preamble: key=value tokens, any number per
//   proj=ME rlat=43.75 rlon=34.5 rota=0               line, separated by blanks
//   ...
//   –––                                            <- end of preamble: a line of ≥ 3 dashes
//   -97  -26    south-west                            ('-', '–' U+2013 or '—' U+2014)
//   -77  -39.5                                     <- points: x y [label], counter-clockwise
//   +104 -33    < south-east                          from the SW corner (the first point);
//   ...                                               a label starting with '<' or naming a
//                                                     corner (south-east, north-east,
//                                                     north-west) marks a corner
//
// '#' starts a comment anywhere. Keys are the seed's (mode, gshhs_data, proj, rlat, rlon, rota,
// south_edge, north_edge, west_edge, east_edge, latlongrid, uscale, spline_type, nx, ny, npass,
// lwidth, xygrid) plus aquatoria's (lat1, lat2, radius, param, points, auto_nx, schedule,
// tolerance, max_outer, max_inner, interp_points, inner_rtol, anderson, solver, threads, method,
// surface, bvp_iterations, bvp_interpolation, bvp_ratio_xi, bvp_ratio_eta); see
// RegionalParams for meanings and ranges.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "grid_params/regional_params.hpp"

namespace aq::curvilinear {

/// Parses izogrid text; `source` (usually the file name) prefixes every message as
/// "source:line: ...". All problems are collected and reported in one exception:
/// ConfigError for unknown or repeated keys, tokens that are not key=value, and bad values
/// (naming key and value) and out-of-range values (validate_regional_params);
/// InputError for a missing end-of-preamble line, malformed point lines, corner labels out of
/// order, and a number of corners other than 4 (giving how many and on which lines).
/// The result has source = `source` and input_text = `text`.
RegionalParams parse_izogrid(std::string_view text, const std::string& source);

/// Sets one parameter by its izogrid key from its text value (the same rules as the file's
/// preamble; the TOML config uses this too, so both formats share keys and checks). Returns an
/// empty string on success, otherwise why the value is bad; "unknown key" for a key it doesn't know.
std::string set_izogrid_key(RegionalParams& params, const std::string& key, std::string_view value);
/// Every key set_izogrid_key() knows, sorted.
std::vector<std::string> izogrid_keys();
/// The names an enumerated key takes (its table in grid_kinds.hpp, without aliases), or none.
std::vector<std::string> izogrid_key_values(const std::string& key);

/// Reads and parses an izogrid file. InputError if it cannot be read; otherwise as parse_izogrid.
RegionalParams read_izogrid_file(const std::filesystem::path& path);

}  // namespace aq::curvilinear

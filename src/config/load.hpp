// SPDX-License-Identifier: GPL-3.0-or-later
// Loading configurations: read -> validate (all problems in one ConfigError) -> echo.
// Relative input paths resolve against the configuration file's folder; output.dir is relative
// to the working directory (so `-c configs/x.toml` writes to ./out by default).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "core/report.hpp"

namespace aq::config {

/// A loaded configuration and its effective values as JSON (for the run report).
template <typename T>
struct Loaded {
  T options;
  Json echo;
  std::string source;  ///< the file, or "built-in defaults"
};

/// What a global configuration is loaded for: the command's own refusals join the checks at load.
enum class GlobalUse {
  kMesh,        ///< `aquatoria mesh` (and the Python binding)
  kBlocks,      ///< `aquatoria blocks`: its blocks become ROMS grids (no floodplain)
  kRomsGlobal,  ///< roms.global_config of a regional ROMS grid (no floodplain, one raster)
  kMask,        ///< the mask and levels of a run (Python's mask()): the dense engine's bitmaps
};

/// Reads the global-run configuration from `path` (or the built-in defaults when empty) and
/// applies `overrides` ("section.key=value"). Throws ConfigError listing every problem, each at
/// the position of the value at fault: bad values, keys that contradict each other, what the
/// forest engine (quadtree.engine = "forest") cannot do, and what `use` cannot take.
Loaded<GlobalConfig> load_global(const std::optional<std::string>& path, const std::vector<std::string>& overrides,
                                 GlobalUse use = GlobalUse::kMesh);

/// Whether this build has the forest engine (AQ_MPI: p4est and MPI); without it load_global
/// refuses quadtree.engine = "forest".
bool forest_engine_built();

/// A depth or box rule as the user gives it in [quadtree]: its range fields, then `size_km` when
/// it is a size rule (size_km != 0), else `level`. The echo of quadtree.depth_rules / box_rules.
Json rule_json(const DepthRule& r);
Json rule_json(const BoxRule& r);

/// Every key of the global configuration as "section.key", in documentation order.
std::vector<std::string> global_keys();

/// One key of a configuration as the help text and the Python binding show it.
struct KeyInfo {
  std::string key;                  ///< "section.key"
  Json default_value;               ///< the built-in default, as the run report echoes it
  std::string help;                 ///< what it sets; for an enumerated key every name and its meaning
  std::vector<std::string> values;  ///< the names an enumerated key takes; empty for other keys
};
/// Every key of the global configuration, in documentation order.
std::vector<KeyInfo> global_key_info();

/// Why `name` cannot be output.name (a plain file name: not empty, no '/', not "." or ".."), or "".
std::string output_name_problem(const std::string& name);

/// A problem of one or more keys together, for callers that report it at their position.
struct KeyProblem {
  std::vector<std::string> keys;
  std::string text;
};
/// What is wrong with `o` for a mesh of `elements` (a model format or a coloured preview without
/// triangles). load_global() reports these; a caller that changes output options afterwards (the
/// Python binding's write) checks them again.
std::vector<KeyProblem> output_problems(const OutputOptions& o, ElementKinds elements);

/// The values of an enumerated option named in `names` (e.g. output.formats from Python), each
/// as E's table has it; ConfigError naming `key` and the first unknown name.
template <NamedEnum E>
std::vector<E> parse_names(const std::vector<std::string>& names, const std::string& key) {
  std::vector<E> out;
  for (const std::string& n : names) {
    const std::optional<E> e = parse_name<E>(n);
    if (!e) throw ConfigError(key + ": " + unknown_name_message<E>(n));
    out.push_back(*e);
  }
  return out;
}

/// The base name of a run without a config file and without output.name, and why.
struct RunName {
  std::string name;
  /// Keys outside [output] and [blocks] whose effective value differs from the built-in
  /// default, as "section.key = value", in documentation order; empty for the seed's run.
  std::vector<std::string> changed;
  /// Those of `changed` the name does not show: a run differing only there writes the same files.
  std::vector<std::string> unnamed;
};

/// "seed_4deg_L3" when the mesh-defining values of `c` (every section but [output] and [blocks])
/// are the built-in defaults (the seed's reference run); otherwise a name that follows them:
/// "global_<Δ0>_L<L>" with Δ0 as "<n>deg", "<n>min" or "<n>sec" (the step in whole arc-seconds),
/// then "_h<h>" (h ≠ 0), "_K<K>" (K ≠ 2), "_rot" (rotated pole), "_<raster stem>" (another
/// input.path), "_corner" (corner balance), "_cb<n>" (coast_band ≠ 2), "_squares" / "_both"
/// (elements); e.g. global_1deg_L3, global_16min_L4_h200_K3_rot.
RunName default_run_name(const GlobalConfig& c);

}  // namespace aq::config

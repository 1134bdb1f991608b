// Loading configurations: read -> validate (all problems in one ConfigError) -> echo.
// Relative input paths resolve against the configuration file's folder; output.dir is relative
// to the working directory (so `-c configs/x.toml` writes to ./out by default).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "config/options.hpp"
#include "core/report.hpp"

namespace aq::config {

/// A loaded configuration and its effective values as JSON (for the run report).
template <typename T>
struct Loaded {
  T options;
  Json echo;
  std::string source;  ///< the file, or "built-in defaults"
};

/// Reads the global-run configuration from `path` (or the built-in defaults when empty) and
/// applies `overrides` ("section.key=value"). Throws ConfigError listing every problem.
Loaded<GlobalConfig> load_global(const std::optional<std::string>& path, const std::vector<std::string>& overrides);

/// A depth or box rule as the user gives it in [quadtree]: its range fields, then `size_km` when
/// it is a size rule (size_km != 0), else `level`. The echo of quadtree.depth_rules / box_rules.
Json rule_json(const DepthRule& r);
Json rule_json(const BoxRule& r);

/// Every key of the global configuration as "section.key", in documentation order.
std::vector<std::string> global_keys();

/// The base name of a run without a config file and without output.name, and why.
struct RunName {
  std::string name;
  /// Keys outside [output] and [blocks] whose effective value differs from the built-in
  /// default, as "section.key = value", in documentation order; empty for the seed's run.
  std::vector<std::string> changed;
};

/// "seed_4deg_L3" when the mesh-defining values of `c` (every section but [output] and [blocks])
/// are the built-in defaults (the seed's reference run); otherwise a name that follows them:
/// "global_<Δ0>_L<L>" with Δ0 as "<n>deg", "<n>min" or "<n>sec" (the step in whole arc-seconds),
/// then "_h<h>" (h ≠ 0), "_K<K>" (K ≠ 2), "_rot" (rotated pole), "_<raster stem>" (another
/// input.path), "_corner" (corner balance), "_cb<n>" (coast_band ≠ 2), "_squares" / "_both"
/// (elements); e.g. global_1deg_L3, global_16min_L4_h200_K3_rot.
RunName default_run_name(const GlobalConfig& c);

}  // namespace aq::config

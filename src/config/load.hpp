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

/// Every key of the global configuration as "section.key", in documentation order.
std::vector<std::string> global_keys();

}  // namespace aq::config

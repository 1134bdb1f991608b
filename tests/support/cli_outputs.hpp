// SPDX-License-Identifier: GPL-3.0-or-later
// Output folders and reports of `aquatoria` runs in CLI tests.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace aq::test {

/// An empty (removed) folder `<tmp>/aq_<prefix>_<name>_<pid>` for a run's outputs.
inline std::filesystem::path fresh_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("aq_" + prefix + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d;
}

/// The run report `<dir>/<name>_report.json`.
inline nlohmann::json read_report(const std::filesystem::path& dir, const std::string& name) {
  return nlohmann::json::parse(std::ifstream(dir / (name + "_report.json")));
}

}  // namespace aq::test

// SPDX-License-Identifier: GPL-3.0-or-later
// Test helper for the real-model clients in ../shared/clients: their `key: value` summaries.
#pragma once

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

namespace aq::test {

/// The `key: value` lines of a client's summary (stdout).
inline std::map<std::string, std::string> key_values(const std::string& text) {
  std::map<std::string, std::string> kv;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(": ");
    if (colon != std::string::npos) kv[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return kv;
}

/// ../shared/clients/<name>/<script> beside the repository.
inline std::filesystem::path client_script(const std::string& name, const std::string& script) {
  return std::filesystem::path(AQ_SOURCE_DIR).parent_path() / "shared" / "clients" / name / script;
}

}  // namespace aq::test

// SPDX-License-Identifier: GPL-3.0-or-later
// What a run was made from (see provenance.hpp).
#include "app/provenance.hpp"

#include <fmt/format.h>

#include <fstream>

#include "core/output_files.hpp"

namespace aq::app {

namespace fs = std::filesystem;

void start_report(Report& report, const char* command, const std::string& config_source, const Json& echo) {
  report["command"] = command;
  report["config_source"] = config_source;
  report["config"] = echo;
}

std::vector<std::string> config_differences(const Json& before, const Json& after) {
  std::vector<std::string> out;
  const auto value_at = [](const Json& j, const std::string& sec, const std::string& key) -> const Json* {
    if (!j.is_object() || !j.contains(sec) || !j[sec].is_object() || !j[sec].contains(key)) return nullptr;
    return &j[sec][key];
  };
  const auto text = [](const Json* v) { return v == nullptr ? std::string("(absent)") : v->dump(); };
  if (after.is_object())
    for (const auto& [sec, keys] : after.items()) {
      if (!keys.is_object()) continue;
      for (const auto& [key, value] : keys.items()) {
        const Json* old = value_at(before, sec, key);
        if (old == nullptr || *old != value) out.push_back(fmt::format("{}.{}: {} -> {}", sec, key, text(old), value.dump()));
      }
    }
  if (before.is_object())
    for (const auto& [sec, keys] : before.items()) {
      if (!keys.is_object()) continue;
      for (const auto& [key, value] : keys.items())
        if (value_at(after, sec, key) == nullptr) out.push_back(fmt::format("{}.{}: {} -> (absent)", sec, key, value.dump()));
    }
  return out;
}

std::string join_some(const std::vector<std::string>& items, std::size_t max) {
  std::string s;
  for (std::size_t k = 0; k < items.size() && k < max; ++k) s += (k == 0 ? "" : "; ") + items[k];
  if (items.size() > max) s += fmt::format("; … ({} more)", items.size() - max);
  return s;
}

std::optional<Json> read_report(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream f(path);
  Json j = Json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  return j;
}

Json input_record(const fs::path& file, const Json& config) {
  Json r{{"file", fs::absolute(file).lexically_normal().string()}, {kChecksumKey, file_checksum(file)}};
  if (!config.is_null()) r["config"] = config;
  return r;
}

std::vector<std::string> differences_from_earlier(const Json& old_report, const Json& echo, const Json& inputs) {
  std::vector<std::string> d;
  if (old_report.contains("config")) d = config_differences(old_report["config"], echo);
  if (!old_report.contains("inputs") || !old_report["inputs"].is_object() || !inputs.is_object()) return d;
  const Json& before = old_report["inputs"];
  for (const auto& [key, now] : inputs.items()) {
    if (!before.contains(key)) continue;
    const Json& was = before[key];
    if (was.value("file", "") != now.value("file", "")) continue;  // a config key's change, listed above
    if (was.value(kChecksumKey, "") == now.value(kChecksumKey, "")) continue;
    std::string what = fmt::format("{} {} has changed (checksum {} -> {})", key, now.value("file", ""),
                                   was.value(kChecksumKey, ""), now.value(kChecksumKey, ""));
    if (was.contains("config") && now.contains("config")) {
      const auto inner = config_differences(was["config"], now["config"]);
      if (!inner.empty()) what += ": made with " + join_some(inner, 4);
    }
    d.push_back(what);
  }
  return d;
}

void warn_if_overwriting(const fs::path& dir, const std::string& report_name, const Json& echo, const Json& inputs,
                         const std::string& name_hint, const Logger& log) {
  const fs::path path = dir / report_name;
  const auto old = read_report(path);
  if (!old) return;
  const auto d = differences_from_earlier(*old, echo, inputs);
  if (d.empty()) return;
  log.warn("{}: this run overwrites the outputs of an earlier run made from other inputs ({}); {}", path.string(),
           join_some(d), name_hint);
}

}  // namespace aq::app

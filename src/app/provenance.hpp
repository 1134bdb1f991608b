// SPDX-License-Identifier: GPL-3.0-or-later
// What a run was made from, and what changed since (the hand-off a user can trust): every run
// report lists its inputs ("inputs": file, checksum, and the configuration that made the file when
// aquatoria wrote it), so a later run can tell, before it overwrites the outputs of an earlier
// one, whether they were made from other inputs, and say which keys or files differ.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/log.hpp"
#include "core/report.hpp"

namespace aq::app {

/// The head of a command's run report: "command", "config_source" (the configuration file, or
/// "built-in defaults") and "config" (its echo), in that order.
void start_report(Report& report, const char* command, const std::string& config_source, const Json& echo);

/// The keys whose values differ between two configuration echoes ({section: {key: value}}), as
/// "section.key: old -> new" (or "(absent)"), in the order of `after`, then keys only in `before`.
std::vector<std::string> config_differences(const Json& before, const Json& after);

/// At most `max` of `items` joined by "; ", with "; … (N more)" when some were left out.
std::string join_some(const std::vector<std::string>& items, std::size_t max = 6);

/// The JSON report at `path`, or nothing when it is absent or not JSON (never throws).
std::optional<Json> read_report(const std::filesystem::path& path);

/// One input of a run: {"file": absolute path, "checksum_xxh64": ..., "config": echo (optional)}.
Json input_record(const std::filesystem::path& file, const Json& config = Json());

/// The earlier report `old_report` (from read_report of the run's report path) against this run's
/// configuration echo and inputs: one line per difference ("regional.method: \"conformal\" ->
/// \"ed2\"", "input roms.global_config /x/global.toml: checksum a -> b"); empty when the earlier
/// run had the same configuration and inputs, or there is none.
std::vector<std::string> differences_from_earlier(const Json& old_report, const Json& echo, const Json& inputs);

/// Logs a warning when this run is about to overwrite outputs in `dir` (the report `report_name`
/// there) made from other inputs, naming them and `name_hint` (how to keep both).
void warn_if_overwriting(const std::filesystem::path& dir, const std::string& report_name, const Json& echo,
                         const Json& inputs, const std::string& name_hint, const Logger& log);

}  // namespace aq::app

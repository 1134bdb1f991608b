// SPDX-License-Identifier: GPL-3.0-or-later
// The run report: an ordered JSON document (parameters, counts, timings, checksums) that every
// command fills in, plus per-stage timing with the "stage: done ... (t s)" line on the logger.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "core/cancel.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"

namespace aq {

using Json = nlohmann::ordered_json;

/// Accumulates the run report. Sections are free-form JSON; "stages" is filled by StageScope.
class Report {
 public:
  Report();
  Json& root() { return root_; }
  [[nodiscard]] const Json& root() const { return root_; }
  Json& operator[](const std::string& key) { return root_[key]; }

  /// Records one finished stage: wall, CPU seconds and peak RSS (MB) so far.
  void add_stage(const std::string& name, double wall_s, double cpu_s, const std::string& summary);
  /// Sets totals (wall/CPU since the report was created, peak RSS).
  void finish();
  [[nodiscard]] std::string dump() const { return root_.dump(2); }

 private:
  Json root_;
  Timer total_;
};

/// Times one stage; on done() logs "stage: done <summary> (t s)" and adds it to the report.
class StageScope {
 public:
  /// Starts a stage; throws Cancelled when the run has been asked to stop (core/cancel.hpp).
  StageScope(std::string name, Report* report, const Logger& log) : name_(std::move(name)), report_(report), log_(log) {
    throw_if_cancelled();
  }
  /// Ends the stage with a one-line summary of what it produced; then throws Cancelled when the
  /// run has been asked to stop meanwhile.
  void done(const std::string& summary);
  [[nodiscard]] double wall_s() const { return timer_.wall_s(); }

 private:
  std::string name_;
  Report* report_;
  const Logger& log_;
  Timer timer_;
  bool finished_ = false;
};

}  // namespace aq

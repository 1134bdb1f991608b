// SPDX-License-Identifier: GPL-3.0-or-later
// Run report and stage timing.
#include "core/report.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aq {

namespace {
double round3(double x) { return std::round(x * 1000.0) / 1000.0; }
}  // namespace

Report::Report() {
  root_["tool"] = "aquatoria";
  root_["stages"] = Json::array();
}

void Report::add_stage(const std::string& name, double wall_s, double cpu_s, const std::string& summary) {
  root_["stages"].push_back(Json{{"stage", name},
                                 {"summary", summary},
                                 {"wall_s", round3(wall_s)},
                                 {"cpu_s", round3(cpu_s)},
                                 {"peak_rss_mb", round3(static_cast<double>(peak_rss_bytes()) / 1048576.0)}});
}

void Report::finish() {
  root_["total"] = Json{{"wall_s", round3(total_.wall_s())},
                        {"cpu_s", round3(total_.cpu_s())},
                        {"peak_rss_mb", round3(static_cast<double>(peak_rss_bytes()) / 1048576.0)}};
}

void StageScope::done(const std::string& summary) {
  if (finished_) return;
  finished_ = true;
  const double wall = timer_.wall_s();
  const double cpu = timer_.cpu_s();
  log_.info("{}: done {} ({:.3f} s)", name_, summary, wall);
  if (report_ != nullptr) report_->add_stage(name_, wall, cpu, summary);
  throw_if_cancelled();
}

}  // namespace aq

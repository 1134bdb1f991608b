// SPDX-License-Identifier: GPL-3.0-or-later
// Ordered writing of planned output files, one of them beside the others (see output_jobs.hpp).
#include "app/output_jobs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <future>

#include "core/output_files.hpp"
#include "core/timer.hpp"

namespace aq::io {

namespace {

std::string facts_text(const Facts& facts) {
  std::string s;
  for (const auto& [k, v] : facts) s += fmt::format(", {} {}", v, k);
  return s;
}

WrittenFile write_one(const OutputJob& job) {
  const Timer timer;
  WrittenFile w;
  w.stats = job.writer(job.temp_path);
  w.seconds = timer.wall_s();
  w.checksum = file_checksum(job.temp_path);
  w.name = job.name;
  w.format = job.format;
  w.path = job.final_path;
  w.bytes = w.stats.bytes;
  w.facts = job.facts ? job.facts(w.stats) : Facts{};
  return w;
}

}  // namespace

std::vector<WrittenFile> write_output_jobs(std::vector<OutputJob> jobs, const std::vector<LogLine>& trailing,
                                           bool concurrent, const Logger& log) {
  const std::size_t n = jobs.size();
  std::vector<WrittenFile> written(n);
  std::vector<std::vector<LogLine>> step_lines(n);
  std::vector<std::exception_ptr> failure(n);
  // finished[k]: job k's writer has returned or thrown (set and read by the calling thread only;
  // the extra thread's jobs count as finished once that thread is done).
  std::vector<char> finished(n, 0);
  auto run = [&](std::size_t k) {
    try {
      if (jobs[k].step) {
        step_lines[k] = jobs[k].step();
      } else {
        written[k] = write_one(jobs[k]);
      }
      return true;
    } catch (...) {
      failure[k] = std::current_exception();
      return false;
    }
  };

  const auto own = [](const OutputJob& j) { return j.own_thread; };
  const bool beside =
      concurrent && std::any_of(jobs.begin(), jobs.end(), own) && !std::all_of(jobs.begin(), jobs.end(), own);
  auto on_extra = [&](std::size_t k) { return beside && own(jobs[k]); };
  // The extra thread runs its jobs in order and stops at its first failure. Its results are read
  // only after the future is ready (which orders its writes before the reads).
  std::future<void> extra;
  if (beside) {
    extra = std::async(std::launch::async, [&] {
      for (std::size_t k = 0; k < n; ++k)
        if (on_extra(k) && !run(k)) break;
    });
  }
  bool extra_done = !beside;

  // Logs the lines of the jobs that are finished and have every job before them finished; stops
  // before the line of a failed job (its log_before lines are logged: they came before it).
  std::size_t logged = 0;
  auto log_ready = [&] {
    for (; logged < n; ++logged) {
      const OutputJob& job = jobs[logged];
      if (on_extra(logged) ? !extra_done : !finished[logged]) return;
      for (const LogLine& line : job.log_before) log.log(line.level, line.text);
      if (failure[logged]) return;
      for (const LogLine& line : step_lines[logged]) log.log(line.level, line.text);
      if (job.step) continue;
      const WrittenFile& w = written[logged];
      log.info("output: {} ({}, {} bytes, {:.3f} s{})", w.name, w.format, w.bytes, w.seconds, facts_text(w.facts));
    }
  };

  for (std::size_t k = 0; k < n; ++k) {
    if (on_extra(k)) continue;
    const bool ok = run(k);
    finished[k] = 1;
    if (!ok) break;
    if (!extra_done) extra_done = extra.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    log_ready();
  }
  if (beside) {
    extra.get();
    extra_done = true;
  }
  log_ready();
  if (logged < n) {
    // Job `logged` failed: every job before it was written and logged.
    std::rethrow_exception(failure[logged]);
  }
  for (const LogLine& line : trailing) log.log(line.level, line.text);
  std::vector<WrittenFile> files;
  for (std::size_t k = 0; k < n; ++k) {
    if (jobs[k].step) continue;
    written[k].own_thread = on_extra(k);
    files.push_back(std::move(written[k]));
  }
  return files;
}

}  // namespace aq::io

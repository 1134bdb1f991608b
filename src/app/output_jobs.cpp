// Ordered writing of planned output files, one of them beside the others (see output_jobs.hpp).
#include "app/output_jobs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <future>
#include <mutex>

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
  std::vector<std::exception_ptr> failure(n), checksum_failure(n);
  std::vector<std::string> checksum(n);
  // finished[k]: job k's writer has returned or thrown (set and read by the calling thread only;
  // the extra thread's jobs count as finished once it has done them all).
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
  auto checksum_of = [&](std::size_t k) {
    try {
      checksum[k] = file_checksum(jobs[k].temp_path);
    } catch (...) {
      checksum_failure[k] = std::current_exception();
    }
  };

  // The files written on this thread are checksummed by whichever thread is free first: the
  // extra one once its own jobs are done, or this one after its last job.
  std::mutex queue_mutex;
  std::condition_variable queue_changed;
  std::deque<std::size_t> to_checksum;
  bool no_more = false;
  auto help_checksum = [&] {
    for (;;) {
      std::size_t k = 0;
      {
        std::unique_lock<std::mutex> lock(queue_mutex);
        queue_changed.wait(lock, [&] { return !to_checksum.empty() || no_more; });
        if (to_checksum.empty()) return;
        k = to_checksum.front();
        to_checksum.pop_front();
      }
      checksum_of(k);
    }
  };

  const auto own = [](const OutputJob& j) { return j.own_thread && !j.step; };
  const bool beside =
      concurrent && std::any_of(jobs.begin(), jobs.end(), own) && !std::all_of(jobs.begin(), jobs.end(), own);
  auto on_extra = [&](std::size_t k) { return beside && own(jobs[k]); };
  // The extra thread runs its jobs in order (each file checksummed at once) and stops at its
  // first failure; their results are read once extra_done is seen true (release/acquire). Then
  // it helps with the checksums until this thread has no more files.
  std::atomic<bool> extra_done{!beside};
  std::future<void> extra;
  if (beside) {
    extra = std::async(std::launch::async, [&] {
      for (std::size_t k = 0; k < n; ++k) {
        if (!on_extra(k)) continue;
        if (!run(k)) break;
        checksum_of(k);
      }
      extra_done.store(true, std::memory_order_release);
      help_checksum();
    });
  }
  // However this function is left, the extra thread is told that no more files come (before the
  // future's destructor waits for it).
  struct NoMore {
    std::mutex& m;
    std::condition_variable& cv;
    bool& flag;
    ~NoMore() {
      {
        const std::lock_guard<std::mutex> lock(m);
        flag = true;
      }
      cv.notify_all();
    }
  } no_more_on_exit{queue_mutex, queue_changed, no_more};

  // Logs the lines of the jobs that are finished and have every job before them finished; stops
  // before the line of a failed job (its log_before lines are logged: they came before it).
  std::size_t logged = 0;
  auto log_ready = [&] {
    for (; logged < n; ++logged) {
      const OutputJob& job = jobs[logged];
      if (on_extra(logged) ? !extra_done.load(std::memory_order_acquire) : !finished[logged]) return;
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
    if (!jobs[k].step) {
      {
        const std::lock_guard<std::mutex> lock(queue_mutex);
        to_checksum.push_back(k);
      }
      queue_changed.notify_one();
    }
    log_ready();
  }
  {
    const std::lock_guard<std::mutex> lock(queue_mutex);
    no_more = true;
  }
  queue_changed.notify_all();
  help_checksum();
  if (beside) extra.get();
  log_ready();
  if (logged < n) {
    // Job `logged` failed: every job before it was written and logged.
    std::rethrow_exception(failure[logged]);
  }
  for (const LogLine& line : trailing) log.log(line.level, line.text);
  for (const auto& e : checksum_failure)
    if (e) std::rethrow_exception(e);
  std::vector<WrittenFile> files;
  for (std::size_t k = 0; k < n; ++k) {
    if (jobs[k].step) continue;
    written[k].own_thread = on_extra(k);
    written[k].checksum = std::move(checksum[k]);
    files.push_back(std::move(written[k]));
  }
  return files;
}

}  // namespace aq::io

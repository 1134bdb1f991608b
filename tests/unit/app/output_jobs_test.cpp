// SPDX-License-Identifier: GPL-3.0-or-later
// write_output_jobs: the own_thread job really runs beside the others, yet the log lines and the
// returned files keep the jobs' order, and the error thrown is the first failure in that order
// (whichever thread failed first in time); steps run in their place, on the extra thread when
// they are own_thread.
#include "app/output_jobs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <future>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "core/output_files.hpp"
#include "support/temp_dir.hpp"

namespace aq::io::unit_app_output_jobs_test {
namespace {

struct CapturedLog {
  std::vector<std::string> lines;
  Logger logger{[this](LogLevel, std::string_view m) { lines.emplace_back(m); }};
};

// "output: a (fmt, 7 bytes, 0.000 s)" -> "output: a" (the seconds differ from run to run).
std::vector<std::string> without_times(const std::vector<std::string>& lines) {
  std::vector<std::string> out;
  for (const auto& l : lines) out.push_back(l.rfind("output: ", 0) == 0 ? l.substr(0, l.find(" (")) : l);
  return out;
}

// The jobs write their files (the name repeated, 1000 times) into this folder, then do what
// `then` does.
const testing::TempDir& folder() {
  static const testing::TempDir dir;
  return dir;
}

OutputJob job(const std::string& name, std::function<WriteStats(const std::filesystem::path&)> then,
              bool own_thread = false) {
  OutputJob j;
  j.format = "fmt";
  j.name = name;
  j.temp_path = folder() / (name + ".tmp");
  j.final_path = folder() / name;
  j.writer = [then = std::move(then), name](const std::filesystem::path& p) {
    std::ofstream f(p, std::ios::binary);
    for (int k = 0; k < 1000; ++k) f << name;
    f.close();
    return then(p);
  };
  j.own_thread = own_thread;
  j.log_before = {{LogLevel::kInfo, "before " + name}};
  return j;
}

WriteStats bytes(std::int64_t n) {
  WriteStats s;
  s.bytes = n;
  return s;
}

// Jobs a, b (own thread), c, d, where b finishes only after d has finished: written in time
// order a, c, d, b, logged in the order a, b, c, d.
TEST(OutputJobs, TheOwnThreadJobRunsBesideTheOthersAndTheLinesKeepTheJobOrder) {
  std::promise<void> d_done;
  std::shared_future<void> d_finished = d_done.get_future().share();
  const auto caller = std::this_thread::get_id();
  std::thread::id b_thread, c_thread;
  bool b_saw_d = false;
  std::vector<OutputJob> jobs;
  jobs.push_back(job("a", [](const auto&) { return bytes(1); }));
  jobs.push_back(job(
      "b",
      [&](const auto&) {
        b_thread = std::this_thread::get_id();
        b_saw_d = d_finished.wait_for(std::chrono::seconds(20)) == std::future_status::ready;
        return bytes(2);
      },
      true));
  jobs.push_back(job("c", [&](const auto&) {
    c_thread = std::this_thread::get_id();
    return bytes(3);
  }));
  jobs.push_back(job("d", [&](const auto&) {
    d_done.set_value();
    return bytes(4);
  }));
  CapturedLog log;
  const auto w = write_output_jobs(std::move(jobs), {{LogLevel::kInfo, "trailing"}}, true, log.logger);
  EXPECT_TRUE(b_saw_d);  // b was still running when d (on the calling thread) finished
  EXPECT_NE(b_thread, caller);
  EXPECT_EQ(c_thread, caller);
  EXPECT_EQ(without_times(log.lines),
            (std::vector<std::string>{"before a", "output: a", "before b", "output: b", "before c", "output: c",
                                      "before d", "output: d", "trailing"}));
  EXPECT_EQ(log.lines[1].rfind("output: a (fmt, 1 bytes, ", 0), 0u) << log.lines[1];
  ASSERT_EQ(w.size(), 4u);
  for (std::size_t k = 0; k < w.size(); ++k) {
    EXPECT_EQ(w[k].name, std::string(1, static_cast<char>('a' + k)));
    EXPECT_EQ(w[k].bytes, static_cast<std::int64_t>(k + 1));
    EXPECT_EQ(w[k].own_thread, k == 1);
    // The checksum of the file as its writer left it, taken on the writer's thread.
    EXPECT_EQ(w[k].checksum, file_checksum(folder() / (w[k].name + ".tmp")));
    EXPECT_EQ(w[k].checksum.size(), 16u);
  }
}

TEST(OutputJobs, NotConcurrentRunsEverythingOnTheCallingThreadInOrder) {
  const auto caller = std::this_thread::get_id();
  std::vector<std::string> order;
  std::vector<OutputJob> jobs;
  for (const char* name : {"a", "b", "c"}) {
    jobs.push_back(job(
        name,
        [&, name](const auto&) {
          EXPECT_EQ(std::this_thread::get_id(), caller);
          order.emplace_back(name);
          return bytes(1);
        },
        std::string(name) == "b"));
  }
  CapturedLog log;
  const auto w = write_output_jobs(std::move(jobs), {}, false, log.logger);
  EXPECT_EQ(order, (std::vector<std::string>{"a", "b", "c"}));
  for (const auto& f : w) EXPECT_FALSE(f.own_thread);
  EXPECT_EQ(without_times(log.lines),
            (std::vector<std::string>{"before a", "output: a", "before b", "output: b", "before c", "output: c"}));
}

// Runs a, b (own thread), c, d where `failing` throw (b after d has thrown, when both fail);
// returns the message thrown, the lines logged and which writers ran.
struct Outcome {
  std::string error;
  std::vector<std::string> lines;
  std::vector<std::string> ran;
};
Outcome run_failing(const std::string& failing) {
  std::promise<void> d_done;
  std::shared_future<void> d_finished = d_done.get_future().share();
  Outcome out;
  std::mutex ran_mutex;
  auto mark = [&](const std::string& name) {
    const std::lock_guard<std::mutex> lock(ran_mutex);
    out.ran.push_back(name);
  };
  auto fail_if = [&](const std::string& name) {
    if (failing.find(name) != std::string::npos) throw OutputError(name + " failed");
  };
  std::vector<OutputJob> jobs;
  jobs.push_back(job("a", [&](const auto&) {
    mark("a");
    fail_if("a");
    return bytes(1);
  }));
  jobs.push_back(job(
      "b",
      [&](const auto&) {
        mark("b");
        if (failing.find('d') != std::string::npos) d_finished.wait_for(std::chrono::seconds(20));
        fail_if("b");
        return bytes(2);
      },
      true));
  jobs.push_back(job("c", [&](const auto&) {
    mark("c");
    fail_if("c");
    return bytes(3);
  }));
  jobs.push_back(job("d", [&](const auto&) {
    mark("d");
    d_done.set_value();
    fail_if("d");
    return bytes(4);
  }));
  CapturedLog log;
  try {
    write_output_jobs(std::move(jobs), {{LogLevel::kInfo, "trailing"}}, true, log.logger);
  } catch (const OutputError& e) {
    out.error = e.what();
  }
  out.lines = without_times(log.lines);
  std::sort(out.ran.begin(), out.ran.end());
  return out;
}

TEST(OutputJobs, TheFirstFailureInJobOrderIsThrownWhicheverThreadFailedFirst) {
  // b (extra thread) fails after d (calling thread) failed: b's error, the lines of a and b's
  // planned line only.
  Outcome o = run_failing("bd");
  EXPECT_EQ(o.error, "b failed");
  EXPECT_EQ(o.lines, (std::vector<std::string>{"before a", "output: a", "before b"}));
  // a fails: nothing more runs on the calling thread; b (already started beside) is waited for.
  o = run_failing("ab");
  EXPECT_EQ(o.error, "a failed");
  EXPECT_EQ(o.lines, (std::vector<std::string>{"before a"}));
  EXPECT_EQ(o.ran, (std::vector<std::string>{"a", "b"}));
  // c fails: a and b are logged, d never runs.
  o = run_failing("c");
  EXPECT_EQ(o.error, "c failed");
  EXPECT_EQ(o.lines, (std::vector<std::string>{"before a", "output: a", "before b", "output: b", "before c"}));
  EXPECT_EQ(o.ran, (std::vector<std::string>{"a", "b", "c"}));
  // d fails (b waits for it and succeeds): everything before d is logged, no trailing line.
  o = run_failing("d");
  EXPECT_EQ(o.error, "d failed");
  EXPECT_EQ(o.lines, (std::vector<std::string>{"before a", "output: a", "before b", "output: b", "before c",
                                               "output: c", "before d"}));
}

// A step (no file) runs on the calling thread in its place and logs what it returns; it is not
// among the files returned.
TEST(OutputJobs, AStepRunsOnTheCallingThreadInItsPlace) {
  const auto caller = std::this_thread::get_id();
  std::vector<OutputJob> jobs;
  jobs.push_back(job(
      "p", [](const auto&) { return bytes(1); }, true));
  OutputJob step;
  step.step = [&] {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    return std::vector<LogLine>{{LogLevel::kInfo, "step line"}};
  };
  step.log_before = {{LogLevel::kInfo, "before step"}};
  jobs.push_back(std::move(step));
  jobs.push_back(job("q", [](const auto&) { return bytes(2); }));
  CapturedLog log;
  const auto w = write_output_jobs(std::move(jobs), {{LogLevel::kInfo, "trailing"}}, true, log.logger);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].name, "p");
  EXPECT_TRUE(w[0].own_thread);
  EXPECT_EQ(w[1].name, "q");
  EXPECT_EQ(without_times(log.lines), (std::vector<std::string>{"before p", "output: p", "before step", "step line",
                                                                "before q", "output: q", "trailing"}));
}

// A step with own_thread (the shape quality when the preview does not need it) runs on the extra
// thread before that thread's files, while the calling thread writes its own; its lines keep
// their place. The step waits until the calling thread's file has started, so the test fails if
// the step ran on the calling thread (it would wait for itself and time out).
TEST(OutputJobs, AnOwnThreadStepRunsBesideTheFiles) {
  const auto caller = std::this_thread::get_id();
  std::promise<void> q_started;
  auto started = q_started.get_future().share();
  std::vector<OutputJob> jobs;
  OutputJob step;
  step.step = [&] {
    EXPECT_NE(std::this_thread::get_id(), caller);
    EXPECT_EQ(started.wait_for(std::chrono::seconds(20)), std::future_status::ready);
    return std::vector<LogLine>{{LogLevel::kInfo, "step line"}};
  };
  step.log_before = {{LogLevel::kInfo, "before step"}};
  step.own_thread = true;
  jobs.push_back(std::move(step));
  jobs.push_back(job(
      "p", [](const auto&) { return bytes(1); }, true));
  jobs.push_back(job("q", [&](const auto&) {
    q_started.set_value();
    return bytes(2);
  }));
  CapturedLog log;
  const auto w = write_output_jobs(std::move(jobs), {{LogLevel::kInfo, "trailing"}}, true, log.logger);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].name, "p");
  EXPECT_TRUE(w[0].own_thread);
  EXPECT_EQ(w[1].name, "q");
  EXPECT_FALSE(w[1].own_thread);
  EXPECT_EQ(without_times(log.lines), (std::vector<std::string>{"before step", "step line", "before p", "output: p",
                                                                "before q", "output: q", "trailing"}));
}

}  // namespace
}  // namespace aq::io::unit_app_output_jobs_test

// SPDX-License-Identifier: GPL-3.0-or-later
// Writing a run's files in a fixed order while one of them is written on a thread of its own
// (ARCHITECTURE §4.8). The caller plans every file first (its temporary path reserved in the
// OutputSet, its writer ready to run, the log lines that precede it); write_output_jobs then runs
// the writers and logs one line per file, in the jobs' order whatever the threads did:
//
//   calling thread:  job 0 ──> job 2 ──> job 3 ──> job 4 ──> (wait) ──> log the rest
//   extra thread:         job 1 (own_thread: the UGRID file, netCDF/HDF5; the shape quality) ─┘
//   log:             lines of 0 │ lines of 1, 2, 3, 4 once 1 is written
//
// Only the calling thread logs: a line waits until every file before it is written. The first
// failure in job order is rethrown, after both threads have stopped; the lines of the jobs
// before it are logged (and the lines planned before the failing job), later ones are not, as
// if the jobs had run one after another.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/log.hpp"
#include "io/write_stats.hpp"

namespace aq::io {

/// Counts worth reporting about a written file, by name (e.g. {"nodes", 36681}).
using Facts = std::vector<std::pair<std::string, std::int64_t>>;

struct WrittenFile {
  std::string name;            ///< file name in the output folder, e.g. "mesh.msh"
  std::string format;          ///< a value of output.formats, or "png_zoom"
  std::filesystem::path path;  ///< final path (the file is there after OutputSet::commit)
  std::int64_t bytes = 0;
  double seconds = 0.0;  ///< wall time of the writer
  std::string checksum;  ///< XXH64 of the written file (file_checksum), taken on the writer's thread
  WriteStats stats;
  Facts facts;
  bool own_thread = false;  ///< written on the extra thread while the other files were written
};

/// A log line held back until the files before it are written.
struct LogLine {
  LogLevel level = LogLevel::kInfo;
  std::string text;
};

/// One file to write, or a step without a file (`step` set: work the files after it need, run in
/// its place, its lines logged there). The writer must not log, and with own_thread it must touch
/// nothing the other jobs touch (it runs beside them): a step with own_thread is one whose result
/// no file of the calling thread reads (the shape quality when the preview does not colour by it).
struct OutputJob {
  std::string format;                ///< as WrittenFile::format
  std::string name;                  ///< as WrittenFile::name
  std::filesystem::path temp_path;   ///< where the writer writes (OutputSet::temp_path)
  std::filesystem::path final_path;  ///< OutputSet::final_path
  std::function<WriteStats(const std::filesystem::path&)> writer;
  std::function<Facts(const WriteStats&)> facts;
  bool own_thread = false;                     ///< may run on the extra thread
  std::vector<LogLine> log_before;             ///< logged before this file's line
  std::function<std::vector<LogLine>()> step;  ///< set: no file; returns the lines to log
};

/// Runs every job's writer (or step) and returns the files in the jobs' order, each with its
/// checksum (taken right after the writer, on its thread: the extra thread's big file is read back
/// while the calling thread writes the others), logging for each
/// job its log_before lines and "output: <name> (<format>, <bytes> bytes, <seconds> s, <facts>)"
/// (a step: the lines it returned), then `trailing`. With `concurrent` (and at least one job of each kind) the
/// own_thread jobs run one after another on one extra thread while the others run on the calling thread; otherwise all
/// run on the calling thread in order. Rethrows the first failure in job order (see above).
std::vector<WrittenFile> write_output_jobs(std::vector<OutputJob> jobs, const std::vector<LogLine>& trailing,
                                           bool concurrent, const Logger& log);

}  // namespace aq::io

// SPDX-License-Identifier: GPL-3.0-or-later
// What every binding of the compiled module shares: the GIL and the process-wide lock around
// C++ work, the OpenMP team size of one call, the log lines of a run, read-only numpy views of
// C++ arrays and the report as a Python dict (see module.cpp for the design).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/cancel.hpp"
#include "core/log.hpp"
#include "core/report.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace aq::python {

namespace py = pybind11;

inline std::mutex& run_mutex() {
  static std::mutex m;
  return m;
}

// The calling thread's OpenMP team size for one call (0 = leave it), restored afterwards.
class ThreadScope {
 public:
  explicit ThreadScope(int threads) {
#ifdef _OPENMP
    saved_ = omp_get_max_threads();
    if (threads > 0) omp_set_num_threads(threads);
#else
    (void)threads;
#endif
  }
  ~ThreadScope() {
#ifdef _OPENMP
    omp_set_num_threads(saved_);
#endif
  }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_ = 1;
};

// Big arrays from the reusable heap during a call, as src/app/main.cpp sets for the command
// (glibc unmaps an mmapped block when it is freed, so every stage would page-fault its memory
// afresh: about 0.3 s of the 1' run); afterwards the threshold goes back to glibc's default
// 128 KiB, so the user's session keeps returning its big numpy arrays to the system.
class MmapThresholdScope {
 public:
  MmapThresholdScope() {
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
#endif
  }
  ~MmapThresholdScope() {
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
  }
  MmapThresholdScope(const MmapThresholdScope&) = delete;
  MmapThresholdScope& operator=(const MmapThresholdScope&) = delete;
};

// The stop request of the call the calling thread makes (python/aquatoria/_interrupt.py makes the
// call on a worker thread with a token of its own, CancelToken in Python, and requests the stop
// when the main thread gets KeyboardInterrupt); null: the call cannot be stopped.
inline const CancelToken*& call_token() {
  thread_local const CancelToken* token = nullptr;
  return token;
}

// The C++ work of one call: GIL released, the process-wide lock held, the thread count and the
// heap threshold set, the call's stop request (core/cancel.hpp) the one the pipeline looks at.
// Throws Cancelled at once when the stop was requested while the call waited for the lock.
class WorkScope {
 public:
  explicit WorkScope(int threads)
      : lock_(run_mutex()), cancel_(call_token() != nullptr ? *call_token() : no_token()), threads_(threads) {
    throw_if_cancelled();
  }

 private:
  static const CancelToken& no_token() {
    static const CancelToken never;
    return never;
  }
  py::gil_scoped_release release_;  // declared first: released before the lock is taken
  std::lock_guard<std::mutex> lock_;
  CancelScope cancel_;
  ThreadScope threads_;
  MmapThresholdScope heap_;
};

// Log lines of a run: kept (the Python layer turns warnings into Python warnings) and echoed to
// stderr at or above `echo`.
struct LogLines {
  std::vector<std::pair<int, std::string>> lines;
  std::mutex mutex;
  /// The lines so far, emptied.
  std::vector<std::pair<int, std::string>> take() {
    const std::lock_guard<std::mutex> g(mutex);
    return std::exchange(lines, {});
  }
};

inline Logger make_logger(const std::shared_ptr<LogLines>& lines, bool verbose) {
  Logger log(
      [lines, verbose](LogLevel level, std::string_view text) {
        {
          const std::lock_guard<std::mutex> g(lines->mutex);
          lines->lines.emplace_back(static_cast<int>(level), std::string(text));
        }
        if (verbose) {
          std::fprintf(stderr, "%.*s\n", static_cast<int>(text.size()), text.data());
          std::fflush(stderr);
        }
      },
      verbose ? LogLevel::kInfo : LogLevel::kWarning);
  return log;
}

// A read-only numpy view of `data` kept alive by `owner` (an empty array when there is nothing
// to view: an empty std::vector's data() may be null).
template <typename T>
py::array view(const T* data, std::vector<py::ssize_t> shape, py::handle owner) {
  if (data == nullptr) {  // an empty vector: its first dimension is 0
    py::array_t<T> empty(shape);
    empty.attr("setflags")(py::arg("write") = false);
    return empty;
  }
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t s = static_cast<py::ssize_t>(sizeof(T));
  for (std::size_t k = shape.size(); k-- > 0;) {
    strides[k] = s;
    s *= shape[k];
  }
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

inline py::object json_to_python(const Json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

}  // namespace aq::python

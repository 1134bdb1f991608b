// SPDX-License-Identifier: GPL-3.0-or-later
// Cooperative cancellation of a run by another thread: the Python package's Ctrl-C
// (python/aquatoria/_interrupt.py). The command line does not need it: its signal handler
// (app/interrupt.hpp) removes the temporaries and ends the process, which a library caller such as
// a Python session cannot let happen.
//
// The caller runs its work under a CancelScope holding a CancelToken and, from another thread,
// calls CancelToken::request(). The pipeline looks at the request where stopping leaves nothing
// half-made and throws Cancelled there; the exception unwinds like any other error (an OutputSet
// removes its temporary files, nothing is committed). It looks at the start and the end of every
// stage (StageScope), before every block a file writer hands to the kernel (io::FileWriter, about
// every 4 MiB) or to netCDF, between the bands of a raster read and between the passes of the
// long stages; with two threads on the 1' lattice the longest stretch without a look is well
// under a second of CPU time. Never inside an OpenMP region: an exception may not leave one.
#pragma once

#include <atomic>

#include "core/error.hpp"

namespace aq {

/// The run was stopped on request (CancelToken::request), not by a fault. Exit code 130, SIGINT's.
class Cancelled : public Error {
 public:
  using Error::Error;
  [[nodiscard]] int exit_code() const noexcept override { return 130; }
};

/// A stop request for one run; request() may be called from any thread (and from a signal
/// handler: it is one lock-free atomic store).
class CancelToken {
 public:
  void request() noexcept { requested_.store(true, std::memory_order_relaxed); }
  [[nodiscard]] bool requested() const noexcept { return requested_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> requested_{false};
};

/// While it lives, `token` is the one cancel_requested() and throw_if_cancelled() look at, on
/// every thread (one run at a time: the Python package runs its calls one after another). Restores
/// the token before it on destruction, so scopes nest.
class CancelScope {
 public:
  explicit CancelScope(const CancelToken& token) noexcept;
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const CancelToken* previous_;
};

/// Whether the running work has been asked to stop (false outside every CancelScope). One relaxed
/// atomic load; any thread, OpenMP workers included.
[[nodiscard]] bool cancel_requested() noexcept;

/// Throws Cancelled ("interrupted") when cancel_requested(). Only where unwinding is safe: never
/// inside an OpenMP parallel region.
void throw_if_cancelled();

}  // namespace aq

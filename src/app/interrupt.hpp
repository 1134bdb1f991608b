// SPDX-License-Identifier: GPL-3.0-or-later
// Clean interruption (ARCHITECTURE §9): SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGPIPE remove the
// run's temporary files (and undo an unfinished commit; core/temp_registry.hpp), print one line
// on stderr and exit with 128 + the signal number (130, 143, 129, 131, 141).
#pragma once

namespace aq::app {

/// Installs the handlers for SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGPIPE. Call once on the main thread, before
/// anything else (main.cpp does it from .preinit_array, before the shared libraries' constructors): the handler
/// forwards a signal that lands on another thread (an OpenMP worker) to it, because output files are created and
/// renamed on the main thread only. Async-signal-safe and allocation-free, so it may run before the C++ runtime
/// is initialised.
void install_interrupt_handlers();

}  // namespace aq::app

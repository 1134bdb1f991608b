// SPDX-License-Identifier: GPL-3.0-or-later
// A shared library whose constructor sleeps AQ_SLOW_START_MS milliseconds (default 0), for
// tests/cli/interrupt_cli_test.cpp: preloaded (LD_PRELOAD) into aquatoria, it stands for the
// libraries whose constructors run while the process starts, so a signal can be sent then.
#include <cstdlib>
#include <ctime>

namespace {

__attribute__((constructor)) void slow_start() {
  const char* ms = std::getenv("AQ_SLOW_START_MS");
  if (ms == nullptr) return;
  const long v = std::strtol(ms, nullptr, 10);
  if (v <= 0) return;
  timespec t{v / 1000, (v % 1000) * 1000000L};
  while (::nanosleep(&t, &t) != 0) {
  }
}

}  // namespace

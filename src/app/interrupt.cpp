// SPDX-License-Identifier: GPL-3.0-or-later
// SIGINT/SIGTERM/SIGHUP/SIGQUIT/SIGPIPE handler: async-signal-safe throughout (gettid/tgkill/unlink/write/_exit, no
// allocation, no stdio).
#include "app/interrupt.hpp"

#include <sys/syscall.h>
#include <unistd.h>

#include <csignal>

#include "core/temp_registry.hpp"

namespace aq::app {
namespace {

volatile pid_t g_main_tid = 0;

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    case SIGQUIT:
      return "SIGQUIT";
    case SIGPIPE:
      return "SIGPIPE";
    default:
      return "a signal";
  }
}

// Writes "aquatoria: interrupted by SIG...; N temporary file(s) removed\n" with write(2).
void say(int sig, int removed) {
  char line[128];
  std::size_t n = 0;
  const auto put = [&](const char* s) {
    while (*s != '\0' && n < sizeof line) line[n++] = *s++;
  };
  put("aquatoria: interrupted by ");
  put(signal_name(sig));
  put("; ");
  char digits[12];
  int k = 0;
  do {
    digits[k++] = static_cast<char>('0' + removed % 10);
    removed /= 10;
  } while (removed > 0 && k < 11);
  while (k > 0 && n < sizeof line) line[n++] = digits[--k];
  put(" temporary file(s) removed\n");
  (void)!::write(STDERR_FILENO, line, n);
}

extern "C" void on_interrupt(int sig) {
  const auto self = static_cast<pid_t>(::syscall(SYS_gettid));
  if (self != g_main_tid) {  // an OpenMP worker: let the main thread do it
    (void)::syscall(SYS_tgkill, ::getpid(), g_main_tid, sig);
    return;
  }
  const int removed = TempRegistry::remove_registered_temporaries();
  say(sig, removed);
  ::_exit(128 + sig);
}

}  // namespace

void install_interrupt_handlers() {
  g_main_tid = static_cast<pid_t>(::syscall(SYS_gettid));
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  for (const int sig : kSignals) sigaddset(&sa.sa_mask, sig);  // no second handler while the first removes files
  sa.sa_flags = SA_RESTART;
  // SIGPIPE too (stderr piped into `grep -m1` that has quit): the message line then fails with
  // EPIPE, which is ignored; the temporaries are removed all the same.
  // A signal ignored when aquatoria started stays ignored (`nohup aquatoria ...` must survive the
  // hangup, a parent that ignores SIGPIPE wants EPIPE errors instead).
  for (const int sig : kSignals) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace aq::app

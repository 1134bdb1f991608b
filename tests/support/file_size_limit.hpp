// SPDX-License-Identifier: GPL-3.0-or-later
// Simulates a full disk for writer tests without touching devices: lowers the soft
// RLIMIT_FSIZE of the process (with SIGXFSZ ignored, writes past the limit fail with EFBIG)
// and restores both on destruction.
#pragma once

#include <sys/resource.h>

#include <csignal>
#include <stdexcept>

namespace aq::testing {

class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    if (getrlimit(RLIMIT_FSIZE, &old_) != 0) throw std::runtime_error("getrlimit failed");
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lim = old_;
    lim.rlim_cur = bytes;
    if (setrlimit(RLIMIT_FSIZE, &lim) != 0) throw std::runtime_error("setrlimit failed");
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, old_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit old_{};
  void (*old_handler_)(int) = nullptr;
};

}  // namespace aq::testing

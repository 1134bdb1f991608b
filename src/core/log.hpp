// SPDX-License-Identifier: GPL-3.0-or-later
// Logging to stderr and progress reporting. The library never prints by itself: it receives a
// Logger (messages and stage lines) whose sink the application chooses. Progress bars are drawn
// by the sink only on a terminal and only from the calling thread.
#pragma once

#include <fmt/format.h>

#include <functional>
#include <string>
#include <string_view>

namespace aq {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarning = 2, kError = 3 };

/// Receives progress of a long stage: fraction done in [0,1] and a short label.
using ProgressFn = std::function<void(double fraction, std::string_view label)>;

/// Where log lines go. The default sink writes to stderr; tests install a capturing sink.
class Logger {
 public:
  using Sink = std::function<void(LogLevel, std::string_view)>;

  Logger();
  explicit Logger(Sink sink, LogLevel min_level = LogLevel::kInfo);

  void set_level(LogLevel level) { min_level_ = level; }
  [[nodiscard]] LogLevel level() const { return min_level_; }
  void log(LogLevel level, std::string_view message) const;

  template <typename... Args>
  void info(fmt::format_string<Args...> f, Args&&... args) const {
    log(LogLevel::kInfo, fmt::format(f, std::forward<Args>(args)...));
  }
  template <typename... Args>
  void warn(fmt::format_string<Args...> f, Args&&... args) const {
    log(LogLevel::kWarning, fmt::format(f, std::forward<Args>(args)...));
  }
  template <typename... Args>
  void debug(fmt::format_string<Args...> f, Args&&... args) const {
    log(LogLevel::kDebug, fmt::format(f, std::forward<Args>(args)...));
  }

  /// A progress callback for a stage (stage, percent, rate in %/s, ETA). On a terminal one line
  /// is redrawn (\r); otherwise (the default stderr logger writing to a file or a pipe) a plain
  /// line "stage: 42% label, 1.9 %/s, ETA 0:30" every kPlainEvery seconds once the stage has run
  /// that long, so short runs print nothing extra. Call it from one thread at a time.
  [[nodiscard]] ProgressFn progress(std::string stage) const;
  /// Progress bars on a terminal: on or off (default: stderr is a terminal).
  void set_progress_enabled(bool on) { progress_enabled_ = on; }
  /// Plain progress lines (default: on for the stderr logger when stderr is not a terminal).
  void set_progress_lines(bool on) { progress_lines_ = on; }
  static constexpr double kPlainEvery = 10.0;

  /// A logger that discards everything (for tests and library defaults).
  static const Logger& null();

 private:
  Sink sink_;
  LogLevel min_level_ = LogLevel::kInfo;
  bool progress_enabled_ = false;
  bool progress_lines_ = false;
};

}  // namespace aq

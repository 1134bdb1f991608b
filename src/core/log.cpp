// SPDX-License-Identifier: GPL-3.0-or-later
// Logger: stderr sink with level prefixes, and a terminal progress bar.
#include "core/log.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

namespace aq {

namespace {
void stderr_sink(LogLevel level, std::string_view message) {
  const char* prefix = "";
  if (level == LogLevel::kWarning) prefix = "warning: ";
  if (level == LogLevel::kError) prefix = "error: ";
  std::fprintf(stderr, "%s%.*s\n", prefix, static_cast<int>(message.size()), message.data());
}
}  // namespace

Logger::Logger()
    : sink_(stderr_sink), progress_enabled_(isatty(STDERR_FILENO) != 0), progress_lines_(isatty(STDERR_FILENO) == 0) {}

Logger::Logger(Sink sink, LogLevel min_level) : sink_(std::move(sink)), min_level_(min_level) {}

void Logger::log(LogLevel level, std::string_view message) const {
  if (sink_ && static_cast<int>(level) >= static_cast<int>(min_level_)) sink_(level, message);
}

namespace {

// "1:05" / "1:02:05".
std::string clock_text(double s) {
  const auto t = static_cast<long>(s + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, (t / 60) % 60, t % 60)
                   : fmt::format("{}:{:02}", t / 60, t % 60);
}

// State of one stage's progress: start time, last percent drawn, last plain line.
struct ProgressState {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  int last_pct = -1;
  double last_line_s = 0.0;
  [[nodiscard]] double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  // ", 1.9 %/s, ETA 0:30" once there is something to measure.
  [[nodiscard]] std::string rate_eta(double fraction, double t) const {
    if (fraction <= 0.0 || t <= 0.05) return {};
    const double rate = fraction / t;
    return fmt::format(", {:.3g} %/s, ETA {}", 100.0 * rate, clock_text((1.0 - fraction) / rate));
  }
};

}  // namespace

ProgressFn Logger::progress(std::string stage) const {
  if (min_level_ > LogLevel::kInfo) return {};
  auto st = std::make_shared<ProgressState>();
  if (progress_enabled_) {
    return [stage = std::move(stage), st](double fraction, std::string_view label) {
      const int pct = static_cast<int>(fraction * 100.0 + 0.5);
      if (pct == st->last_pct) return;
      st->last_pct = pct;
      constexpr int kWidth = 30;
      const int filled = pct * kWidth / 100;
      const std::string tail = st->rate_eta(fraction, st->elapsed());
      std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %.*s%s\x1b[K", stage.c_str(), filled, "##############################",
                   kWidth - filled, "", pct, static_cast<int>(label.size()), label.data(), tail.c_str());
      if (pct >= 100) std::fprintf(stderr, "\r\x1b[K");
      std::fflush(stderr);
    };
  }
  if (progress_lines_ && sink_) {
    return [stage = std::move(stage), st, sink = sink_](double fraction, std::string_view label) {
      const double t = st->elapsed();
      if (fraction >= 1.0 || t - st->last_line_s < kPlainEvery) return;
      st->last_line_s = t;
      sink(LogLevel::kInfo, fmt::format("{}: {:.0f}% {}{}", stage, 100.0 * fraction, label, st->rate_eta(fraction, t)));
    };
  }
  return {};
}

const Logger& Logger::null() {
  static const Logger kNull(Logger::Sink{}, LogLevel::kError);
  return kNull;
}

}  // namespace aq

// Logger: stderr sink with level prefixes, and a terminal progress bar.
#include "core/log.hpp"

#include <unistd.h>

#include <cstdio>
#include <memory>

namespace aq {

namespace {
void stderr_sink(LogLevel level, std::string_view message) {
  const char* prefix = "";
  if (level == LogLevel::kWarning) prefix = "warning: ";
  if (level == LogLevel::kError) prefix = "error: ";
  std::fprintf(stderr, "%s%.*s\n", prefix, static_cast<int>(message.size()), message.data());
}
}  // namespace

Logger::Logger() : sink_(stderr_sink), progress_enabled_(isatty(STDERR_FILENO) != 0) {}

Logger::Logger(Sink sink, LogLevel min_level) : sink_(std::move(sink)), min_level_(min_level) {}

void Logger::log(LogLevel level, std::string_view message) const {
  if (sink_ && static_cast<int>(level) >= static_cast<int>(min_level_)) sink_(level, message);
}

ProgressFn Logger::progress(std::string stage) const {
  if (!progress_enabled_ || min_level_ > LogLevel::kInfo) return {};
  auto last = std::make_shared<int>(-1);
  return [stage = std::move(stage), last](double fraction, std::string_view label) {
    const int pct = static_cast<int>(fraction * 100.0 + 0.5);
    if (pct == *last) return;
    *last = pct;
    constexpr int kWidth = 30;
    const int filled = pct * kWidth / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %.*s\x1b[K", stage.c_str(), filled, "##############################",
                 kWidth - filled, "", pct, static_cast<int>(label.size()), label.data());
    if (pct >= 100) std::fprintf(stderr, "\r\x1b[K");
    std::fflush(stderr);
  };
}

const Logger& Logger::null() {
  static const Logger kNull(Logger::Sink{}, LogLevel::kError);
  return kNull;
}

}  // namespace aq

#include "swemps/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <string>

namespace swemps::cli {

Progress::Progress(double end_time_s, bool enabled, std::FILE* stream)
    : end_time_s_(end_time_s),
      enabled_(enabled),
      terminal_(isatty(fileno(stream)) != 0),
      stream_(stream),
      start_(Clock::now()),
      last_draw_(start_) {}

namespace {

std::string clock_text(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e7) return "--:--";
  const auto s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%02ld:%02ld", s / 60, s % 60);
  }
  return buf;
}

}  // namespace

void Progress::update(double time_s, std::size_t steps, std::size_t particles) {
  if (!enabled_) return;
  const auto now = Clock::now();
  const double fraction = std::clamp(time_s / end_time_s_, 0.0, 1.0);
  if (terminal_) {
    if (now - last_draw_ < std::chrono::milliseconds(200) && fraction < 1.0) return;
  } else if (fraction < next_fraction_ && now - last_draw_ < std::chrono::seconds(30)) {
    return;
  }
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double steps_per_s = elapsed > 0.0 ? static_cast<double>(steps) / elapsed : 0.0;
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  if (terminal_) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, ' ');
    std::fprintf(stream_,
                 "\r[%s] %5.1f%%  t = %.4g / %.4g s  %zu particles  %.0f steps/s  left %s ",
                 bar.c_str(), 100.0 * fraction, time_s, end_time_s_, particles, steps_per_s,
                 clock_text(left).c_str());
    drawn_ = true;
  } else {
    while (next_fraction_ <= fraction) next_fraction_ += 0.1;
    std::fprintf(stream_,
                 "progress: %5.1f%%  t = %.4g / %.4g s  %zu steps  %zu particles  %.0f steps/s  "
                 "elapsed %s  left %s\n",
                 100.0 * fraction, time_s, end_time_s_, steps, particles, steps_per_s,
                 clock_text(elapsed).c_str(), clock_text(left).c_str());
  }
  std::fflush(stream_);
}

void Progress::finish() {
  if (enabled_ && terminal_ && drawn_) {
    std::fputc('\n', stream_);
    std::fflush(stream_);
  }
}

}  // namespace swemps::cli

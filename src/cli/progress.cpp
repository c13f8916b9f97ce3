#include "swemps/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <string>
#include <utility>

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

void Progress::resume_from(double time_s, std::size_t steps) {
  start_fraction_ = std::clamp(time_s / end_time_s_, 0.0, 1.0);
  start_steps_ = steps;
  while (next_fraction_ <= start_fraction_) next_fraction_ += 0.1;
}

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
  const double steps_per_s =
      elapsed > 0.0 ? static_cast<double>(steps - std::min(steps, start_steps_)) / elapsed : 0.0;
  const double done = fraction - start_fraction_;
  const double left = done > 0.0 ? elapsed * (1.0 - fraction) / done : -1.0;
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

SweepProgress::SweepProgress(std::vector<double> run_costs, bool enabled, std::FILE* stream)
    : run_costs_(std::move(run_costs)),
      enabled_(enabled),
      terminal_(isatty(fileno(stream)) != 0),
      stream_(stream),
      start_(Clock::now()),
      last_draw_(start_) {
  for (const double c : run_costs_) total_cost_ += c;
}

std::string SweepProgress::counts() const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const double fraction = total_cost_ > 0.0 ? done_cost_ / total_cost_ : 0.0;
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  return std::to_string(done_) + "/" + std::to_string(run_costs_.size()) + " runs  elapsed " +
         clock_text(elapsed) + "  left " + clock_text(left);
}

void SweepProgress::draw_bar(std::size_t running) {
  constexpr int width = 30;
  const double fraction = run_costs_.empty()
                              ? 1.0
                              : static_cast<double>(done_) / static_cast<double>(run_costs_.size());
  std::string bar(static_cast<std::size_t>(fraction * width), '#');
  bar.resize(width, ' ');
  std::fprintf(stream_, "\r[%s] %s  %zu running ", bar.c_str(), counts().c_str(), running);
  std::fflush(stream_);
  last_draw_ = Clock::now();
  drawn_ = true;
}

void SweepProgress::tick(std::size_t running) {
  if (!enabled_ || !terminal_) return;
  if (Clock::now() - last_draw_ < std::chrono::milliseconds(200)) return;
  draw_bar(running);
}

void SweepProgress::finished(std::size_t run, const std::string& what, std::size_t running) {
  ++done_;
  if (run < run_costs_.size()) done_cost_ += run_costs_[run];
  if (!enabled_) return;
  if (terminal_) {
    // Clears the bar (ESC [ K: to the end of the line), writes the run's line, redraws.
    std::fprintf(stream_, "\r\033[K%s\n", what.c_str());
    draw_bar(running);
  } else {
    std::fprintf(stream_, "%s  [%s]\n", what.c_str(), counts().c_str());
    std::fflush(stream_);
  }
}

void SweepProgress::finish() {
  if (enabled_ && terminal_ && drawn_) {
    std::fputc('\n', stream_);
    std::fflush(stream_);
  }
}

}  // namespace swemps::cli

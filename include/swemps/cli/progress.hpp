#pragma once
// Progress of a run for a person watching: on a terminal, one line redrawn in place with a
// bar, simulated time, steps per second and time left; otherwise (a log file, CI) a plain
// line every tenth of the run or every 30 s, whichever comes first.

#include <chrono>
#include <cstddef>
#include <cstdio>

namespace swemps::cli {

class Progress {
 public:
  Progress(double end_time_s, bool enabled, std::FILE* stream = stderr);
  void update(double time_s, std::size_t steps, std::size_t particles);
  void finish();  // ends the terminal line

 private:
  using Clock = std::chrono::steady_clock;
  double end_time_s_;
  bool enabled_, terminal_;
  std::FILE* stream_;
  Clock::time_point start_, last_draw_;
  double next_fraction_ = 0.1;
  bool drawn_ = false;
};

}  // namespace swemps::cli

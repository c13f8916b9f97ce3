#pragma once
// Progress of a run for a person watching: on a terminal, one line redrawn in place with a
// bar, simulated time, steps per second and time left; otherwise (a log file, CI) a plain
// line every tenth of the run or every 30 s, whichever comes first.

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace swemps::cli {

class Progress {
 public:
  Progress(double end_time_s, bool enabled, std::FILE* stream = stderr);
  // A run restarted at time_s after `steps` steps: rates and time left count from there.
  void resume_from(double time_s, std::size_t steps);
  void update(double time_s, std::size_t steps, std::size_t particles);
  void finish();  // ends the terminal line

 private:
  using Clock = std::chrono::steady_clock;
  double end_time_s_;
  double start_fraction_ = 0.0;
  std::size_t start_steps_ = 0;
  bool enabled_, terminal_;
  std::FILE* stream_;
  Clock::time_point start_, last_draw_;
  double next_fraction_ = 0.1;
  bool drawn_ = false;
};

// Progress of a sweep of runs (swe-mps study): on a terminal, a line per finished run above a
// bar redrawn in place with runs done, runs going, elapsed time and time left; otherwise a
// plain line per finished run with the same counts.
class SweepProgress {
 public:
  // `run_costs`: each run's expected cost in any unit, for the time left: the runs of a
  // sweep differ in cost by orders of magnitude, so counting runs would mislead.
  SweepProgress(std::vector<double> run_costs, bool enabled, std::FILE* stream = stderr);
  // Redraws the bar (a terminal, at most five times a second); `running` runs are going.
  void tick(std::size_t running);
  // Run `run` has ended; `what` says how ("spacing 0.1 m, mps: ok, 2.1 s, fan L1 0.021").
  void finished(std::size_t run, const std::string& what, std::size_t running);
  void finish();  // ends the terminal line

 private:
  using Clock = std::chrono::steady_clock;
  void draw_bar(std::size_t running);
  std::string counts() const;  // "3/16 runs, elapsed 00:12, left 01:40"

  std::vector<double> run_costs_;
  double total_cost_ = 0.0, done_cost_ = 0.0;
  std::size_t done_ = 0;
  bool enabled_, terminal_;
  std::FILE* stream_;
  Clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

}  // namespace swemps::cli

#pragma once
// The simulation's phase timing (Simulation::phase_times()), shared by its source files.

#include <chrono>

namespace swemps::swe {

// Adds the time since its construction to `total` when it goes out of scope.
class ScopedTimer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit ScopedTimer(double& total) : total_(total), start_(Clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  Clock::time_point start_;
};

}  // namespace swemps::swe

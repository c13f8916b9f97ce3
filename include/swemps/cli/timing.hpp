#pragma once
// Wall-clock timing of the parts of a run, for the closing summaries.

#include <chrono>

namespace swemps::cli {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace swemps::cli

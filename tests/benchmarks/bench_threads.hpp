#pragma once
// The thread counts a benchmark measures: SWEMPS_BENCH_THREADS ("1 2"), else its own default.

#include <cstdlib>
#include <sstream>
#include <utility>
#include <vector>

namespace swemps::bench {

inline std::vector<int> thread_counts(std::vector<int> fallback) {
  std::vector<int> counts;
  if (const char* env = std::getenv("SWEMPS_BENCH_THREADS")) {
    std::istringstream in(env);
    for (int t; in >> t;) counts.push_back(t);
  }
  return counts.empty() ? std::move(fallback) : counts;
}

}  // namespace swemps::bench

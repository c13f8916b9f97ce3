#pragma once
// The one way particle loops run in parallel.
//
// Below parallel_threshold iterations a loop runs on one thread: starting and joining a team
// costs more than the work, and on a busy machine a descheduled thread stalls every barrier.
// Each iteration must write only its own slots, so the result never depends on the number
// of threads (or on whether the loop ran in parallel at all).

#include <cstddef>
#include <cstdint>

namespace swemps {

inline constexpr std::int64_t parallel_threshold = 2048;

// Calls body(i) for i in [0, count), statically scheduled over the OpenMP threads.
template <class Body>
void parallel_for(std::size_t count, const Body& body) {
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (std::int64_t i = 0; i < n; ++i) body(static_cast<std::size_t>(i));
}

}  // namespace swemps

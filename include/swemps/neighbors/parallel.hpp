#pragma once
// The one way particle loops run in parallel.
//
// Below parallel_threshold iterations a loop runs on one thread: starting and joining a team
// costs more than the work, and on a busy machine a descheduled thread stalls every barrier.
// Each iteration must write only its own slots, so the result never depends on the number
// of threads (or on whether the loop ran in parallel at all).

#include <algorithm>
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

// For reductions: [0, count) cut into at most `reduction_chunks` ranges that depend on count
// alone, body(chunk, begin, end) called for each in parallel. The caller keeps one result per
// chunk and combines them in chunk order, so that a reduction gives the same result (the
// same particle, for a minimum with ties) for any number of threads.
inline constexpr std::size_t reduction_chunks = 64;

template <class Body>
void parallel_chunks(std::size_t count, const Body& body) {
  const bool parallel = count > static_cast<std::size_t>(parallel_threshold);
  const std::size_t chunks = parallel ? reduction_chunks : 1;
  const std::size_t size = (count + chunks - 1) / chunks;
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(chunks); ++c) {
    const auto chunk = static_cast<std::size_t>(c);
    const std::size_t begin = std::min(count, chunk * size);
    body(chunk, begin, std::min(count, begin + size));
  }
}

}  // namespace swemps

#pragma once
// Below this many loop iterations a particle loop runs on one thread: starting and joining
// a team costs more than the work, and on a busy machine a descheduled thread stalls every
// barrier. The choice never changes results (every iteration writes only its own slot).

#include <cstdint>

namespace swemps {

inline constexpr std::int64_t parallel_threshold = 2048;

}  // namespace swemps

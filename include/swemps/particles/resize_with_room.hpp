#pragma once
// Per-particle buffers that follow a particle count that grows a little at a time.

#include <cstddef>
#include <vector>

namespace swemps::particles {

// Resizes v to n, with room to spare when it must grow. Resized to the exact count, a buffer
// moves whole each time splitting or an inflow adds a few particles, and the allocator keeps
// the old block: on the 1e6-particle lattice benchmark the step's buffers resized exactly cost
// 24 bytes a particle of resident memory (docs/performance.md).
template <class T>
void resize_with_room(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 8);
  v.resize(n);
}

}  // namespace swemps::particles

#pragma once
// How many neighbours the particles had over a run: the lengths of the neighbour-list rows of
// every summation (a particle's row holds the particles and ghosts within its search radius,
// itself not counted), as a histogram, so that the smallest, median and largest count over all
// particles and steps cost one pass over the row offsets per step. What a row holds is what a
// step costs, and a scheme whose radius follows each particle's area keeps it in a narrow
// band where one radius for all lets it grow as water thins (docs/method.md).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"

namespace swemps::swe {

class NeighborCounts {
 public:
  // Counts every row of the list.
  void add(const neighbors::NeighborList& list);
  bool empty() const { return rows_ == 0; }
  std::uint64_t rows() const { return rows_; }  // particle-summations counted
  // Over every row counted; 0 while empty. The median is the lower one of an even count.
  std::size_t min() const;
  std::size_t median() const;
  std::size_t max() const;

 private:
  std::vector<std::uint64_t> rows_of_length_;  // [k]: rows holding k neighbours
  std::uint64_t rows_ = 0;
};

}  // namespace swemps::swe

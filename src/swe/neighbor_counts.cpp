#include "swemps/swe/neighbor_counts.hpp"

#include <algorithm>

namespace swemps::swe {

void NeighborCounts::add(const neighbors::NeighborList& list) {
  const std::size_t n = list.row_count();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t length = list.offsets[i + 1] - list.offsets[i];
    if (length >= rows_of_length_.size()) rows_of_length_.resize(length + 1, 0);
    ++rows_of_length_[length];
  }
  rows_ += n;
}

std::size_t NeighborCounts::min() const {
  const auto first = std::find_if(rows_of_length_.begin(), rows_of_length_.end(),
                                  [](std::uint64_t c) { return c > 0; });
  return first == rows_of_length_.end()
             ? 0
             : static_cast<std::size_t>(first - rows_of_length_.begin());
}

std::size_t NeighborCounts::median() const {
  if (rows_ == 0) return 0;
  const std::uint64_t half = (rows_ - 1) / 2;  // the lower middle row, counted from 0
  std::uint64_t seen = 0;
  for (std::size_t k = 0; k < rows_of_length_.size(); ++k) {
    seen += rows_of_length_[k];
    if (seen > half) return k;
  }
  return 0;  // not reached: the counts add up to rows_
}

std::size_t NeighborCounts::max() const {
  for (std::size_t k = rows_of_length_.size(); k > 0; --k) {
    if (rows_of_length_[k - 1] > 0) return k - 1;
  }
  return 0;
}

}  // namespace swemps::swe

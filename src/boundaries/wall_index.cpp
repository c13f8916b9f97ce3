#include "swemps/boundaries/wall_index.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "swemps/boundaries/ghost_walls.hpp"

namespace swemps::boundaries {

WallIndex::WallIndex(std::vector<WallSegment> segments) : segments_(std::move(segments)) {
  std::vector<neighbors::BoxGrid::Box> boxes;
  boxes.reserve(segments_.size());
  double total_length = 0.0;
  for (const auto& s : segments_) {
    for (const auto& p : {s.from, s.to}) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
        throw std::invalid_argument("wall segment with a non-finite end");
      }
    }
    boxes.push_back({std::min(s.from[0], s.to[0]), std::min(s.from[1], s.to[1]),
                     std::max(s.from[0], s.to[0]), std::max(s.from[1], s.to[1])});
    total_length += std::hypot(s.to[0] - s.from[0], s.to[1] - s.from[1]);
  }
  if (!segments_.empty()) {
    grid_ = neighbors::BoxGrid(boxes, total_length / static_cast<double>(segments_.size()));
  }
}

bool WallIndex::crosses_any(std::array<double, 2> p0, std::array<double, 2> p1) const {
  bool crossed = false;
  for_each_candidate(std::min(p0[0], p1[0]), std::min(p0[1], p1[1]), std::max(p0[0], p1[0]),
                     std::max(p0[1], p1[1]), [&](std::uint32_t k) {
                       if (!crossed) crossed = GhostWalls::crosses(segments_[k], p0, p1);
                     });
  return crossed;
}

}  // namespace swemps::boundaries

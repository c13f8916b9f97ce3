#pragma once
// Wall segments filed by the square cells of a grid over them, so that the walls near a point
// or a short path are found without testing every wall: a town's buildings are tens of
// thousands of segments, and every particle near the water's edge asks for its walls twice a
// step (ghosts and reflections), every split daughter and merged pair once more.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "swemps/neighbors/box_grid.hpp"

namespace swemps::boundaries {

enum class WallCondition { slip, no_slip };

struct WallSegment {
  std::array<double, 2> from, to;  // m
  WallCondition condition = WallCondition::slip;
};

class WallIndex {
 public:
  WallIndex() = default;
  // Files each segment under every cell its bounding box touches (neighbors::BoxGrid). The
  // cells are about the walls' mean length on a side: a query near a wall then reads a few
  // cells of a few segments each. Throws std::invalid_argument for a segment with a non-finite end.
  explicit WallIndex(std::vector<WallSegment> segments);

  bool empty() const { return segments_.empty(); }
  std::span<const WallSegment> segments() const { return segments_; }
  double cell_size() const { return grid_.cell_size(); }

  // Calls visit(k) for the index k of every segment whose bounding box may meet the box
  // [x_min, x_max] x [y_min, y_max]: every segment that does, and some that do not; a
  // segment filed under several of the box's cells is visited once per cell.
  template <class Visit>
  void for_each_candidate(double x_min, double y_min, double x_max, double y_max,
                          Visit&& visit) const {
    grid_.for_each_candidate(x_min, y_min, x_max, y_max, visit);
  }

  // True if the path p0-p1 crosses (or ends on) a segment: a particle placed at p1 from p0
  // (a split daughter, a merged pair) would be on another side of it.
  bool crosses_any(std::array<double, 2> p0, std::array<double, 2> p1) const;

 private:
  std::vector<WallSegment> segments_;
  neighbors::BoxGrid grid_;
};

}  // namespace swemps::boundaries

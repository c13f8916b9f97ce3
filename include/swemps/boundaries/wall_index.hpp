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

namespace swemps::boundaries {

enum class WallCondition { slip, no_slip };

struct WallSegment {
  std::array<double, 2> from, to;  // m
  WallCondition condition = WallCondition::slip;
};

class WallIndex {
 public:
  WallIndex() = default;
  // Files each segment under every cell its bounding box touches. The cells are about the
  // walls' mean length on a side: a query near a wall then reads a few cells of a few
  // segments each. Long walls among short ones (a domain's sides beside a town) make the
  // cells larger only where the grid would otherwise exceed kMaxCellsPerSegment cells per
  // segment. Throws std::invalid_argument for a segment with a non-finite end.
  explicit WallIndex(std::vector<WallSegment> segments);

  bool empty() const { return segments_.empty(); }
  std::span<const WallSegment> segments() const { return segments_; }
  double cell_size() const { return cell_; }

  // Calls visit(k) for the index k of every segment whose bounding box may meet the box
  // [x_min, x_max] x [y_min, y_max]: every segment that does, and some that do not; a
  // segment filed under several of the box's cells is visited once per cell.
  template <class Visit>
  void for_each_candidate(double x_min, double y_min, double x_max, double y_max,
                          Visit&& visit) const {
    if (segments_.empty() || x_max < x0_ || y_max < y0_) return;
    const auto [i0, j0] = cell_of(x_min, y_min);
    const auto [i1, j1] = cell_of(x_max, y_max);
    if (i0 >= nx_ || j0 >= ny_) return;  // cell_of clamps below; beyond the grid above
    for (std::size_t j = j0; j <= std::min(j1, ny_ - 1); ++j) {
      for (std::size_t i = i0; i <= std::min(i1, nx_ - 1); ++i) {
        const std::size_t c = j * nx_ + i;
        for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) visit(ids_[k]);
      }
    }
  }

  // True if the path p0-p1 crosses (or ends on) a segment: a particle placed at p1 from p0
  // (a split daughter, a merged pair) would be on another side of it.
  bool crosses_any(std::array<double, 2> p0, std::array<double, 2> p1) const;

  // The grid never has more cells than this many per segment (and at least 4096 in all).
  static constexpr std::size_t kMaxCellsPerSegment = 16;

 private:
  // The cell holding (x, y), clamped to the grid's first cells below; indices beyond the
  // grid's last cells are returned as they are (callers clamp them).
  std::array<std::size_t, 2> cell_of(double x, double y) const;

  std::vector<WallSegment> segments_;
  double x0_ = 0.0, y0_ = 0.0, cell_ = 1.0;
  std::size_t nx_ = 0, ny_ = 0;
  // Compressed rows: cell c's segments are ids_[start_[c] .. start_[c + 1]).
  std::vector<std::uint32_t> start_, ids_;
};

}  // namespace swemps::boundaries

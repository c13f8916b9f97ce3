#include "swemps/boundaries/wall_index.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "swemps/boundaries/ghost_walls.hpp"

namespace swemps::boundaries {

WallIndex::WallIndex(std::vector<WallSegment> segments) : segments_(std::move(segments)) {
  if (segments_.empty()) return;
  double x_min = INFINITY, y_min = INFINITY, x_max = -INFINITY, y_max = -INFINITY;
  double total_length = 0.0;
  for (const auto& s : segments_) {
    for (const auto& p : {s.from, s.to}) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
        throw std::invalid_argument("wall segment with a non-finite end");
      }
      x_min = std::min(x_min, p[0]);
      y_min = std::min(y_min, p[1]);
      x_max = std::max(x_max, p[0]);
      y_max = std::max(y_max, p[1]);
    }
    total_length += std::hypot(s.to[0] - s.from[0], s.to[1] - s.from[1]);
  }
  const double width = x_max - x_min, height = y_max - y_min;
  const double max_cells =
      static_cast<double>(std::max<std::size_t>(4096, kMaxCellsPerSegment * segments_.size()));
  // The mean length, or larger where that would make too many cells; never zero, so that a
  // single point-like box still has one cell.
  cell_ = total_length / static_cast<double>(segments_.size());
  cell_ = std::max(cell_, std::sqrt(std::max(width, 1e-9) * std::max(height, 1e-9) / max_cells));
  cell_ = std::max({cell_, width / max_cells, height / max_cells, 1e-9});
  x0_ = x_min;
  y0_ = y_min;
  nx_ = static_cast<std::size_t>(std::floor(width / cell_)) + 1;
  ny_ = static_cast<std::size_t>(std::floor(height / cell_)) + 1;

  // Two passes over the segments' cells: count, then file (compressed rows).
  start_.assign(nx_ * ny_ + 1, 0);
  const auto for_each_cell = [&](const WallSegment& s, auto&& f) {
    const auto [i0, j0] = cell_of(std::min(s.from[0], s.to[0]), std::min(s.from[1], s.to[1]));
    const auto [i1, j1] = cell_of(std::max(s.from[0], s.to[0]), std::max(s.from[1], s.to[1]));
    for (std::size_t j = j0; j <= std::min(j1, ny_ - 1); ++j) {
      for (std::size_t i = i0; i <= std::min(i1, nx_ - 1); ++i) f(j * nx_ + i);
    }
  };
  for (const auto& s : segments_) for_each_cell(s, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
  ids_.resize(start_.back());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::uint32_t k = 0; k < segments_.size(); ++k) {
    for_each_cell(segments_[k], [&](std::size_t c) { ids_[next[c]++] = k; });
  }
}

std::array<std::size_t, 2> WallIndex::cell_of(double x, double y) const {
  const double i = std::floor((x - x0_) / cell_);
  const double j = std::floor((y - y0_) / cell_);
  // Beyond the grid above: any index past the last cell (callers clamp it); below: cell 0.
  const auto clamp = [](double index, std::size_t count) {
    if (!(index > 0.0)) return std::size_t{0};
    return index >= static_cast<double>(count) ? count : static_cast<std::size_t>(index);
  };
  return {clamp(i, nx_), clamp(j, ny_)};
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

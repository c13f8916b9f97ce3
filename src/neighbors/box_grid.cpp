#include "swemps/neighbors/box_grid.hpp"

#include <cmath>

namespace swemps::neighbors {

BoxGrid::BoxGrid(const std::vector<Box>& boxes, double typical_size) {
  if (boxes.empty()) return;
  double x_min = INFINITY, y_min = INFINITY, x_max = -INFINITY, y_max = -INFINITY;
  for (const Box& b : boxes) {
    x_min = std::min(x_min, b[0]);
    y_min = std::min(y_min, b[1]);
    x_max = std::max(x_max, b[2]);
    y_max = std::max(y_max, b[3]);
  }
  const double width = x_max - x_min, height = y_max - y_min;
  const double max_cells =
      static_cast<double>(std::max<std::size_t>(4096, kMaxCellsPerBox * boxes.size()));
  cell_ = std::isfinite(typical_size) ? typical_size : 0.0;
  cell_ = std::max({cell_, std::sqrt(std::max(width, 1e-9) * std::max(height, 1e-9) / max_cells),
                    width / max_cells, height / max_cells, 1e-9});
  x0_ = x_min;
  y0_ = y_min;
  nx_ = static_cast<std::size_t>(std::floor(width / cell_)) + 1;
  ny_ = static_cast<std::size_t>(std::floor(height / cell_)) + 1;
  // Two passes over the boxes' cells: count, then file.
  const auto for_each_cell = [&](const Box& b, auto&& f) {
    const auto [i0, j0] = cell_of(b[0], b[1]);
    const auto [i1, j1] = cell_of(b[2], b[3]);
    for (std::size_t j = j0; j <= std::min(j1, ny_ - 1); ++j) {
      for (std::size_t i = i0; i <= std::min(i1, nx_ - 1); ++i) f(j * nx_ + i);
    }
  };
  start_.assign(nx_ * ny_ + 1, 0);
  for (const Box& b : boxes) for_each_cell(b, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
  ids_.resize(start_.back());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::uint32_t k = 0; k < boxes.size(); ++k) {
    for_each_cell(boxes[k], [&](std::size_t c) { ids_[next[c]++] = k; });
  }
}

std::array<std::size_t, 2> BoxGrid::cell_of(double x, double y) const {
  const auto clamp = [&](double index, std::size_t count) {
    if (!(index > 0.0)) return std::size_t{0};
    return index >= static_cast<double>(count) ? count : static_cast<std::size_t>(index);
  };
  return {clamp(std::floor((x - x0_) / cell_), nx_), clamp(std::floor((y - y0_) / cell_), ny_)};
}

}  // namespace swemps::neighbors

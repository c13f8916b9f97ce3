#pragma once
// Axis-aligned boxes (of wall segments, of building footprints) filed under the square cells
// of a grid over them, so that the boxes near a point or a small box are found without
// testing every one. Cells are about the boxes' mean size; never more than kMaxCellsPerBox
// cells per box (and at least 4096 in all), so that a few boxes far apart make no huge grid.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace swemps::neighbors {

class BoxGrid {
 public:
  using Box = std::array<double, 4>;  // x_min, y_min, x_max, y_max (finite)

  BoxGrid() = default;
  // `typical_size`: the cells' side before the cap on their number (> 0 or not, it is
  // raised where it must be).
  BoxGrid(const std::vector<Box>& boxes, double typical_size);

  bool empty() const { return nx_ == 0; }
  double cell_size() const { return cell_; }

  // Calls visit(k) for every box k filed under a cell the query box [x_min, x_max] x
  // [y_min, y_max] touches: every box that meets it, and some that do not; a box filed under
  // several of those cells is visited once per cell.
  template <class Visit>
  void for_each_candidate(double x_min, double y_min, double x_max, double y_max,
                          Visit&& visit) const {
    if (nx_ == 0 || !(x_max >= x0_) || !(y_max >= y0_)) return;
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

  static constexpr std::size_t kMaxCellsPerBox = 16;

 private:
  // The cell holding (x, y), clamped to the first cells below; indices beyond the grid's
  // last cells are returned as they are (callers clamp them).
  std::array<std::size_t, 2> cell_of(double x, double y) const;

  double x0_ = 0.0, y0_ = 0.0, cell_ = 1.0;
  std::size_t nx_ = 0, ny_ = 0;
  // Compressed rows: cell c's boxes are ids_[start_[c] .. start_[c + 1]).
  std::vector<std::uint32_t> start_, ids_;
};

}  // namespace swemps::neighbors

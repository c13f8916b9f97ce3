#pragma once
// Cell-list neighbour search. Points are binned into square (cubic) cells at least as wide
// as the search radius, so the neighbours of a point lie in its own cell and the 3^Dim
// cells around it. Binning is a counting sort: order() lists point indices cell by cell,
// which callers use to reorder their particle arrays so that neighbours sit near each other
// in memory. Building is serial and deterministic; queries are read-only and thread-safe.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace swemps::neighbors {

template <int Dim>
using Coordinates = std::array<std::span<const double>, Dim>;

template <int Dim>
class CellList {
 public:
  // Bins `coords` (Dim arrays of equal length) into cells of width >= search_radius /
  // subdivisions; the candidates of a point are then the points in the block of cells
  // `subdivisions` deep around its own, which holds every point within search_radius. Finer
  // cells fit that disc more tightly: with 2 subdivisions a 2D query tests 31 % fewer
  // candidates (a 5 x 5 block of half-width cells against 3 x 3 full ones), at the price of
  // more, shorter runs.
  void build(const Coordinates<Dim>& coords, double search_radius, int subdivisions = 1);

  std::size_t point_count() const { return order_.size(); }
  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }
  double cell_width() const { return cell_width_; }
  // Every point within this distance of a query point is among its candidates (>= the
  // search radius asked for; more when few points forced wider cells).
  double search_radius() const { return cell_width_ * reach_; }
  // Point indices sorted by cell (row-major cell order, x fastest).
  std::span<const std::uint32_t> order() const { return order_; }
  // Coordinate d of point order()[k] at k: a copy in cell order, so that a loop over the
  // candidates of a point reads a few contiguous runs with unit stride instead of gathering.
  std::span<const double> cell_ordered(int d) const { return cell_ordered_[d]; }

  // How many points for_each_candidate(point, ...) visits, without visiting them.
  std::size_t candidate_count(const std::array<double, Dim>& point) const {
    std::size_t count = 0;
    for_each_cell_run(point, [&](std::int64_t first_cell, std::int64_t last_cell) {
      count += cell_start_[static_cast<std::size_t>(last_cell) + 1] -
               cell_start_[static_cast<std::size_t>(first_cell)];
    });
    return count;
  }

  // Calls run(begin, end) for each range [begin, end) of positions in order() (and
  // cell_ordered()) that together hold the candidates for_each_candidate visits, in its order.
  template <class Run>
  void for_each_candidate_range(const std::array<double, Dim>& point, Run&& run) const {
    for_each_cell_run(point, [&](std::int64_t first_cell, std::int64_t last_cell) {
      run(cell_start_[static_cast<std::size_t>(first_cell)],
          cell_start_[static_cast<std::size_t>(last_cell) + 1]);
    });
  }

  // How many cells on each side of a point's own cell hold every point within `radius` of it:
  // the block for_each_candidate_range(point, reach_for(radius), run) visits. At least the
  // block of search_radius(); a hair more than radius / cell_width, so that rounding of the
  // cell coordinates cannot put a point within radius one cell further out.
  std::int64_t reach_for(double radius) const {
    const double cells = radius / cell_width_ * (1.0 + 1e-8);
    if (!(cells < 1e9)) return std::int64_t{1} << 30;  // a radius the grid cannot hold
    return std::max(reach_, static_cast<std::int64_t>(cells) + 1);
  }

  // As above, over a block `reach` cells deep on each side instead of the cell list's own.
  template <class Run>
  void for_each_candidate_range(const std::array<double, Dim>& point, std::int64_t reach,
                                Run&& run) const {
    for_each_cell_run(point, reach, [&](std::int64_t first_cell, std::int64_t last_cell) {
      run(cell_start_[static_cast<std::size_t>(first_cell)],
          cell_start_[static_cast<std::size_t>(last_cell) + 1]);
    });
  }

  // Calls f(j) for every point j in the cells around `point` (a superset of the points
  // within cell_width() of it), in a fixed order.
  template <class F>
  void for_each_candidate(const std::array<double, Dim>& point, F&& f) const {
    for_each_cell_run(point, [&](std::int64_t first_cell, std::int64_t last_cell) {
      visit_cells(first_cell, last_cell, f);
    });
  }

 private:
  // Calls run(first, last) for each run of consecutive cells (a row of up to 2 reach + 1) that
  // makes up the (2 reach + 1)^Dim block around `point`'s cell, clipped to the grid.
  template <class Run>
  void for_each_cell_run(const std::array<double, Dim>& point, Run&& run) const {
    for_each_cell_run(point, reach_, run);
  }
  template <class Run>
  void for_each_cell_run(const std::array<double, Dim>& point, std::int64_t reach,
                         Run&& run) const {
    std::array<std::int64_t, Dim> c{};
    for (int d = 0; d < Dim; ++d) c[d] = cell_coordinate(point[d], d);
    std::array<std::int64_t, Dim> lo{}, hi{};
    for (int d = 0; d < Dim; ++d) {
      lo[d] = std::max<std::int64_t>(c[d] - reach, 0);
      hi[d] = std::min<std::int64_t>(c[d] + reach, cells_[d] - 1);
      if (lo[d] > hi[d]) return;  // point far outside the binned box: no candidates
    }
    if constexpr (Dim == 1) {
      run(lo[0], hi[0]);
    } else if constexpr (Dim == 2) {
      for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
        const std::int64_t row = cy * cells_[0];
        run(row + lo[0], row + hi[0]);
      }
    } else {
      for (std::int64_t cz = lo[2]; cz <= hi[2]; ++cz)
        for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
          const std::int64_t row = (cz * cells_[1] + cy) * cells_[0];
          run(row + lo[0], row + hi[0]);
        }
    }
  }

  // Cells of a row are contiguous in order_, so a run of cells is one contiguous range.
  template <class F>
  void visit_cells(std::int64_t first_cell, std::int64_t last_cell, F& f) const {
    const std::uint32_t begin = cell_start_[static_cast<std::size_t>(first_cell)];
    const std::uint32_t end = cell_start_[static_cast<std::size_t>(last_cell) + 1];
    for (std::uint32_t k = begin; k < end; ++k) f(order_[k]);
  }

  // Cell of a query point, clamped to reach + 1 cells outside the binned box on either side:
  // a point further out has no candidates, one just outside still sees the edge cells.
  std::int64_t cell_coordinate(double value, int d) const {
    const double c = std::floor((value - origin_[d]) / cell_width_);
    const auto outside = static_cast<double>(reach_ + 1);
    if (!(c > -outside)) return -(reach_ + 1);  // also catches NaN
    if (c > static_cast<double>(cells_[d] - 1) + outside) return cells_[d] + reach_;
    return static_cast<std::int64_t>(c);
  }

  std::array<double, Dim> origin_{};
  std::array<std::int64_t, Dim> cells_{};
  double cell_width_ = 1.0;
  std::int64_t reach_ = 1;  // cells searched on each side of a query point's cell
  std::vector<std::uint32_t> cell_start_;  // size cell_count + 1
  std::vector<std::uint32_t> order_;
  std::array<std::vector<double>, Dim> cell_ordered_;
};

extern template class CellList<1>;
extern template class CellList<2>;
extern template class CellList<3>;

}  // namespace swemps::neighbors

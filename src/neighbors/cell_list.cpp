#include "swemps/neighbors/cell_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::neighbors {

template <int Dim>
void CellList<Dim>::build(const Coordinates<Dim>& coords, double search_radius, int subdivisions) {
  if (!(search_radius > 0.0) || !std::isfinite(search_radius)) {
    throw std::invalid_argument("cell list: cell width must be finite and > 0");
  }
  if (subdivisions < 1 || subdivisions > 8) {
    throw std::invalid_argument("cell list: subdivisions must be 1 to 8");
  }
  reach_ = subdivisions;
  const double min_cell_width = search_radius / subdivisions;
  const std::size_t n = coords[0].size();
  for (int d = 1; d < Dim; ++d) {
    if (coords[d].size() != n)
      throw std::invalid_argument("cell list: coordinate arrays differ in length");
  }
  if (n >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("cell list: too many points for 32-bit indices");
  }

  // The bounds, in parallel over fixed chunks (a minimum and a maximum are the same in any
  // order). Every value is checked: a NaN compares false and would slip past min/max.
  std::array<double, Dim> lo, hi;
  lo.fill(0.0);
  hi.fill(0.0);
  if (n > 0) {
    std::array<std::array<double, Dim>, reduction_chunks> chunk_lo, chunk_hi;
    std::array<std::uint8_t, reduction_chunks> broken{};
    std::array<std::uint8_t, reduction_chunks> used{};
    parallel_chunks(n, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      if (begin == end) return;
      bool bad = false;
      for (int d = 0; d < Dim; ++d) {
        double low = coords[d][begin], high = low;
        for (std::size_t i = begin; i < end; ++i) {
          const double c = coords[d][i];
          bad |= !std::isfinite(c);
          low = std::min(low, c);
          high = std::max(high, c);
        }
        chunk_lo[chunk][d] = low;
        chunk_hi[chunk][d] = high;
      }
      broken[chunk] = bad ? 1 : 0;
      used[chunk] = 1;
    });
    for (std::size_t chunk = 0; chunk < reduction_chunks; ++chunk) {
      if (broken[chunk]) throw std::domain_error("cell list: non-finite coordinate");
    }
    for (int d = 0; d < Dim; ++d) lo[d] = hi[d] = coords[d][0];
    for (std::size_t chunk = 0; chunk < reduction_chunks; ++chunk) {
      if (!used[chunk]) continue;
      for (int d = 0; d < Dim; ++d) {
        lo[d] = std::min(lo[d], chunk_lo[chunk][d]);
        hi[d] = std::max(hi[d], chunk_hi[chunk][d]);
      }
    }
  }

  for (int d = 0; d < Dim; ++d) {
    if (!std::isfinite(hi[d] - lo[d]))
      throw std::domain_error("cell list: coordinate span overflows");
  }

  // A few far-flung points must not make the grid huge: widen cells until there are at
  // most a few cells per point. Wider cells only add candidates, never lose neighbours.
  // Cells a hair wider than asked: (x - origin) / width is rounded, so two points closer
  // than `reach` widths could otherwise land reach + 1 cells apart. 1e-8 covers the rounding of
  // cell coordinates up to ~1e7 cells along an axis.
  cell_width_ = min_cell_width * (1.0 + 1e-8);
  const double max_cells = 4.0 * static_cast<double>(n) + 1024.0;
  for (;;) {
    double total = 1.0;
    for (int d = 0; d < Dim; ++d) total *= std::floor((hi[d] - lo[d]) / cell_width_) + 1.0;
    if (total <= max_cells) break;
    cell_width_ *= 2.0;
  }
  origin_ = lo;
  std::size_t total_cells = 1;
  for (int d = 0; d < Dim; ++d) {
    cells_[d] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / cell_width_)) + 1;
    total_cells *= static_cast<std::size_t>(cells_[d]);
  }

  // Counting sort by cell: stable, so points keep their relative order inside a cell.
  // The cell of every point in parallel; the counting itself stays serial (it is a few
  // percent of the build, and a parallel histogram would need one per thread).
  std::vector<std::uint32_t> cell_of(n);
  parallel_for(n, [&](std::size_t i) {
    std::size_t index = 0;
    for (int d = Dim - 1; d >= 0; --d) {
      auto c = static_cast<std::int64_t>((coords[d][i] - origin_[d]) / cell_width_);
      c = std::clamp<std::int64_t>(c, 0, cells_[d] - 1);
      index = index * static_cast<std::size_t>(cells_[d]) + static_cast<std::size_t>(c);
    }
    cell_of[i] = static_cast<std::uint32_t>(index);
  });
  // Each cell's count, summed to its end, then the points placed from the last backwards,
  // each at its cell's end less one: the ends come down to the starts, and points keep their
  // order within a cell, with no second array of cells to count with.
  cell_start_.assign(total_cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of[i]];
  for (std::size_t c = 1; c < total_cells; ++c) cell_start_[c] += cell_start_[c - 1];
  cell_start_[total_cells] = static_cast<std::uint32_t>(n);
  order_.resize(n);
  for (std::size_t i = n; i-- > 0;)
    order_[--cell_start_[cell_of[i]]] = static_cast<std::uint32_t>(i);
  for (int d = 0; d < Dim; ++d) {
    cell_ordered_[d].resize(n);
    parallel_for(n, [&](std::size_t k) { cell_ordered_[d][k] = coords[d][order_[k]]; });
  }
}

template class CellList<1>;
template class CellList<2>;
template class CellList<3>;

}  // namespace swemps::neighbors

#include "swemps/neighbors/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::neighbors {

namespace {

template <int Dim>
std::array<double, Dim> point_at(const Coordinates<Dim>& coords, std::size_t i) {
  std::array<double, Dim> p{};
  for (int d = 0; d < Dim; ++d) p[d] = coords[d][i];
  return p;
}

template <int Dim>
double distance_squared(const Coordinates<Dim>& coords, const std::array<double, Dim>& p,
                        std::size_t j) {
  double r2 = 0.0;
  for (int d = 0; d < Dim; ++d) {
    const double delta = coords[d][j] - p[d];
    r2 += delta * delta;
  }
  return r2;
}

// The cell-ordered coordinates of a cell list, as plain pointers so that loops over a range of
// them vectorise.
template <int Dim>
std::array<const double*, Dim> cell_ordered_pointers(const CellList<Dim>& cells) {
  std::array<const double*, Dim> c{};
  for (int d = 0; d < Dim; ++d) c[d] = cells.cell_ordered(d).data();
  return c;
}

// Squared distance from `p` to the point at cell-ordered position k. The count and the fill
// pass both use this one expression, so they agree on every comparison with the radius.
template <int Dim>
inline double distance_squared_at(const std::array<const double*, Dim>& c,
                                  const std::array<double, Dim>& p, std::size_t k) {
  double r2 = 0.0;
  for (int d = 0; d < Dim; ++d) {
    const double delta = c[d][k] - p[d];
    r2 += delta * delta;
  }
  return r2;
}

// The number of candidates for_each_candidate_range(p, run) visits: room enough for a row.
template <int Dim, class... Reach>
std::size_t candidates_in_block(const CellList<Dim>& cells, const std::array<double, Dim>& p,
                                Reach... reach) {
  std::size_t count = 0;
  cells.for_each_candidate_range(
      p, reach..., [&](std::uint32_t begin, std::uint32_t end) { count += end - begin; });
  return count;
}

// The candidates of the usual block around p that `keep(k, r2)` keeps, written into index in
// block order, target i left out; the number written. index has room for every candidate,
// so each is written and kept by advancing m, without a branch: about a third of the
// candidates are neighbours, a pattern no branch predictor guesses.
template <int Dim, class Keep>
std::uint32_t fill_from_block(const CellList<Dim>& cells, const std::array<const double*, Dim>& c,
                              const std::array<double, Dim>& p, std::size_t i, const Keep& keep,
                              std::uint32_t* index) {
  const auto order = cells.order();
  std::uint32_t m = 0;
  cells.for_each_candidate_range(p, [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t k = begin; k < end; ++k) {
      const double r2 = distance_squared_at<Dim>(c, p, k);
      const std::uint32_t j = order[k];
      index[m] = j;
      m += keep(k, r2) & (j != i) ? 1u : 0u;
    }
  });
  return m;
}

// Rows written in one pass over the candidates. The targets are cut into the fixed chunks of
// parallel_chunks(); a chunk appends its rows to a buffer of its own (NeighborList's
// chunk_rows, kept between builds), making room before each row for the `most(i)`
// candidates its loops may visit, then every buffer is copied into place. This costs a copy
// of the index; the two passes it replaced (count the rows, then fill them) computed every
// candidate's distance twice, and the counting pass was 40 % of the search. The rows, and
// their order, are the same for any number of threads.
template <class Most, class Fill>
void write_rows(std::size_t target_count, const Most& most, const Fill& fill, NeighborList& out) {
  out.offsets.assign(target_count + 1, 0);
  out.chunk_rows.resize(reduction_chunks);
  parallel_chunks(target_count, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    auto& rows = out.chunk_rows[chunk];
    std::size_t used = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t room = used + most(i);
      if (rows.size() < room) rows.resize(std::max(room, rows.size() + rows.size() / 8));
      const std::uint32_t length = fill(i, rows.data() + used);
      used += length;
      out.offsets[i + 1] = length;
    }
  });
  for (std::size_t i = 0; i < target_count; ++i) out.offsets[i + 1] += out.offsets[i];
  out.index.resize(out.offsets[target_count]);
  parallel_chunks(target_count, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::copy_n(out.chunk_rows[chunk].data(), out.offsets[end] - out.offsets[begin],
                out.index.data() + out.offsets[begin]);
  });
}

// A row put in ascending order, by insertion: rows come from the search in block order, which
// is close to ascending when the points are sorted by cell (as the particles are every few
// steps), so this is a few comparisons an entry.
void sort_row(std::uint32_t* row, std::uint32_t length) {
  for (std::uint32_t a = 1; a < length; ++a) {
    const std::uint32_t value = row[a];
    std::uint32_t b = a;
    for (; b > 0 && row[b - 1] > value; --b) row[b] = row[b - 1];
    row[b] = value;
  }
}

// The rows of the uniform-radius builder. `within(k, r2)` says whether the point at
// cell-ordered position k, at squared distance r2 from the target, is its neighbour. The
// loops read the cell-ordered coordinates with unit stride. A target is one of the binned
// points, so it meets itself at distance 0; the fill skips it by index.
template <int Dim, class Within>
void build_rows(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                std::size_t target_count, const Within& within, NeighborList& out) {
  if (target_count > cells.point_count()) {
    throw std::invalid_argument("neighbour list: more targets than binned points");
  }
  const auto c = cell_ordered_pointers(cells);
  write_rows(
      target_count,
      [&](std::size_t i) { return candidates_in_block<Dim>(cells, point_at<Dim>(coords, i)); },
      [&](std::size_t i, std::uint32_t* index) {
        return fill_from_block<Dim>(cells, c, point_at<Dim>(coords, i), i, within, index);
      },
      out);
}

}  // namespace

template <int Dim>
void build_neighbor_list(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                         std::size_t target_count, double radius, NeighborList& out) {
  if (radius > cells.search_radius()) {
    throw std::invalid_argument("neighbour list: radius larger than the cell width");
  }
  const double radius2 = radius * radius;
  build_rows<Dim>(
      cells, coords, target_count, [radius2](std::size_t, double r2) { return r2 < radius2; }, out);
}

template <int Dim>
void build_neighbor_list(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                         std::span<const double> radii, std::size_t target_count,
                         NeighborList& out) {
  if (radii.size() != cells.point_count()) {
    throw std::invalid_argument("neighbour list: one radius per binned point needed");
  }
  if (target_count > cells.point_count()) {
    throw std::invalid_argument("neighbour list: more targets than binned points");
  }
  // The cells hold every pair within `covered` in their usual block. Points with a larger
  // radius ("wide" points) are reached two other ways: a wide target searches a block deep
  // enough for the largest radius of all; a narrow target finds the wide points whose radius
  // reaches it in a second, coarse cell list of the wide points alone. In the usual block a
  // narrow target therefore takes a wide candidate only within its own radius, and the coarse
  // pass only beyond it, so that no pair is listed twice.
  const double covered = cells.search_radius();
  const auto order = cells.order();
  const auto c = cell_ordered_pointers(cells);
  double largest = 0.0;
  for (const double r : radii) largest = std::max(largest, r);
  // Squared radii of the targets by index, and of the candidates in cell order (read with
  // unit stride beside the cell-ordered coordinates), where a wide candidate counts 0.
  std::vector<double> target_r2(target_count), candidate_r2(radii.size());
  parallel_for(target_count, [&](std::size_t i) { target_r2[i] = radii[i] * radii[i]; });
  parallel_for(radii.size(), [&](std::size_t k) {
    const double r = radii[order[k]];
    candidate_r2[k] = r > covered ? 0.0 : r * r;
  });
  std::vector<std::uint32_t> wide;
  for (std::uint32_t j = 0; j < radii.size(); ++j)
    if (radii[j] > covered) wide.push_back(j);
  std::array<std::vector<double>, Dim> wide_coords;
  for (int d = 0; d < Dim; ++d) {
    wide_coords[d].resize(wide.size());
    for (std::size_t m = 0; m < wide.size(); ++m) wide_coords[d][m] = coords[d][wide[m]];
  }
  CellList<Dim> wide_cells;
  if (!wide.empty()) {
    Coordinates<Dim> view;
    for (int d = 0; d < Dim; ++d) view[d] = wide_coords[d];
    wide_cells.build(view, largest);
  }
  const std::int64_t wide_reach = cells.reach_for(largest);

  // The wide points whose radius reaches narrow target i beyond its own radius, in a fixed
  // order.
  const auto visit_wide = [&](std::size_t i, const std::array<double, Dim>& p, auto&& found) {
    if (wide.empty()) return;
    const double ri2 = target_r2[i];
    const auto wide_order = wide_cells.order();
    wide_cells.for_each_candidate_range(p, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t j = wide[wide_order[k]];
        const double r2 = distance_squared<Dim>(coords, p, j);
        if (r2 >= ri2 && r2 < radii[j] * radii[j]) found(j);
      }
    });
  };
  // A wide target's neighbours: every pair within either radius, over a block as deep as the
  // largest radius, in a fixed order.
  const auto visit_as_wide = [&](std::size_t i, const std::array<double, Dim>& p, auto&& found) {
    const double ri2 = target_r2[i];
    cells.for_each_candidate_range(p, wide_reach, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t j = order[k];
        if (j != i && distance_squared_at<Dim>(c, p, k) < std::max(ri2, radii[j] * radii[j]))
          found(j);
      }
    });
  };

  // One pass, as build_rows() makes it (write_rows() says how); a row has room for the
  // candidates of its block and, for a narrow target, of its coarse block of wide points.
  const auto most = [&](std::size_t i) {
    const auto p = point_at<Dim>(coords, i);
    if (radii[i] > covered) return candidates_in_block<Dim>(cells, p, wide_reach);
    return candidates_in_block<Dim>(cells, p) +
           (wide.empty() ? std::size_t{0} : candidates_in_block<Dim>(wide_cells, p));
  };
  const auto fill = [&](std::size_t i, std::uint32_t* index) {
    const auto p = point_at<Dim>(coords, i);
    std::uint32_t m = 0;
    const auto found = [&](std::uint32_t j) { index[m++] = j; };
    if (radii[i] > covered) {
      visit_as_wide(i, p, found);
      return m;
    }
    const double ri2 = target_r2[i];
    const auto keep = [&](std::size_t k, double r2) { return r2 < std::max(ri2, candidate_r2[k]); };
    m = fill_from_block<Dim>(cells, c, p, i, keep, index);
    visit_wide(i, p, found);
    return m;
  };
  const auto fill_ascending = [&](std::size_t i, std::uint32_t* index) {
    const std::uint32_t m = fill(i, index);
    sort_row(index, m);
    return m;
  };
  write_rows(target_count, most, fill_ascending, out);
}

double typical_radius(std::span<const double> radii, std::vector<double>& scratch) {
  if (radii.empty()) throw std::invalid_argument("typical radius: no radii");
  scratch.assign(radii.begin(), radii.end());
  const auto k =
      static_cast<std::ptrdiff_t>(typical_radius_quantile * static_cast<double>(radii.size() - 1));
  std::nth_element(scratch.begin(), scratch.begin() + k, scratch.end());
  return scratch[static_cast<std::size_t>(k)];
}

template <int Dim>
NeighborList brute_force_neighbors(const Coordinates<Dim>& coords, std::size_t target_count,
                                   double radius) {
  NeighborList out;
  out.offsets.push_back(0);
  const std::size_t n = coords[0].size();
  for (std::size_t i = 0; i < target_count; ++i) {
    const auto p = point_at<Dim>(coords, i);
    for (std::size_t j = 0; j < n; ++j) {
      const double r2 = distance_squared<Dim>(coords, p, j);
      if (j != i && r2 < radius * radius) {
        out.index.push_back(static_cast<std::uint32_t>(j));
      }
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.index.size()));
  }
  return out;
}

template void build_neighbor_list<1>(const CellList<1>&, const Coordinates<1>&, std::size_t, double,
                                     NeighborList&);
template void build_neighbor_list<2>(const CellList<2>&, const Coordinates<2>&,
                                     std::span<const double>, std::size_t, NeighborList&);
template void build_neighbor_list<2>(const CellList<2>&, const Coordinates<2>&, std::size_t, double,
                                     NeighborList&);
template void build_neighbor_list<3>(const CellList<3>&, const Coordinates<3>&, std::size_t, double,
                                     NeighborList&);
template NeighborList brute_force_neighbors<1>(const Coordinates<1>&, std::size_t, double);
template NeighborList brute_force_neighbors<2>(const Coordinates<2>&, std::size_t, double);
template NeighborList brute_force_neighbors<3>(const Coordinates<3>&, std::size_t, double);

}  // namespace swemps::neighbors

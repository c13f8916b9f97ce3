#include "swemps/neighbors/neighbor_list.hpp"

#include <algorithm>
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

}  // namespace

template <int Dim>
void build_neighbor_list(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                         std::size_t target_count, double radius, NeighborList& out) {
  if (radius > cells.cell_width()) {
    throw std::invalid_argument("neighbour list: radius larger than the cell width");
  }
  if (target_count > cells.point_count()) {
    throw std::invalid_argument("neighbour list: more targets than binned points");
  }
  const double radius2 = radius * radius;
  out.offsets.assign(target_count + 1, 0);

  // One distance pass: each row is written at a slot sized by its candidate count (cheap to
  // get from the cell ranges), then the rows are packed. Counting first and filling second
  // would test every candidate distance twice; the list build was the largest cost of a step.
  std::vector<std::uint32_t> bound(target_count + 1, 0);
  parallel_for(target_count, [&](std::size_t i) {
    bound[i + 1] = static_cast<std::uint32_t>(cells.candidate_count(point_at<Dim>(coords, i)));
  });
  for (std::size_t i = 0; i < target_count; ++i) bound[i + 1] += bound[i];
  out.index.resize(bound[target_count]);
  parallel_for(target_count, [&](std::size_t i) {
    std::uint32_t* slot = out.index.data() + bound[i];
    const auto p = point_at<Dim>(coords, i);
    cells.for_each_candidate(p, [&](std::uint32_t j) {
      if (j != i && distance_squared<Dim>(coords, p, j) < radius2) *slot++ = j;
    });
    out.offsets[i + 1] = static_cast<std::uint32_t>(slot - (out.index.data() + bound[i]));
  });
  // Pack: rows move only towards the front, in order, so a forward copy is safe.
  std::uint32_t packed = 0;
  for (std::size_t i = 0; i < target_count; ++i) {
    const std::uint32_t count = out.offsets[i + 1];
    std::copy_n(out.index.data() + bound[i], count, out.index.data() + packed);
    out.offsets[i] = packed;
    packed += count;
  }
  out.offsets[target_count] = packed;
  out.index.resize(packed);
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
      if (j != i && distance_squared<Dim>(coords, p, j) < radius * radius) {
        out.index.push_back(static_cast<std::uint32_t>(j));
      }
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.index.size()));
  }
  return out;
}

template void build_neighbor_list<1>(const CellList<1>&, const Coordinates<1>&, std::size_t, double,
                                     NeighborList&);
template void build_neighbor_list<2>(const CellList<2>&, const Coordinates<2>&, std::size_t, double,
                                     NeighborList&);
template void build_neighbor_list<3>(const CellList<3>&, const Coordinates<3>&, std::size_t, double,
                                     NeighborList&);
template NeighborList brute_force_neighbors<1>(const Coordinates<1>&, std::size_t, double);
template NeighborList brute_force_neighbors<2>(const Coordinates<2>&, std::size_t, double);
template NeighborList brute_force_neighbors<3>(const Coordinates<3>&, std::size_t, double);

}  // namespace swemps::neighbors

#pragma once
// Neighbour lists in compressed-row form: for each target point i, the indices j != i of
// all points closer than a radius. Built once per step from a CellList and reused by every
// particle loop of that step. Distances are not kept: with 20 to 80 neighbours a row of
// doubles is 160 to 640 bytes per particle, and reading it back from memory was no faster than
// recomputing the distance from the neighbours' positions, which the sums read anyway
// (docs/performance.md). The order inside a row follows the cell list, so it is the same for
// any thread count.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "swemps/neighbors/cell_list.hpp"

namespace swemps::neighbors {

struct NeighborList {
  std::vector<std::uint32_t> offsets;  // row i is index[offsets[i] .. offsets[i+1])
  std::vector<std::uint32_t> index;
  // The builders' working space: the rows of each chunk of targets before they are copied
  // into index (neighbor_list.cpp, write_rows). Kept so that a build allocates nothing new.
  std::vector<std::vector<std::uint32_t>> chunk_rows;

  std::size_t row_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::span<const std::uint32_t> row(std::size_t i) const {
    return {index.data() + offsets[i], index.data() + offsets[i + 1]};
  }
};

// Rows for the targets [0, target_count) of `coords`, over all points of `cells` (which
// must have been built from `coords` with a cell width >= radius). Parallel with OpenMP.
template <int Dim>
void build_neighbor_list(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                         std::size_t target_count, double radius, NeighborList& out);

// Rows for points that each have their own radius (radii: one per binned point, ghosts
// included): j is a neighbour of target i when |x_i - x_j| < max(radius_i, radius_j), so the
// rows are symmetric among targets and hold every pair either particle's kernel reaches.
// `cells` may be sized for a typical radius: a target with a larger radius searches a deeper
// block, and the few points with one are also found through a coarse cell list of their own,
// so that a handful of wide kernels does not widen every particle's search. A row lists its
// points in ascending order: a row is then a function of the points and radii alone, however
// it was found, so that rows repaired after a few points changed (row_repair.hpp) are the rows
// a new search would give, and a run that repairs continues bit for bit after a restart that
// searches anew.
template <int Dim>
void build_neighbor_list(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                         std::span<const double> radii, std::size_t target_count,
                         NeighborList& out);

// Cells for radii that differ between points are sized for this quantile of the radii: the
// wider few (at most one in ten) are reached through a coarse list of their own (above, and
// the point sampler of swe/operators.cpp), so that they do not widen every point's search.
inline constexpr double typical_radius_quantile = 0.9;

// The typical_radius_quantile quantile of `radii` (not empty), by a partial sort of a copy
// kept in `scratch`.
double typical_radius(std::span<const double> radii, std::vector<double>& scratch);

// The O(N^2) reference the fast path is tested against; rows sorted by index.
template <int Dim>
NeighborList brute_force_neighbors(const Coordinates<Dim>& coords, std::size_t target_count,
                                   double radius);

}  // namespace swemps::neighbors

#pragma once
// Repairing a few rows of a neighbour list instead of searching every row again.
//
// A step searches every particle's neighbours once (neighbor_list.hpp). Two things then change
// a few points only: a particle whose depth iteration widened its kernel past the radius it was
// searched with, and the daughters that splitting adds beside their parents. Searching all rows
// again for them cost the valley flood 2.4 searches and depth sums a step where one is needed
// (docs/performance.md, "Whole runs of real scenes"). Here only the changed points are searched
// for, and only the rows that hold them are rewritten.

#include <cstdint>
#include <span>
#include <vector>

#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"

namespace swemps::neighbors {

// Brings `list`, the variable-radius rows of build_neighbor_list (j in row i when
// |x_i - x_j| < max(radius_i, radius_j), rows ascending) for the targets [0, list.row_count()),
// up to date after the points in `changed` moved, changed radius or were added: `changed` is
// ascending and holds every target in [list.row_count(), target_count) and any other point
// whose position or radius is not what the list was built with. `cells` must be built from
// `coords` as they are now (any cell width; a wide radius searches a deeper block); `radii` has
// one radius per point of coords.
//
// The result is exactly the list build_neighbor_list would give for the points and radii as
// they are now: a pair of unchanged points keeps its distance, so an unchanged target's row
// keeps its unchanged points, and loses and gains only changed ones. Returns, ascending, the
// targets whose row was rewritten: the changed targets, and every target whose row held or now
// holds a changed point. The list is rewritten in place (the other rows move by what the
// rewritten rows before them gained or lost), so that a repair needs no second copy of it.
template <int Dim>
std::vector<std::uint32_t> repair_rows(const CellList<Dim>& cells, const Coordinates<Dim>& coords,
                                       std::span<const double> radii, std::size_t target_count,
                                       std::span<const std::uint32_t> changed, NeighborList& list);

}  // namespace swemps::neighbors

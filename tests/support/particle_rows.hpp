#pragma once
// The neighbour rows of every fluid particle within one radius, ghosts among the points: the
// rows a test of the walls' pair hiding starts from.

#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"

namespace swemps::testing {

inline neighbors::NeighborList rows_within(const particles::SweParticles& p, double radius) {
  const neighbors::Coordinates<2> coords{std::span<const double>(p.x),
                                         std::span<const double>(p.y)};
  neighbors::CellList<2> cells;
  cells.build(coords, radius);
  neighbors::NeighborList rows;
  neighbors::build_neighbor_list<2>(cells, coords, p.fluid_count(), radius, rows);
  return rows;
}

}  // namespace swemps::testing

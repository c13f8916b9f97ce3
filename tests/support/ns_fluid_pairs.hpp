#pragma once
// The fluid rows of a 2D Navier-Stokes tank's neighbour list and each pair's kernel weight,
// as a step finds them: for the tests of the Poisson systems built on them.

#include <cmath>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/particles.hpp"

namespace swemps::test {

inline void fluid_pairs(const ns::Particles<2>& particles, const kernels::AnyKernel<2>& kernel,
                        neighbors::NeighborList& pairs, std::vector<double>& weight) {
  const double support = kernels::support<2>(kernel);
  const auto coords = particles.coordinates();
  neighbors::CellList<2> cells;
  cells.build(coords, support);
  neighbors::build_neighbor_list<2>(cells, coords, particles.fluid, support, pairs);
  weight.clear();
  for (std::size_t i = 0; i < pairs.row_count(); ++i) {
    for (std::uint32_t j : pairs.row(i)) {
      weight.push_back(kernels::weight<2>(
          kernel, std::hypot(particles.position[0][j] - particles.position[0][i],
                             particles.position[1][j] - particles.position[1][i])));
    }
  }
}

}  // namespace swemps::test

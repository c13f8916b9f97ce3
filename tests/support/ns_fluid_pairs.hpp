#pragma once
// The fluid rows of a Navier-Stokes tank's neighbour list and each pair's kernel weight, as a
// step finds them: for the tests of the Poisson systems and gradients built on them.

#include <cmath>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/particles.hpp"

namespace swemps::test {

template <int Dim>
void fluid_pairs(const ns::Particles<Dim>& particles, const kernels::AnyKernel<Dim>& kernel,
                 neighbors::NeighborList& pairs, std::vector<double>& weight) {
  const double support = kernels::support<Dim>(kernel);
  const auto coords = particles.coordinates();
  neighbors::CellList<Dim> cells;
  cells.build(coords, support);
  neighbors::build_neighbor_list<Dim>(cells, coords, particles.fluid, support, pairs);
  weight.clear();
  for (std::size_t i = 0; i < pairs.row_count(); ++i) {
    for (std::uint32_t j : pairs.row(i)) {
      double r2 = 0.0;
      for (int d = 0; d < Dim; ++d) {
        const double x = particles.position[d][j] - particles.position[d][i];
        r2 += x * x;
      }
      weight.push_back(kernels::weight<Dim>(kernel, std::sqrt(r2)));
    }
  }
}

}  // namespace swemps::test

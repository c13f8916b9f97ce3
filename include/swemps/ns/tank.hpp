#pragma once
// The starting particles of a Navier-Stokes run: an open box-shaped tank with water boxes in
// it, all on one lattice of spacing l_0. Lattice nodes sit at the cell centres of the tank
// interior, so the first solid layer is half a spacing behind each wall plane and every
// particle, fluid or solid, is l_0 from its lattice neighbours.

#include <array>
#include <vector>

#include "swemps/ns/particles.hpp"

namespace swemps::ns {

template <int Dim>
struct Box {
  std::array<double, Dim> lower{}, upper{};  // m
};

template <int Dim>
struct TankSpec {
  // The inside of the tank. The floor is the plane at lower[Dim-1]; the side walls rise from
  // it to upper[Dim-1]; there is no lid. Each side must be a whole number of spacings.
  Box<Dim> interior;
  std::vector<Box<Dim>> water;  // inside the interior; a lattice node inside a box is fluid
  double spacing_m = 0.0;
  // Solid layers behind each wall: the first is wall particles, the rest dummies. Enough
  // that a wall particle's kernel support is full: ceil(support / l_0).
  int solid_layers = 3;
};

// Throws std::invalid_argument for a non-positive spacing, a side that is not a whole number
// of spacings (to 1e-6 of a spacing), a water box outside the interior or too few layers.
template <int Dim>
Particles<Dim> fill_tank(const TankSpec<Dim>& spec);

}  // namespace swemps::ns

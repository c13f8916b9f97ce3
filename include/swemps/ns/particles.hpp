#pragma once
// Particles of the Navier-Stokes mode in structure-of-arrays form, in Dim dimensions with
// gravity along the last axis (2D: a vertical x-z plane; 3D: x, y, z).
//
// Three kinds share the arrays, in this order: fluid [0, fluid), wall [fluid, fluid + wall),
// dummy [fluid + wall, size). Wall particles are the first layer of a solid: they take part
// in the pressure Poisson equation, so the fluid feels the wall's pressure. Dummy particles
// are the layers behind it: they only complete the number density of wall and fluid
// particles near the wall, so that a wall does not look like a free surface. Walls and
// dummies never move. Keeping the fluid first lets neighbour lists hold rows only for the
// particles that need them.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "swemps/neighbors/cell_list.hpp"

namespace swemps::ns {

enum class Kind { fluid, wall, dummy };

template <int Dim>
struct Particles {
  static_assert(Dim == 2 || Dim == 3, "the Navier-Stokes mode runs in 2D or 3D");

  std::array<std::vector<double>, Dim> position;  // m
  std::array<std::vector<double>, Dim> velocity;  // m/s; zero for walls and dummies
  std::vector<double> pressure;                   // Pa
  std::size_t fluid = 0, wall = 0, dummy = 0;

  std::size_t size() const { return fluid + wall + dummy; }
  Kind kind(std::size_t i) const {
    return i < fluid ? Kind::fluid : (i < fluid + wall ? Kind::wall : Kind::dummy);
  }
  neighbors::Coordinates<Dim> coordinates() const {
    neighbors::Coordinates<Dim> c;
    for (int d = 0; d < Dim; ++d) c[d] = position[d];
    return c;
  }

  // Appends one particle. Particles must be added kind by kind: all fluid, then all wall,
  // then all dummy (throws std::logic_error otherwise).
  void add(Kind kind, const std::array<double, Dim>& x,
           const std::array<double, Dim>& u = std::array<double, Dim>{});

  // Removes the fluid particles whose flag is set, keeping the order of the rest.
  void remove_fluid(std::span<const char> remove);

  // Reorders the fluid particles: new fluid particle k is old particle order[k]. `order`
  // must be a permutation of [0, fluid).
  void reorder_fluid(std::span<const std::uint32_t> order);
};

// |x_j - x_i|^2 of two particles.
template <int Dim>
double squared_distance(const Particles<Dim>& p, std::size_t i, std::size_t j) {
  double r2 = 0.0;
  for (int d = 0; d < Dim; ++d) {
    const double delta = p.position[d][j] - p.position[d][i];
    r2 += delta * delta;
  }
  return r2;
}

extern template struct Particles<2>;
extern template struct Particles<3>;

}  // namespace swemps::ns

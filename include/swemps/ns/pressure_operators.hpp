#pragma once
// The pressure side of a Navier-Stokes scheme: how the Poisson equation's Laplacian is
// discretised and how the pressure gradient moves the particles. The simulation
// (simulation.hpp) forms the number density, the free surface and the source, and calls
// these at fixed points of the step; a new discretisation is a new class, not flags in the
// step (as the shallow-water schemes, swe/scheme.hpp).
//
// Two are implemented, picked by Settings::operators (make_pressure_operators):
//  - MpsOperators (mps_operators.hpp): the standard MPS Laplacian with its lattice constants
//    (method.md section 3), a symmetric system, and the pressure gradients of
//    Settings::gradient (minimum-pressure, corrected, corrected-repulsive).
//  - LeastSquaresOperators (least_squares_operators.hpp): LSMPS (least_squares.hpp), whose
//    system is not symmetric.

#include <array>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/boundary_pressure.hpp"
#include "swemps/ns/lattice.hpp"
#include "swemps/ns/particles.hpp"
#include "swemps/ns/poisson.hpp"
#include "swemps/ns/settings.hpp"

namespace swemps::ns {

// What the operators read of a step: the particles at the predicted positions x*, the
// neighbour list (rows for the fluid, and for the walls with Poisson walls) and the pressure
// kernel's weight of each of its pairs.
template <int Dim>
struct StepGeometry {
  const Particles<Dim>& particles;
  const neighbors::NeighborList& pairs;
  std::span<const double> pair_weight;
  const Settings& settings;
  const LatticeConstants& lattice;  // the pressure kernel's
};

template <int Dim>
class PressureOperators {
 public:
  virtual ~PressureOperators() = default;
  virtual std::string_view name() const = 0;

  // The Poisson system (poisson.hpp) over the particles marked in `unknown`, for the source
  // b_i of `source`: lap p_i = b_i. `boundary` is the wall extrapolation with extrapolated
  // walls, null with Poisson walls. Unknowns whose pressure nothing determines (a group of
  // them with no free surface in reach) are unmarked and left out, so the system is regular;
  // their pressure is 0 like the surface's. Sets out.residual_to_compression to the factor
  // from a row of the system to the Laplacian (the simulation multiplies dt^2 / rho in).
  virtual void assemble(const StepGeometry<Dim>& g, std::vector<char>& unknown,
                        std::span<const double> source, const BoundaryExtrapolation* boundary,
                        PoissonSystem& out) = 0;

  // The velocity change -dt grad p / rho of every fluid particle over a step of dt, from the
  // pressures in g.particles (fluid, walls and, with extrapolated walls, dummies), at the
  // same positions assemble() saw; into change[d][i], i < fluid.
  virtual void velocity_change(const StepGeometry<Dim>& g, double dt,
                               std::array<std::vector<double>, Dim>& change) = 0;
};

template <int Dim>
std::unique_ptr<PressureOperators<Dim>> make_pressure_operators(const Settings& settings);

extern template std::unique_ptr<PressureOperators<2>> make_pressure_operators<2>(const Settings&);
extern template std::unique_ptr<PressureOperators<3>> make_pressure_operators<3>(const Settings&);

}  // namespace swemps::ns

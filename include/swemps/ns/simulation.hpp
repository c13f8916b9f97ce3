#pragma once
// Incompressible Navier-Stokes by semi-implicit MPS (method.md section 3; Koshizuka & Oka
// 1996), in a vertical plane (Dim = 2, axes x, z) or in 3D (x, y, z). Gravity acts along
// the last axis. Water is fluid particles of equal volume l_0^Dim; walls are wall and dummy
// particles (particles.hpp).
//
// One step, and why in this order:
//  1. Neighbours at x^k. Every few steps the fluid is first sorted by cell, so that
//     neighbours are near in memory.
//  2. Explicit part: u* = u + dt (nu <lap u> + g), with the velocity kernel's Laplacian
//     (2d/(lambda n0)) sum_j (u_j - u_i) w_ij. Walls and dummies carry u = 0: no slip.
//     With the mixed source, n^k is summed here too.
//  3. Predicted positions x* = x + dt u*; the optional collision model separates fluid
//     particles closer than a fraction of l_0 (before the density is measured, so the
//     Poisson equation sees the corrected positions).
//  4. Neighbours at x*; number density n*_i = sum_j w_ij with the pressure kernel over all
//     kinds. n*_i < beta n0 marks the free surface (p = 0), where the optional asymmetry
//     test (settings.hpp) also finds the neighbourhood one-sided.
//  5. Pressure Poisson equation (poisson.hpp) for fluid and wall particles that are not on
//     the surface, assembled by the scheme's pressure operators (pressure_operators.hpp: the
//     MPS Laplacian, or the least-squares one) and solved by a preconditioned Krylov method
//     warm-started from the last pressure. Negative pressures are set to zero: water does
//     not hold tension here, and a negative p_j would pull particles together. With
//     BoundaryPressure::extrapolated the walls are no unknowns: their pressures follow from
//     the fluid's (boundary_pressure.hpp).
//  6. Pressure gradient, by the same operators: with the MPS ones (d/n0) sum_j (p_j -
//     p_min,i) x_ij w_ij / r_ij^2 over fluid and wall neighbours (subtracting the smallest
//     nearby pressure makes every pair repulsive), or the corrected variants (settings.hpp),
//     which apply the inverse correction matrix to the sum of p_j - p_i, with the p_min
//     repulsion only between close pairs or not at all; with the least-squares ones each
//     particle's fit (least_squares_operators.hpp).
//  7. Correction: u = u* - dt grad p / rho, x = x* + dt (u - u*).
//  8. Fluid that left the tank's box (through a wall, a breakdown sign) is removed and
//     counted, never silently kept.

#include <array>
#include <chrono>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/boundary_pressure.hpp"
#include "swemps/ns/lattice.hpp"
#include "swemps/ns/particles.hpp"
#include "swemps/ns/poisson.hpp"
#include "swemps/ns/pressure_operators.hpp"
#include "swemps/ns/settings.hpp"
#include "swemps/swe/state_record.hpp"

namespace swemps::ns {

// The run cannot go on: non-finite values or a time step that collapsed.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StepReport {
  double time_step_s = 0.0;
  PoissonReport poisson;
  std::size_t unknowns = 0;           // particles in the Poisson equation
  std::size_t surface_particles = 0;  // fluid particles with p = 0 as free surface
  std::size_t collisions = 0;
};

struct PhaseTimes {  // wall-clock seconds per part of the step, summed over the run
  double sort = 0.0, neighbors = 0.0, explicit_part = 0.0, density = 0.0, assembly = 0.0,
         solve = 0.0, correction = 0.0;
  double total() const {
    return sort + neighbors + explicit_part + density + assembly + solve + correction;
  }
};

struct RunTotals {
  std::size_t steps = 0;
  long long poisson_iterations = 0;
  int max_poisson_iterations = 0;
  std::size_t unconverged_solves = 0;  // solves that hit max_iterations
  std::size_t lost_particles = 0;      // fluid removed for leaving the tank's box
  PhaseTimes phases;
};

template <int Dim>
class Simulation {
 public:
  // `bounds`: the box a fluid particle must stay in (the tank, walls included); leaving it
  // removes the particle (step 8). Throws std::invalid_argument for settings out of range
  // or no fluid.
  Simulation(Particles<Dim> particles, const Settings& settings,
             const std::array<double, Dim>& lower, const std::array<double, Dim>& upper);

  double time() const { return time_; }
  std::size_t steps() const { return totals_.steps; }
  const Particles<Dim>& particles() const { return particles_; }
  const Settings& settings() const { return settings_; }
  const kernels::AnyKernel<Dim>& pressure_kernel() const { return pressure_kernel_; }
  const LatticeConstants& pressure_lattice() const { return pressure_lattice_; }
  const StepReport& last_step() const { return last_; }
  const RunTotals& totals() const { return totals_; }
  // Number density n* and free-surface flags of the last step, for fluid and wall particles.
  std::span<const double> number_density() const { return number_density_; }
  std::span<const char> free_surface() const { return surface_; }
  // The pressure Poisson system of the last step, as it was handed to the solver (for
  // measuring linear solvers on real systems).
  const PoissonSystem& poisson_system() const { return system_; }

  // courant l_0 / u, with u the larger of the fastest fluid particle and the free-fall speed
  // sqrt(2 g H) over the water's height H; bounded by the viscous limit 0.2 l_0^2 / nu and by
  // max_time_step_s.
  double stable_time_step() const;
  // One step of dt (> 0). Throws SimulationError if the state stops being finite.
  void advance(double dt);
  // Steps until time() == t exactly: the span left is cut into equal steps of at most
  // stable_time_step(), so none is shorter than half of it.
  void advance_to(double t);

  // Everything the next step depends on, as a record (a checkpoint's simulation part): time,
  // run totals, the last step's report, and every particle's position, velocity and pressure
  // (the pressure is the next Poisson solve's starting guess, so it decides the next step's
  // round-off). Neighbour lists, number densities and the Poisson system are made anew each
  // step from these, so a restored simulation steps on bit for bit.
  void save_state(swe::StateWriter& out) const;
  // Into a simulation built from the same scene. Throws swe::StateError for a record of
  // another model or dimension, or of a tank with other particle counts.
  void restore_state(swe::StateReader& in);

 private:
  void sort_fluid_by_cell();
  void find_neighbours();
  void explicit_part(double dt);
  void collide(double dt);
  void measure_density(double dt);
  // Whether particle i's neighbourhood is one-sided (the free surface's second test).
  bool one_sided(std::size_t i) const;
  void solve_pressure(double dt);
  void correct(double dt);
  void remove_escaped();
  StepGeometry<Dim> geometry() const {
    return {particles_, pairs_, pair_weight_, settings_, pressure_lattice_};
  }

  Particles<Dim> particles_;
  Settings settings_;
  std::array<double, Dim> lower_, upper_;
  kernels::AnyKernel<Dim> pressure_kernel_, velocity_kernel_;
  LatticeConstants pressure_lattice_, velocity_lattice_;
  double search_radius_ = 0.0;
  PoissonSolver solver_;
  std::unique_ptr<PressureOperators<Dim>> operators_;

  double time_ = 0.0;
  StepReport last_;
  RunTotals totals_;

  neighbors::CellList<Dim> cells_;
  neighbors::NeighborList pairs_;
  std::vector<double> pair_weight_;       // pressure kernel, per pair of pairs_
  std::vector<double> number_density_;    // n*, fluid and wall
  std::vector<double> previous_density_;  // n^k (mixed source)
  std::vector<char> surface_, unknown_;
  std::vector<double> source_;
  std::array<std::vector<double>, Dim> predicted_velocity_;
  BoundaryExtrapolation boundary_;  // BoundaryPressure::extrapolated only
  PoissonSystem system_;
  Eigen::VectorXd guess_;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

}  // namespace swemps::ns

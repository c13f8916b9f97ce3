#include "swemps/ns/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/ns/boundary_pressure.hpp"

namespace swemps::ns {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("ns settings: " + what);
}

void check_settings(const Settings& s) {
  require(s.spacing_m > 0.0 && std::isfinite(s.spacing_m), "spacing must be finite and > 0");
  require(s.density_kg_m3 > 0.0 && std::isfinite(s.density_kg_m3), "density must be > 0");
  require(s.kinematic_viscosity_m2_s >= 0.0 && std::isfinite(s.kinematic_viscosity_m2_s),
          "viscosity must be >= 0");
  require(s.gravity_m_s2 >= 0.0 && std::isfinite(s.gravity_m_s2), "gravity must be >= 0");
  require(s.courant > 0.0 && s.courant <= 1.0, "courant number must be in (0, 1]");
  require(s.max_time_step_s > 0.0, "max time step must be > 0");
  require(s.free_surface_beta > 0.0 && s.free_surface_beta < 1.0, "beta must be in (0, 1)");
  require(s.source_gamma >= 0.0 && s.source_gamma <= 1.0, "gamma must be in [0, 1]");
  require(s.repulsion_distance_spacings > 0.0 && s.repulsion_distance_spacings <= 8.0,
          "repulsion distance must be in (0, 8] spacings");
  require(s.free_surface_asymmetry >= 0.0 && s.free_surface_asymmetry < 1.0,
          "free-surface asymmetry must be in [0, 1) spacings");
  require(s.gradient != PressureGradient::minimum_pressure ||
              (s.boundary == BoundaryPressure::poisson && s.free_surface_asymmetry == 0.0),
          "extrapolated boundary pressures and the free-surface asymmetry test need the "
          "corrected pressure gradient");
  for (const KernelChoice* k : {&s.pressure_kernel, &s.velocity_kernel}) {
    require(k->support_spacings > 1.0 && k->support_spacings <= 8.0,
            "kernel support must be in (1, 8] spacings");
  }
  if (s.collision) {
    require(s.collision->distance_spacings > 0.0 && s.collision->distance_spacings < 1.0,
            "collision distance must be in (0, 1) spacings");
    require(s.collision->restitution >= 0.0 && s.collision->restitution <= 1.0,
            "collision restitution must be in [0, 1]");
  }
  require(s.operators != Operators::least_squares ||
              (s.boundary == BoundaryPressure::extrapolated &&
               s.gradient != PressureGradient::minimum_pressure),
          "the least-squares operators need extrapolated boundary pressures and a corrected "
          "pressure gradient");
  require(s.gradient_weights == GradientWeights::mps ||
              (s.gradient != PressureGradient::minimum_pressure && s.operators == Operators::mps),
          "the kernel-slope gradient weights need a corrected gradient on the MPS operators");
  require(s.sort_interval >= 1, "sort interval must be >= 1");
}

template <int Dim>
kernels::AnyKernel<Dim> kernel_of(const KernelChoice& choice, double spacing_m) {
  return kernels::make_kernel<Dim>(choice.spec, choice.support_spacings * spacing_m);
}

}  // namespace

template <int Dim>
Simulation<Dim>::Simulation(Particles<Dim> particles, const Settings& settings,
                            const std::array<double, Dim>& lower,
                            const std::array<double, Dim>& upper)
    : particles_(std::move(particles)),
      settings_((check_settings(settings), settings)),
      lower_(lower),
      upper_(upper),
      pressure_kernel_(kernel_of<Dim>(settings.pressure_kernel, settings.spacing_m)),
      velocity_kernel_(kernel_of<Dim>(settings.velocity_kernel, settings.spacing_m)),
      pressure_lattice_(lattice_constants<Dim>(pressure_kernel_, settings.spacing_m)),
      velocity_lattice_(lattice_constants<Dim>(velocity_kernel_, settings.spacing_m)),
      search_radius_(std::max(kernels::support<Dim>(pressure_kernel_),
                              kernels::support<Dim>(velocity_kernel_))),
      solver_(settings.solver),
      operators_(make_pressure_operators<Dim>(settings)) {
  if (particles_.fluid == 0) throw std::invalid_argument("ns simulation: no fluid particles");
  for (int d = 0; d < Dim; ++d) {
    if (!(upper_[d] > lower_[d])) throw std::invalid_argument("ns simulation: empty bounds");
  }
}

template <int Dim>
double Simulation<Dim>::stable_time_step() const {
  const double l0 = settings_.spacing_m;
  double speed2 = 0.0;
  for (std::size_t i = 0; i < particles_.fluid; ++i) {
    double s2 = 0.0;
    for (int d = 0; d < Dim; ++d) s2 += particles_.velocity[d][i] * particles_.velocity[d][i];
    speed2 = std::max(speed2, s2);
  }
  // The speed scale is the larger of the fastest particle and the free-fall speed over
  // the water's height: a column at rest is about to move that fast, and a step sized on
  // u = 0 alone would let gravity compress the bottom layer by a large part of l_0.
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (std::size_t i = 0; i < particles_.fluid; ++i) {
    lowest = std::min(lowest, particles_.position[Dim - 1][i]);
    highest = std::max(highest, particles_.position[Dim - 1][i]);
  }
  const double height = std::max(highest - lowest, 0.0) + l0;
  const double speed =
      std::max(std::sqrt(speed2), std::sqrt(2.0 * settings_.gravity_m_s2 * height));
  double dt = settings_.max_time_step_s;
  if (speed > 0.0) dt = std::min(dt, settings_.courant * l0 / speed);
  if (settings_.kinematic_viscosity_m2_s > 0.0) {
    dt = std::min(dt, 0.2 * l0 * l0 / settings_.kinematic_viscosity_m2_s);
  }
  return dt;
}

template <int Dim>
void Simulation<Dim>::advance_to(double t) {
  while (time_ < t) {
    // The span left is cut into equal steps no longer than the stable one, so no step is
    // shorter than half of it: the number-density source scales a density error by 1/dt^2,
    // and a sliver of a step to land on t would spike the pressure.
    const double remaining = t - time_;
    const double steps = std::ceil(remaining / stable_time_step() * (1.0 - 1e-12));
    if (steps <= 1.0) {
      advance(remaining);
      time_ = t;
    } else {
      advance(remaining / steps);
    }
  }
}

template <int Dim>
void Simulation<Dim>::advance(double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw SimulationError("ns step: time step " + std::to_string(dt) + " s is not > 0");
  }
  last_ = StepReport{};
  last_.time_step_s = dt;
  auto start = Clock::now();
  if (totals_.steps % settings_.sort_interval == 0) {
    sort_fluid_by_cell();
    totals_.phases.sort += seconds_since(start);
  }
  start = Clock::now();
  find_neighbours();
  totals_.phases.neighbors += seconds_since(start);
  start = Clock::now();
  explicit_part(dt);
  if (settings_.collision) collide(dt);
  totals_.phases.explicit_part += seconds_since(start);
  start = Clock::now();
  find_neighbours();
  totals_.phases.neighbors += seconds_since(start);
  start = Clock::now();
  measure_density(dt);
  totals_.phases.density += seconds_since(start);
  solve_pressure(dt);
  start = Clock::now();
  correct(dt);
  remove_escaped();
  totals_.phases.correction += seconds_since(start);
  time_ += dt;
  ++totals_.steps;
}

template <int Dim>
void Simulation<Dim>::sort_fluid_by_cell() {
  const std::size_t fluid = particles_.fluid;
  neighbors::Coordinates<Dim> coords;
  for (int d = 0; d < Dim; ++d)
    coords[d] = std::span<const double>(particles_.position[d]).first(fluid);
  neighbors::CellList<Dim> cells;
  cells.build(coords, search_radius_);
  const auto order = cells.order();
  const std::vector<std::uint32_t> old_of_new(order.begin(), order.end());
  particles_.reorder_fluid(old_of_new);
  solver_.follow_renumbering(old_of_new);
}

template <int Dim>
void Simulation<Dim>::find_neighbours() {
  const auto coords = particles_.coordinates();
  cells_.build(coords, search_radius_);
  // Wall particles need rows of their own only as unknowns of the Poisson equation; with
  // extrapolated boundary pressures only the fluid's rows are read (in 3D tanks the walls
  // outnumber the water, and their rows took a third of the step).
  const std::size_t rows = settings_.boundary == BoundaryPressure::extrapolated
                               ? particles_.fluid
                               : particles_.fluid + particles_.wall;
  neighbors::build_neighbor_list<Dim>(cells_, coords, rows, search_radius_, pairs_);
}

template <int Dim>
void Simulation<Dim>::explicit_part(double dt) {
  const std::size_t fluid = particles_.fluid;
  const double nu = settings_.kinematic_viscosity_m2_s;
  const double viscous_factor =
      nu * 2.0 * Dim / (velocity_lattice_.lambda_m2 * velocity_lattice_.number_density);
  const bool mixed = settings_.source == SourceTerm::mixed;
  const std::size_t candidates = particles_.fluid + particles_.wall;
  if (mixed) previous_density_.assign(candidates, 0.0);
  for (int d = 0; d < Dim; ++d) predicted_velocity_[d].resize(fluid);
  auto& p = particles_;
  std::visit(
      [&](const auto& velocity_kernel) {
        std::visit(
            [&](const auto& pressure_kernel) {
              parallel_for(pairs_.row_count(), [&](std::size_t i) {
                std::array<double, Dim> laplacian{};
                double density = 0.0;
                for (std::uint32_t j : pairs_.row(i)) {
                  const double r = std::sqrt(squared_distance(p, i, j));
                  if (mixed) density += pressure_kernel.w(r);
                  if (i >= fluid || nu == 0.0) continue;
                  const double w = velocity_kernel.w(r);
                  for (int d = 0; d < Dim; ++d) {
                    laplacian[d] += (p.velocity[d][j] - p.velocity[d][i]) * w;
                  }
                }
                if (mixed) previous_density_[i] = density;
                if (i >= fluid) return;
                for (int d = 0; d < Dim; ++d) {
                  const double gravity = d == Dim - 1 ? -settings_.gravity_m_s2 : 0.0;
                  predicted_velocity_[d][i] =
                      p.velocity[d][i] + dt * (viscous_factor * laplacian[d] + gravity);
                }
              });
            },
            pressure_kernel_);
      },
      velocity_kernel_);
  for (int d = 0; d < Dim; ++d) {
    for (std::size_t i = 0; i < fluid; ++i) {
      p.velocity[d][i] = predicted_velocity_[d][i];
      p.position[d][i] += dt * p.velocity[d][i];
    }
  }
}

// Koshizuka's collision model on the predicted positions: for each close, approaching pair
// the approaching part of the relative velocity is reduced to restitution times itself,
// shared equally (equal masses). Each particle sums the changes from all its pairs from the
// same velocities (Jacobi), so the result does not depend on the order or thread count.
template <int Dim>
void Simulation<Dim>::collide(double dt) {
  const std::size_t fluid = particles_.fluid;
  const double limit = settings_.collision->distance_spacings * settings_.spacing_m;
  const double share = 0.5 * (1.0 + settings_.collision->restitution);
  auto& p = particles_;
  std::vector<char> hit(fluid, 0);
  parallel_for(fluid, [&](std::size_t i) {
    std::array<double, Dim> change{};
    for (std::uint32_t j : pairs_.row(i)) {
      const double r2 = squared_distance(p, i, j);
      if (r2 >= limit * limit || r2 == 0.0) continue;
      const double r = std::sqrt(r2);
      double approach = 0.0;  // (u_i - u_j) . e_ij, e_ij from i to j
      for (int d = 0; d < Dim; ++d) {
        approach +=
            (p.velocity[d][i] - p.velocity[d][j]) * (p.position[d][j] - p.position[d][i]) / r;
      }
      if (approach <= 0.0) continue;
      // Against a wall or dummy (fixed) the particle alone takes the whole exchange.
      const double part = j < fluid ? share : 1.0 + settings_.collision->restitution;
      for (int d = 0; d < Dim; ++d) {
        change[d] -= part * approach * (p.position[d][j] - p.position[d][i]) / r;
      }
      hit[i] = 1;
    }
    for (int d = 0; d < Dim; ++d) predicted_velocity_[d][i] = p.velocity[d][i] + change[d];
  });
  std::size_t count = 0;
  for (std::size_t i = 0; i < fluid; ++i) {
    if (!hit[i]) continue;
    ++count;
    for (int d = 0; d < Dim; ++d) {
      p.position[d][i] += dt * (predicted_velocity_[d][i] - p.velocity[d][i]);
      p.velocity[d][i] = predicted_velocity_[d][i];
    }
  }
  last_.collisions = count;
}

template <int Dim>
void Simulation<Dim>::measure_density(double dt) {
  const std::size_t fluid = particles_.fluid;
  const std::size_t candidates = fluid + particles_.wall;
  pair_weight_.resize(pairs_.index.size());
  number_density_.assign(candidates, 0.0);
  // With extrapolated boundary pressures, the fluid's distance to a boundary particle is
  // taken without gravity's part of the predicted displacement, g dt^2 (settings.hpp).
  const double lift =
      settings_.boundary == BoundaryPressure::extrapolated ? settings_.gravity_m_s2 * dt * dt : 0.0;
  const auto& p = particles_;
  std::visit(
      [&](const auto& kernel) {
        parallel_for(pairs_.row_count(), [&](std::size_t i) {
          double density = 0.0;
          const std::size_t first = pairs_.offsets[i];
          const auto row = pairs_.row(i);
          for (std::size_t m = 0; m < row.size(); ++m) {
            const std::uint32_t j = row[m];
            const double w = kernel.w(std::sqrt(squared_distance(p, i, j)));
            pair_weight_[first + m] = w;
            if (lift == 0.0 || i >= fluid || j < fluid) {
              density += w;
              continue;
            }
            double r2 = 0.0;
            for (int d = 0; d < Dim; ++d) {
              const double delta =
                  p.position[d][j] - p.position[d][i] - (d == Dim - 1 ? lift : 0.0);
              r2 += delta * delta;
            }
            density += kernel.w(std::sqrt(r2));
          }
          number_density_[i] = density;
        });
      },
      pressure_kernel_);
}

template <int Dim>
bool Simulation<Dim>::one_sided(std::size_t i) const {
  const double limit = settings_.free_surface_asymmetry * settings_.spacing_m;
  if (limit == 0.0) return true;
  std::array<double, Dim> offset{};
  double total = 0.0;
  const std::size_t first = pairs_.offsets[i];
  const auto row = pairs_.row(i);
  for (std::size_t m = 0; m < row.size(); ++m) {
    const double w = pair_weight_[first + m];
    total += w;
    for (int d = 0; d < Dim; ++d) {
      offset[d] += w * (particles_.position[d][row[m]] - particles_.position[d][i]);
    }
  }
  if (!(total > 0.0)) return true;
  double length2 = 0.0;
  for (int d = 0; d < Dim; ++d) length2 += offset[d] * offset[d];
  return length2 > limit * limit * total * total;
}

template <int Dim>
void Simulation<Dim>::solve_pressure(double dt) {
  auto start = Clock::now();
  const std::size_t fluid = particles_.fluid;
  const std::size_t candidates = fluid + particles_.wall;
  const double n0 = pressure_lattice_.number_density;
  const double threshold = settings_.free_surface_beta * n0;
  const double scale = settings_.density_kg_m3 / (dt * dt);
  const bool mixed = settings_.source == SourceTerm::mixed;
  const bool extrapolated = settings_.boundary == BoundaryPressure::extrapolated;
  surface_.assign(candidates, 0);
  unknown_.assign(candidates, 0);
  source_.assign(candidates, 0.0);
  std::size_t surface_count = 0;
  for (std::size_t i = 0; i < (extrapolated ? fluid : candidates); ++i) {
    const double n = number_density_[i];
    surface_[i] = n < threshold && one_sided(i);
    if (surface_[i]) {
      if (i < fluid) ++surface_count;
      continue;
    }
    // A wall particle takes part only next to water; alone it would form a group of
    // unknowns with no free surface, and the matrix would be singular.
    // Any unknown also needs a fluid or wall neighbour inside the support, or its row of
    // the matrix would be empty.
    bool active = false, coupled = false;
    const std::size_t first = pairs_.offsets[i];
    const auto row = pairs_.row(i);
    for (std::size_t m = 0; m < row.size(); ++m) {
      if ((!extrapolated && row[m] >= candidates) || !(pair_weight_[first + m] > 0.0)) continue;
      coupled = true;
      if (row[m] < fluid || i < fluid) active = true;
    }
    if (!active || !coupled) continue;
    unknown_[i] = 1;
    source_[i] = mixed ? -scale * ((n - previous_density_[i]) / n0 +
                                   settings_.source_gamma * (previous_density_[i] - n0) / n0)
                       : -scale * (n - n0) / n0;
  }
  if (extrapolated) {
    build_boundary_extrapolation(pairs_, pair_weight_, fluid, particles_.size(),
                                 particles_.position[Dim - 1],
                                 settings_.density_kg_m3 * settings_.gravity_m_s2, boundary_);
  }
  operators_->assemble(geometry(), unknown_, source_, extrapolated ? &boundary_ : nullptr,
                       system_);
  system_.residual_to_compression *= dt * dt / settings_.density_kg_m3;
  guess_.resize(static_cast<Eigen::Index>(system_.particle_of_unknown.size()));
  for (std::size_t k = 0; k < system_.particle_of_unknown.size(); ++k) {
    guess_[static_cast<Eigen::Index>(k)] = particles_.pressure[system_.particle_of_unknown[k]];
  }
  totals_.phases.assembly += seconds_since(start);
  start = Clock::now();
  try {
    last_.poisson = solver_.solve(system_, guess_);
  } catch (const std::runtime_error& e) {
    // A preconditioner that cannot be formed means the matrix is no longer an M-matrix: the
    // particles have broken down, which callers report as such.
    throw SimulationError(std::string("ns step: ") + e.what() + " at t = " + std::to_string(time_) +
                          " s");
  }
  totals_.phases.solve += seconds_since(start);
  std::fill(particles_.pressure.begin(), particles_.pressure.end(), 0.0);
  for (std::size_t k = 0; k < system_.particle_of_unknown.size(); ++k) {
    const double value = guess_[static_cast<Eigen::Index>(k)];
    if (!std::isfinite(value)) {
      throw SimulationError("ns step: the pressure solve gave a non-finite value at t = " +
                            std::to_string(time_) + " s");
    }
    particles_.pressure[system_.particle_of_unknown[k]] = std::max(value, 0.0);
  }
  if (extrapolated) extrapolate_boundary_pressure(boundary_, particles_.pressure);
  last_.unknowns = system_.particle_of_unknown.size();
  last_.surface_particles = surface_count;
  totals_.poisson_iterations += last_.poisson.iterations;
  totals_.max_poisson_iterations =
      std::max(totals_.max_poisson_iterations, last_.poisson.iterations);
  if (!last_.poisson.converged) ++totals_.unconverged_solves;
}

template <int Dim>
void Simulation<Dim>::correct(double dt) {
  const std::size_t fluid = particles_.fluid;
  operators_->velocity_change(geometry(), dt, predicted_velocity_);
  auto& p = particles_;
  for (int d = 0; d < Dim; ++d) {
    for (std::size_t i = 0; i < fluid; ++i) {
      const double change = predicted_velocity_[d][i];
      if (!std::isfinite(change)) {
        throw SimulationError(
            "ns step: non-finite pressure gradient at t = " + std::to_string(time_) + " s");
      }
      p.velocity[d][i] += change;
      p.position[d][i] += dt * change;
    }
  }
}

template <int Dim>
void Simulation<Dim>::remove_escaped() {
  const std::size_t fluid = particles_.fluid;
  std::vector<char> gone(fluid, 0);
  std::size_t count = 0;
  for (std::size_t i = 0; i < fluid; ++i) {
    for (int d = 0; d < Dim; ++d) {
      const double x = particles_.position[d][i];
      // No lid: a splash may rise above the walls and fall back.
      const bool above_allowed = d == Dim - 1;
      if (!(x >= lower_[d]) || (!above_allowed && !(x <= upper_[d]))) {
        gone[i] = 1;
      }
    }
    count += gone[i];
  }
  if (count == 0) return;
  particles_.remove_fluid(gone);
  solver_.forget_kept_setup();
  totals_.lost_particles += count;
  if (particles_.fluid == 0) throw SimulationError("ns step: every fluid particle left the tank");
}

namespace {

template <int Dim>
std::string state_label() {
  return Dim == 2 ? "ns simulation 2D" : "ns simulation 3D";
}

}  // namespace

template <int Dim>
void Simulation<Dim>::save_state(swe::StateWriter& out) const {
  out.text(state_label<Dim>());
  out.number(time_);
  out.count(totals_.steps);
  out.count(static_cast<std::uint64_t>(totals_.poisson_iterations));
  out.count(static_cast<std::uint64_t>(totals_.max_poisson_iterations));
  out.count(totals_.unconverged_solves);
  out.count(totals_.lost_particles);
  out.number(last_.time_step_s);
  out.count(static_cast<std::uint64_t>(last_.poisson.iterations));
  out.number(last_.poisson.relative_residual);
  out.count(last_.poisson.converged ? 1 : 0);
  out.count(last_.unknowns);
  out.count(last_.surface_particles);
  out.count(last_.collisions);
  out.count(particles_.fluid);
  out.count(particles_.wall);
  out.count(particles_.dummy);
  for (int d = 0; d < Dim; ++d) out.numbers(particles_.position[d]);
  for (int d = 0; d < Dim; ++d) out.numbers(particles_.velocity[d]);
  out.numbers(particles_.pressure);
}

template <int Dim>
void Simulation<Dim>::restore_state(swe::StateReader& in) {
  in.expect(state_label<Dim>());
  const double time_s = in.number();
  RunTotals totals;
  totals.steps = in.count();
  totals.poisson_iterations = static_cast<long long>(in.count());
  totals.max_poisson_iterations = static_cast<int>(in.count());
  totals.unconverged_solves = in.count();
  totals.lost_particles = in.count();
  StepReport last;
  last.time_step_s = in.number();
  last.poisson.iterations = static_cast<int>(in.count());
  last.poisson.relative_residual = in.number();
  last.poisson.converged = in.count() != 0;
  last.unknowns = in.count();
  last.surface_particles = in.count();
  last.collisions = in.count();
  const std::size_t fluid = in.count(), wall = in.count(), dummy = in.count();
  // Fluid may have left the tank since the start; the tank's walls never change.
  if (wall != particles_.wall || dummy != particles_.dummy ||
      fluid + totals.lost_particles != particles_.fluid + totals_.lost_particles) {
    throw swe::StateError(in.what() + " holds a tank of " + std::to_string(fluid) + " fluid, " +
                          std::to_string(wall) + " wall and " + std::to_string(dummy) +
                          " dummy particles (" + std::to_string(totals.lost_particles) +
                          " lost), this scene's has " + std::to_string(particles_.fluid) + ", " +
                          std::to_string(particles_.wall) + " and " +
                          std::to_string(particles_.dummy) + ": it belongs to another scene");
  }
  Particles<Dim> restored;
  restored.fluid = fluid;
  restored.wall = wall;
  restored.dummy = dummy;
  const auto read_field = [&](std::vector<double>& field) {
    field = in.numbers();
    if (field.size() != restored.size()) {
      throw swe::StateError(in.what() + ": a particle field holds " + std::to_string(field.size()) +
                            " values for " + std::to_string(restored.size()) + " particles");
    }
  };
  for (int d = 0; d < Dim; ++d) read_field(restored.position[d]);
  for (int d = 0; d < Dim; ++d) read_field(restored.velocity[d]);
  read_field(restored.pressure);
  particles_ = std::move(restored);
  time_ = time_s;
  // Phase times are wall-clock seconds of this process, not state.
  totals.phases = totals_.phases;
  totals_ = totals;
  last_ = last;
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace swemps::ns

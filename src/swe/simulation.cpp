#include "swemps/swe/simulation.hpp"

#include <cmath>
#include <sstream>

namespace swemps::swe {

namespace {

using Clock = std::chrono::steady_clock;

// Adds the time since `start` to `total` when it goes out of scope.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(Clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  Clock::time_point start_;
};

neighbors::Coordinates<2> positions(const particles::SweParticles& p, std::size_t count) {
  return {std::span<const double>(p.x.data(), count), std::span<const double>(p.y.data(), count)};
}

}  // namespace

Simulation::Simulation(particles::SweParticles fluid, Settings settings,
                       boundaries::GhostWalls walls, std::vector<std::unique_ptr<Effect>> effects)
    : particles_(std::move(fluid)),
      settings_(settings),
      walls_(std::move(walls)),
      effects_(std::move(effects)),
      effect_seconds_(effects_.size(), 0.0),
      // Before the first summation the areas are the lattice areas A_0.
      kernel_(influence_radius(particles_, settings.alpha_e)) {
  if (particles_.fluid_count() == 0) throw std::invalid_argument("simulation: no water particles");
  if (particles_.ghost_count() != 0)
    throw std::invalid_argument("simulation: ghosts in the initial state");
  ledger_.initial_m3 = particles_.total_fluid_volume();
}

void Simulation::sort_by_cell() {
  ScopedTimer timer(phase_times_.sort);
  cells_.build(positions(particles_, particles_.fluid_count()), kernel_.support());
  order_.assign(cells_.order().begin(), cells_.order().end());
  particles_.reorder(order_);
}

void Simulation::refresh() {
  if (fresh_) return;
  update_fields();
  const std::size_t before = particles_.fluid_count();
  run_effects(Stage::resolution, 0.0);
  // A resolution effect changed the particle set: the neighbour list and the sums no longer
  // describe it. Once more, without the resolution stage, so one step splits at most once.
  if (particles_.fluid_count() != before) update_fields();
  fresh_ = true;
}

void Simulation::update_fields() {
  particles_.drop_ghosts();
  // eq 9 with the areas of the previous summation: the radius must be known before the
  // neighbours (and so the new areas) can be found.
  kernel_ = Kernel(influence_radius(particles_, settings_.alpha_e));
  sort_by_cell();
  {
    ScopedTimer timer(phase_times_.walls);
    walls_.add_ghosts(particles_, kernel_.support());
  }
  {
    ScopedTimer timer(phase_times_.neighbors);
    const auto coords = positions(particles_, particles_.size());
    cells_.build(coords, kernel_.support());
    build_neighbor_list<2>(cells_, coords, particles_.fluid_count(), kernel_.support(),
                           neighbor_list_);
  }
  {
    ScopedTimer timer(phase_times_.depth);
    sum_depth(particles_, neighbor_list_, kernel_);
    boundaries::GhostWalls::copy_fields_to_ghosts(particles_);  // eq 5 and eq 6 read ghosts' h, A
    // Only eq 6 needs the number density (ghosts' own n is never read).
    if (settings_.gradient == GradientVariant::mps) {
      sum_number_density(particles_, neighbor_list_, kernel_);
    }
  }
}

double Simulation::stable_time_step() {
  refresh();
  const TimeStepLimit limit =
      swe::stable_time_step(particles_, settings_.gravity_m_s2, settings_.cfl);
  if (!(limit.dt_s >= settings_.min_time_step_s) || !std::isfinite(limit.dt_s)) {
    const std::size_t i = limit.particle;
    std::ostringstream msg;
    msg << "the time step collapsed to " << limit.dt_s << " s (floor " << settings_.min_time_step_s
        << " s) at t = " << time_s_ << " s, step " << steps_ << ", limited by particle " << i
        << " at (" << particles_.x[i] << ", " << particles_.y[i] << ") m with depth "
        << particles_.depth[i] << " m and velocity (" << particles_.u[i] << ", " << particles_.v[i]
        << ") m/s";
    throw SimulationError(msg.str());
  }
  return limit.dt_s;
}

void Simulation::run_effects(Stage stage, double dt_s) {
  StepContext context{particles_, neighbor_list_, kernel_, accel_x_, accel_y_,
                      settings_,  ledger_,        time_s_, dt_s};
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    if (effects_[k]->stage() != stage) continue;
    ScopedTimer timer(effect_seconds_[k]);
    effects_[k]->apply(context);
  }
}

void Simulation::advance(double dt_s) {
  refresh();
  const std::size_t n = particles_.fluid_count();
  accel_x_.resize(n);
  accel_y_.resize(n);
  {
    ScopedTimer timer(phase_times_.gradient);
    depth_gradient(settings_.gradient, particles_, neighbor_list_, kernel_, accel_x_, accel_y_);
    const double g = settings_.gravity_m_s2;
    for (std::size_t i = 0; i < n; ++i) {  // eq 2 with z_s = h on a flat bed
      accel_x_[i] *= -g;
      accel_y_[i] *= -g;
    }
  }
  run_effects(Stage::forces, dt_s);
  {
    ScopedTimer timer(phase_times_.integrate);
    for (std::size_t i = 0; i < n; ++i) {
      particles_.u[i] += dt_s * accel_x_[i];
      particles_.v[i] += dt_s * accel_y_[i];
    }
  }
  run_effects(Stage::velocity, dt_s);
  {
    ScopedTimer timer(phase_times_.integrate);
    old_x_.assign(particles_.x.begin(), particles_.x.begin() + static_cast<std::ptrdiff_t>(n));
    old_y_.assign(particles_.y.begin(), particles_.y.begin() + static_cast<std::ptrdiff_t>(n));
    for (std::size_t i = 0; i < n; ++i) {
      particles_.x[i] += dt_s * particles_.u[i];
      particles_.y[i] += dt_s * particles_.v[i];
    }
  }
  {
    ScopedTimer timer(phase_times_.walls);
    wall_reflections_ += walls_.keep_inside(particles_, old_x_, old_y_);
  }
  particles_.drop_ghosts();
  fresh_ = false;
  run_effects(Stage::topology, dt_s);
  time_s_ += dt_s;
  ++steps_;
  particle_steps_ += n;
}

double Simulation::relative_volume_change() const {
  const double expected = ledger_.expected_m3();
  return (fluid_volume() - expected) / ledger_.initial_m3;
}

std::vector<EffectTime> Simulation::effect_times() const {
  std::vector<EffectTime> out;
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    out.push_back({std::string(effects_[k]->name()), effect_seconds_[k], effects_[k]->report()});
  }
  return out;
}

}  // namespace swemps::swe

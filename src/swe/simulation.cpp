#include "swemps/swe/simulation.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

namespace {

using Clock = std::chrono::steady_clock;

// Steps between two sorts of the particles by cell: sorting costs a tenth of a step; between
// sorts, the neighbour search still finds every neighbour, only with less memory locality.
constexpr std::size_t kSortInterval = 8;

// Cells half as wide as the support for the neighbour search: about 40 candidates per
// particle instead of 57 for some 20 neighbours (neighbors/cell_list.hpp).
constexpr int kCellSubdivisions = 2;

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
      // Before the first summation the areas are the lattice areas A_0. A run that starts dry
      // (all its water comes through an inflow) has no radius yet; 1 m stands in, unused.
      // No summation has run yet, so no particle is known to be isolated.
      kernel_(particles_.fluid_count() > 0
                  ? influence_radius(particles_, settings.alpha_e, settings.max_area_ratio,
                                     std::numeric_limits<double>::infinity())
                  : 1.0) {
  if (particles_.fluid_count() == 0 && effects_.empty())
    throw std::invalid_argument("simulation: no water particles and nothing to add any");
  if (particles_.ghost_count() != 0)
    throw std::invalid_argument("simulation: ghosts in the initial state");
  ledger_.initial_m3 = particles_.total_fluid_volume();
}

void Simulation::sort_by_cell() {
  ScopedTimer timer(phase_times_.sort);
  last_sort_step_ = steps_;
  sorted_count_ = particles_.fluid_count();
  cells_.build(positions(particles_, particles_.fluid_count()), kernel_.support());
  order_.assign(cells_.order().begin(), cells_.order().end());
  particles_.reorder(order_);
}

void Simulation::refresh() {
  if (fresh_) return;
  update_fields(sorting_due());
  const std::size_t before = particles_.fluid_count();
  run_effects(Stage::resolution, 0.0);
  // A resolution effect changed the particle set: the neighbour list and the sums no longer
  // describe it. Once more, without the resolution stage, so one step splits at most once.
  if (particles_.fluid_count() != before) update_fields(sorting_due());
  fresh_ = true;
}

VolumeBalanceReport Simulation::balance_volumes(std::vector<double> target_depth_m,
                                                double tolerance_m, int max_iterations) {
  std::size_t n = particles_.fluid_count();
  if (target_depth_m.size() != n) {
    throw std::invalid_argument("balance_volumes: one target depth per fluid particle needed");
  }
  for (const double d : target_depth_m) {
    if (!(d > 0.0) || !std::isfinite(d))
      throw std::invalid_argument("balance_volumes: target depths must be finite and > 0");
  }
  VolumeBalanceReport report;
  report.volume_before_m3 = particles_.total_fluid_volume();
  std::vector<double> permuted(n);
  for (report.iterations = 1; report.iterations <= max_iterations; ++report.iterations) {
    update_fields(true);
    // update_fields() sorted the particles: carry the targets along.
    for (std::size_t k = 0; k < n; ++k) permuted[k] = target_depth_m[order_[k]];
    target_depth_m.swap(permuted);
    report.max_depth_error_m = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      report.max_depth_error_m =
          std::max(report.max_depth_error_m, std::abs(particles_.depth[i] - target_depth_m[i]));
    }
    if (report.max_depth_error_m <= tolerance_m) break;
    // h is linear in the volumes for a fixed radius, and every weight is positive, so this
    // multiplicative update keeps volumes positive and converges where a balanced state
    // exists. The area is set to what it will be at balance, so that eq 9 takes its radius
    // from the balanced areas in the next pass.
    //
    // Where the water is thinner than what the neighbours' kernels already bring (a shore
    // particle beside deeper water), no positive volume balances and the iteration drives
    // the volume towards zero: such a particle is removed once its area falls below
    // kVanishingArea of its lattice area, and the others are balanced without it.
    constexpr double kVanishingArea = 0.5;
    std::vector<std::uint8_t> vanishing(n, 0);
    std::size_t vanished = 0;
    for (std::size_t i = 0; i < n; ++i) {
      particles_.volume[i] *= target_depth_m[i] / particles_.depth[i];
      particles_.area[i] = particles_.volume[i] / target_depth_m[i];
      if (particles_.area[i] < kVanishingArea * particles_.initial_area[i]) {
        vanishing[i] = 1;
        ++vanished;
      }
    }
    if (vanished > 0) {
      if (vanished == n)
        throw std::invalid_argument("balance_volumes: no particle can be balanced");
      particles_.drop_ghosts();
      particles_.remove(vanishing);
      std::size_t kept = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (!vanishing[i]) target_depth_m[kept++] = target_depth_m[i];
      }
      target_depth_m.resize(kept);
      n = kept;
      permuted.resize(n);
      report.removed_particles += vanished;
    }
  }
  report.iterations = std::min(report.iterations, max_iterations);
  fresh_ = false;
  ledger_.initial_m3 = particles_.total_fluid_volume();
  report.volume_after_m3 = ledger_.initial_m3;
  return report;
}

bool Simulation::sorting_due() const {
  // Particles move at most about half a spacing per step (eq 13), so memory order decays
  // slowly; a particle set that grew or shrank (splitting, inflow, outflow) is sorted at once,
  // as new particles are appended far from their neighbours in memory.
  return steps_ - last_sort_step_ >= kSortInterval || particles_.fluid_count() != sorted_count_ ||
         steps_ == 0;
}

void Simulation::update_fields(bool sort) {
  particles_.drop_ghosts();
  if (particles_.fluid_count() == 0) return;  // dry so far: nothing to sum
  // eq 9 with the areas of the previous summation: the radius must be known before the
  // neighbours (and so the new areas) can be found.
  kernel_ = Kernel(influence_radius(particles_, settings_.alpha_e, settings_.max_area_ratio,
                                    1.0 / kernel_.w(0.0)));
  if (sort) sort_by_cell();
  {
    ScopedTimer timer(phase_times_.walls);
    walls_.add_ghosts(particles_, kernel_.support());
  }
  {
    ScopedTimer timer(phase_times_.neighbors);
    const auto coords = positions(particles_, particles_.size());
    cells_.build(coords, kernel_.support(), kCellSubdivisions);
    build_neighbor_list<2>(cells_, coords, particles_.fluid_count(), kernel_.support(),
                           neighbor_list_);
  }
  {
    ScopedTimer timer(phase_times_.depth);
    sum_depth(particles_, neighbor_list_, kernel_);
    boundaries::GhostWalls::copy_fields_to_ghosts(particles_);  // eq 5 and eq 6 read ghosts' h, A
    // eq 5's number density is summed with the eq 6 gradient in advance() (one pass for both).
  }
}

double Simulation::stable_time_step() {
  refresh();
  TimeStepLimit limit = swe::stable_time_step(particles_, settings_.gravity_m_s2, settings_.cfl);
  const double effects_limit = effects_time_step_limit();
  if (effects_limit < limit.dt_s) {
    limit.dt_s = effects_limit;
  } else if (particles_.fluid_count() == 0) {
    throw SimulationError(
        "no water is left and no effect adds any at t = " + std::to_string(time_s_) + " s");
  }
  if (particles_.fluid_count() == 0) return limit.dt_s;  // dry: only the effects limit the step
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

double Simulation::effects_time_step_limit() const {
  double limit = std::numeric_limits<double>::infinity();
  for (const auto& effect : effects_) {
    limit = std::min(limit, effect->time_step_limit(settings_, time_s_));
  }
  return limit;
}

void Simulation::run_effects(Stage stage, double dt_s) {
  StepContext context{particles_, neighbor_list_, kernel_, accel_x_, accel_y_,
                      settings_,  ledger_,        time_s_, dt_s};
  if (stage == Stage::topology) {
    context.previous_x = old_x_;
    context.previous_y = old_y_;
  }
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
    parallel_for(n, [&](std::size_t i) {  // eq 2 with z_s = h on a flat bed
      accel_x_[i] *= -g;
      accel_y_[i] *= -g;
    });
  }
  run_effects(Stage::forces, dt_s);
  {
    ScopedTimer timer(phase_times_.integrate);
    parallel_for(n, [&](std::size_t i) {
      particles_.u[i] += dt_s * accel_x_[i];
      particles_.v[i] += dt_s * accel_y_[i];
    });
  }
  run_effects(Stage::velocity, dt_s);
  {
    ScopedTimer timer(phase_times_.integrate);
    old_x_.resize(n);
    old_y_.resize(n);
    parallel_for(n, [&](std::size_t i) {
      old_x_[i] = particles_.x[i];
      old_y_[i] = particles_.y[i];
      particles_.x[i] += dt_s * particles_.u[i];
      particles_.y[i] += dt_s * particles_.v[i];
    });
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
  // Relative to all the water the run has had, so a run that starts dry has a reference too.
  const double reference = ledger_.initial_m3 + ledger_.added_m3;
  if (reference == 0.0) return 0.0;
  return (fluid_volume() - ledger_.expected_m3()) / reference;
}

std::vector<EffectTime> Simulation::effect_times() const {
  std::vector<EffectTime> out;
  for (std::size_t k = 0; k < effects_.size(); ++k) {
    out.push_back({std::string(effects_[k]->name()), effect_seconds_[k], effects_[k]->report()});
  }
  return out;
}

}  // namespace swemps::swe

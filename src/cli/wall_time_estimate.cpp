#include "swemps/cli/wall_time_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "swemps/cli/statistics_sampling.hpp"
#include "swemps/cli/timing.hpp"

namespace swemps::cli {

namespace {

// pilot_factor: the factors it chooses between (scale_pilot's measurements say why no wider).
constexpr int kFinerFactor = 2;
constexpr int kWiderFactor = 3;

// The window's ratios need this many of the pilot's steps in it.
constexpr std::size_t kWindowPilotSteps = 10;

// One simulation stepped for the estimate: each step timed into the fit of its cost, and the
// flood statistics' samples a run of the scene would take counted (run_pilot).
class Recorder {
 public:
  Recorder(const Stepper& sim, double scene_steps_per_step, double map_length_m)
      : sim_(sim),
        scene_steps_(scene_steps_per_step),
        map_length_m_(map_length_m),
        sampled_(static_cast<bool>(sim.fastest_wave_m_s)) {
    if (sampled_) samples_ = 1.0;  // at t = 0
  }

  std::size_t step() {
    const double before_s = sim_.time_s();
    const auto stepping = Clock::now();
    const std::size_t stepped = sim_.step();
    // Timed with the step: reading the speeds may do work the next step would (the depths).
    const double fastest = sampled_ ? sim_.fastest_wave_m_s() : 0.0;
    fit_.add(static_cast<double>(stepped), seconds_since(stepping));
    ++steps_;
    particle_steps_ += static_cast<double>(stepped);
    if (!sampled_) return stepped;
    // The run samples after the first of its steps that ends once a wave could have crossed
    // half the length: every ceil(interval / dt) of its steps, dt the pilot's step over the
    // scene's steps in it; every step where there is no wave.
    const double dt_s = sim_.time_s() - before_s;
    const double interval_s = fastest > 0.0 ? kMapCourant * map_length_m_ / fastest : 0.0;
    const double scene_dt_s = dt_s / scene_steps_;
    const double period_s = scene_dt_s * std::max(1.0, std::ceil(interval_s / scene_dt_s - 1e-9));
    if (period_s > 0.0) samples_ += dt_s / period_s;
    if (sim_.on_output_time && sim_.on_output_time()) samples_ += 1.0;
    return stepped;
  }

  std::size_t steps() const { return steps_; }
  double particle_steps() const { return particle_steps_; }
  double samples() const { return samples_; }
  const StepCostFit& fit() const { return fit_; }

 private:
  const Stepper& sim_;
  double scene_steps_, map_length_m_;
  bool sampled_;
  StepCostFit fit_;
  std::size_t steps_ = 0;
  double particle_steps_ = 0.0, samples_ = 0.0;
};

}  // namespace

void StepCostFit::add(double particles, double seconds) {
  n_ += 1.0;
  x_ += particles;
  y_ += seconds;
  xx_ += particles * particles;
  xy_ += particles * seconds;
}

// Not separable: a spread of particle counts too narrow to tell the two costs apart (round-off
// of the sums), or a line with a negative cost either way (steps timed through a noisy clock).
// The mean cost of a particle-step then keeps the fitted total the total measured.
bool StepCostFit::separable() const {
  const double spread = n_ * xx_ - x_ * x_;
  if (!(n_ > 0.0 && spread > 1e-9 * n_ * xx_)) return false;
  const double slope = (n_ * xy_ - x_ * y_) / spread;
  return slope >= 0.0 && y_ - slope * x_ >= 0.0;
}

double StepCostFit::per_particle_step() const {
  if (separable()) return (n_ * xy_ - x_ * y_) / (n_ * xx_ - x_ * x_);
  return x_ > 0.0 ? y_ / x_ : 0.0;
}

double StepCostFit::per_step() const {
  return separable() ? (y_ - per_particle_step() * x_) / n_ : 0.0;
}

SceneWindow step_window(double end_time_s, const Stepper& scene, double map_length_m,
                        double budget_s) {
  SceneWindow w;
  Recorder recorder(scene, 1.0, map_length_m);
  // A scene that starts dry has nothing to time until an inflow lets water in; those steps
  // cost next to nothing, and count against the budget too.
  const auto start = Clock::now();
  while (scene.fluid() == 0 && scene.time_s() < end_time_s && seconds_since(start) < budget_s) {
    recorder.step();
  }
  w.dry_time_s = scene.time_s();
  const std::size_t dry_steps = recorder.steps();
  const auto timed = Clock::now();
  while (scene.time_s() < end_time_s && seconds_since(start) < budget_s) {
    w.particle_steps += static_cast<double>(recorder.step());
  }
  w.seconds = seconds_since(timed);
  w.steps = recorder.steps() - dry_steps;
  w.until_s = scene.time_s();
  w.finished = w.until_s >= end_time_s;
  w.statistics_samples = recorder.samples();
  return w;
}

int pilot_factor(double window_estimate_s, int dimensions, double budget_s) {
  const double finer_s = window_estimate_s / std::pow(double(kFinerFactor), dimensions + 1);
  return finer_s <= budget_s ? kFinerFactor : kWiderFactor;
}

double PilotSetup::scene_steps_per_step() const {
  return first_dt_s > 0.0 && scene_first_dt_s > 0.0 ? first_dt_s / scene_first_dt_s
                                                    : static_cast<double>(factor);
}

PilotRun run_pilot(const PilotSetup& setup, const Stepper& pilot) {
  PilotRun run;
  run.setup = setup;
  Recorder recorder(pilot, setup.scene_steps_per_step(), setup.map_length_m);
  const auto start = Clock::now();
  const auto go_on = [&] {
    return pilot.time_s() < setup.end_time_s && seconds_since(start) < setup.budget_s;
  };
  while (pilot.fluid() == 0 && go_on()) recorder.step();
  run.dry_time_s = pilot.time_s();
  // The steps that end within the scene's window, to the round-off of the running sum of dt.
  const double window_end_s = setup.window.until_s * (1.0 + 1e-12);
  while (go_on() && pilot.time_s() < window_end_s) {
    const std::size_t stepped = recorder.step();
    if (pilot.time_s() > window_end_s) break;
    ++run.window_steps;
    run.window_particle_steps += static_cast<double>(stepped);
  }
  while (go_on()) recorder.step();
  run.seconds = seconds_since(start);
  run.steps = recorder.steps();
  run.particle_steps = recorder.particle_steps();
  run.reached_s = pilot.time_s();
  run.finished = run.reached_s >= setup.end_time_s;
  run.statistics_samples = recorder.samples();
  run.seconds_per_step = recorder.fit().per_step();
  run.seconds_per_particle_step = recorder.fit().per_particle_step();
  return run;
}

WallTimeEstimate scale_pilot(const PilotRun& pilot, double particle_ratio,
                             double seconds_per_sample, double reading_s) {
  const PilotSetup& setup = pilot.setup;
  const SceneWindow& window = setup.window;
  WallTimeEstimate e;
  // The share of the run the pilot covered, counted from its first particle: the time before
  // costs next to nothing.
  double to_end = 1.0;
  if (!pilot.finished) {
    const double covered_s = pilot.reached_s - pilot.dry_time_s;
    to_end = covered_s > 0.0 ? (setup.end_time_s - pilot.dry_time_s) / covered_s : 1.0;
    e.extrapolated = true;
  }
  double step_ratio = setup.scene_steps_per_step();
  double cost_ratio = 1.0;
  const double a = pilot.seconds_per_step, b = pilot.seconds_per_particle_step;
  if (pilot.window_steps >= kWindowPilotSteps && pilot.window_particle_steps > 0.0 &&
      window.steps > 0 && window.measured()) {
    const auto scene_steps = static_cast<double>(window.steps);
    const auto pilot_steps = static_cast<double>(pilot.window_steps);
    step_ratio = scene_steps / pilot_steps;
    const double fitted_s = a * scene_steps + b * window.particle_steps;
    if (fitted_s > 0.0) cost_ratio = window.seconds / fitted_s;
    e.calibrated = true;
  }
  e.step_ratio = step_ratio;
  e.particle_ratio = particle_ratio;
  e.cost_ratio = cost_ratio;
  e.steps = static_cast<double>(pilot.steps) * step_ratio * to_end;
  e.particle_steps = pilot.particle_steps * step_ratio * particle_ratio * to_end;
  e.stepping_s = cost_ratio * (e.steps * a + e.particle_steps * b);
  e.statistics_samples = pilot.statistics_samples * to_end;
  e.statistics_s = e.statistics_samples * seconds_per_sample;
  e.seconds = e.stepping_s + e.statistics_s + reading_s;
  return e;
}

WallTimeEstimate whole_window(const SceneWindow& window, double seconds_per_sample,
                              double reading_s) {
  WallTimeEstimate e;
  e.steps = static_cast<double>(window.steps);
  e.particle_steps = window.particle_steps;
  e.stepping_s = window.seconds;
  e.statistics_samples = window.statistics_samples;
  e.statistics_s = e.statistics_samples * seconds_per_sample;
  e.seconds = e.stepping_s + e.statistics_s + reading_s;
  return e;
}

}  // namespace swemps::cli

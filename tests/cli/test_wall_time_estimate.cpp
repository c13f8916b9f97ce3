// How `swe-mps check` turns a pilot run into the scene's wall time: the pilot's factor, its
// count of statistics samples as a run takes them, the fitted cost of a step, and the scaling
// back to the scene's spacing (wall times themselves are measured, never asserted).

#include <catch2/catch.hpp>

#include "swemps/cli/wall_time_estimate.hpp"

using swemps::cli::PilotRun;
using swemps::cli::StepCostFit;
using swemps::cli::Stepper;

TEST_CASE("the pilot runs at twice the spacing, or 3 times where that would not finish",
          "[cli][estimate]") {
  using swemps::cli::pilot_factor;
  CHECK(pilot_factor(0.0, 2, 30.0) == 2);
  CHECK(pilot_factor(240.0, 2, 30.0) == 2);  // 240 s / 2^3 = 30 s
  CHECK(pilot_factor(241.0, 2, 30.0) == 3);
  CHECK(pilot_factor(480.0, 3, 30.0) == 2);  // 480 s / 2^4 in 3D
  CHECK(pilot_factor(481.0, 3, 30.0) == 3);
}

TEST_CASE("a step's cost is fitted as a cost a step and a cost a particle-step",
          "[cli][estimate]") {
  StepCostFit fit;
  for (const double particles : {10.0, 20.0, 40.0, 80.0})
    fit.add(particles, 0.5 + 0.01 * particles);
  CHECK(fit.per_step() == Approx(0.5));
  CHECK(fit.per_particle_step() == Approx(0.01));
  // One count only: the mean cost of a particle-step.
  StepCostFit flat;
  flat.add(100.0, 1.0);
  flat.add(100.0, 3.0);
  CHECK(flat.per_step() == 0.0);
  CHECK(flat.per_particle_step() == Approx(0.02));
  CHECK(StepCostFit{}.per_particle_step() == 0.0);
  // A line through noisy steps that would cost less than nothing a step: the mean instead,
  // so that the steps fitted cost what they took (3 s over 300 particle-steps).
  StepCostFit noisy;
  noisy.add(100.0, 0.2);
  noisy.add(200.0, 2.8);
  CHECK(noisy.per_step() == 0.0);
  CHECK(noisy.per_particle_step() == Approx(0.01));
}

namespace {

// One second a step, water from the fourth step on, waves at `wave_m_s`, an output time at 5.
struct FakeScene {
  double t = 0.0;
  double wave_m_s = 1.0;
  std::size_t fluid() const { return t >= 3.0 ? 10 : 0; }
  Stepper stepper(bool statistics = true) {
    Stepper s{[this] {
                const std::size_t stepped = fluid();
                t += 1.0;
                return stepped;
              },
              [this] { return fluid(); },
              [this] { return t; },
              {},
              {}};
    if (statistics) {
      s.fastest_wave_m_s = [this] { return wave_m_s; };
      s.on_output_time = [this] { return t == 5.0; };
    }
    return s;
  }
};

}  // namespace

TEST_CASE("the scene's window steps it from the start, its dry time untimed", "[cli][estimate]") {
  FakeScene scene;
  // On 4 m cells a run samples once a wave at 1 m/s could cross 2 m: every second step.
  const auto window = swemps::cli::step_window(10.0, scene.stepper(), 4.0, 60.0);
  CHECK(window.finished);
  CHECK(window.until_s == 10.0);
  CHECK(window.dry_time_s == 3.0);
  CHECK(window.steps == 7);
  CHECK(window.particle_steps == 70.0);
  CHECK(window.measured());
  // t = 0, half a sample in each of 10 steps, the output time.
  CHECK(window.statistics_samples == Approx(1.0 + 10 * 0.5 + 1.0));
  const auto e = swemps::cli::whole_window(window, 0.5, 2.0);
  CHECK(e.steps == 7.0);
  CHECK(e.stepping_s == window.seconds);
  CHECK(e.seconds == Approx(window.seconds + 7.0 * 0.5 + 2.0));
  // No budget: nothing beyond the dry steps, which never count against it... nor are taken.
  FakeScene again;
  const auto none = swemps::cli::step_window(10.0, again.stepper(), 4.0, 0.0);
  CHECK_FALSE(none.finished);
  CHECK(none.steps == 0);
  CHECK_FALSE(none.measured());
}

TEST_CASE("a pilot run counts the statistics samples a run would take", "[cli][estimate]") {
  FakeScene pilot;
  swemps::cli::PilotSetup setup;
  setup.factor = 2;
  setup.first_dt_s = 1.0;
  setup.scene_first_dt_s = 0.5;  // two of the scene's steps in each of the pilot's
  setup.end_time_s = 10.0;
  setup.map_length_m = 4.0;
  setup.window.until_s = 6.0;
  PilotRun run = swemps::cli::run_pilot(setup, pilot.stepper());
  CHECK(run.finished);
  CHECK(run.reached_s == 10.0);
  CHECK(run.dry_time_s == 3.0);
  CHECK(run.steps == 10);
  CHECK(run.particle_steps == 70.0);
  CHECK(run.setup.factor == 2);
  // The steps ending at t = 4, 5 and 6 lie in the window.
  CHECK(run.window_steps == 3);
  CHECK(run.window_particle_steps == 30.0);
  // t = 0, half a sample in each of 10 steps, the output time.
  CHECK(run.statistics_samples == Approx(1.0 + 10 * 0.5 + 1.0));

  // Waves so fast that a run samples every one of its steps: two in each of the pilot's.
  FakeScene fast;
  fast.wave_m_s = 100.0;
  run = swemps::cli::run_pilot(setup, fast.stepper());
  CHECK(run.statistics_samples == Approx(1.0 + 10 * 2.0 + 1.0));
  // Without a speed to sample by (no statistics in the model): none.
  FakeScene unsampled;
  CHECK(swemps::cli::run_pilot(setup, unsampled.stepper(false)).statistics_samples == 0.0);
}

TEST_CASE("a pilot's steps and particle-steps are scaled to the scene's spacing",
          "[cli][estimate]") {
  PilotRun pilot;
  pilot.setup.factor = 2;
  pilot.setup.first_dt_s = 0.2;
  pilot.setup.scene_first_dt_s = 0.1;  // half the pilot's
  pilot.setup.end_time_s = 100.0;
  pilot.steps = 100;
  pilot.particle_steps = 1000.0;
  pilot.seconds_per_step = 0.01;
  pilot.seconds_per_particle_step = 0.001;
  pilot.statistics_samples = 10.0;
  pilot.reached_s = 100.0;
  pilot.finished = true;
  // No window to measure by: the first stable steps, and 4 particles for each of the pilot's.
  auto e = swemps::cli::scale_pilot(pilot, 4.0, 0.5, 1.0);
  CHECK_FALSE(e.calibrated);
  CHECK(e.steps == Approx(200.0));
  CHECK(e.particle_steps == Approx(8000.0));
  CHECK(e.stepping_s == Approx(200 * 0.01 + 8000 * 0.001));
  CHECK(e.statistics_s == Approx(5.0));
  CHECK(e.seconds == Approx(10.0 + 5.0 + 1.0));
  CHECK_FALSE(e.extrapolated);

  // A window of 30 of the scene's steps over 10 of the pilot's, 300 particle-steps in 1.2 s,
  // where the pilot's line gives 30 x 0.01 + 300 x 0.001 = 0.6 s: 3 times its steps at twice
  // its cost.
  pilot.window_steps = 10;
  pilot.window_particle_steps = 25.0;
  pilot.setup.window.steps = 30;
  pilot.setup.window.particle_steps = 300.0;
  pilot.setup.window.seconds = 1.2;
  e = swemps::cli::scale_pilot(pilot, 4.0, 0.5, 1.0);
  CHECK(e.calibrated);
  CHECK(e.step_ratio == Approx(3.0));
  CHECK(e.cost_ratio == Approx(2.0));
  CHECK(e.steps == Approx(300.0));
  CHECK(e.particle_steps == Approx(12000.0));
  CHECK(e.stepping_s == Approx(2.0 * (300 * 0.01 + 12000 * 0.001)));
  // Too few of the pilot's steps in the window to measure by.
  pilot.window_steps = 9;
  CHECK_FALSE(swemps::cli::scale_pilot(pilot, 4.0, 0.5, 1.0).calibrated);

  // Without a first step to compare, the factor; stopped at t = 30 of 100, its first particle
  // at t = 10: carried on 90 / 20 times.
  pilot.setup.scene_first_dt_s = 0.0;
  pilot.finished = false;
  pilot.reached_s = 30.0;
  pilot.dry_time_s = 10.0;
  e = swemps::cli::scale_pilot(pilot, 4.0, 0.5, 0.0);
  CHECK(e.extrapolated);
  CHECK(e.steps == Approx(100 * 2 * 4.5));
  CHECK(e.particle_steps == Approx(1000 * 2 * 4 * 4.5));
  CHECK(e.statistics_samples == Approx(45.0));
}

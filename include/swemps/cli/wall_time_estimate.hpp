#pragma once
// How long a run of a scene will take, measured rather than guessed. The scene itself is
// stepped in memory for a few seconds (its window); if that reaches the end time, that is the
// run. Otherwise a pilot run, the scene with its particles `factor` times further apart,
// stepped in memory to its end time, shows how the time step and the particle count develop
// (a flood that speeds up shortens the step; inflows and splitting add particles), and the
// window, over the same stretch of simulated time, shows how the scene differs from its pilot:
// its steps, its particles and its cost per step. `swe-mps check` reports the result.

#include <cstddef>
#include <functional>

namespace swemps::cli {

// A simulation as the estimate steps it, whatever its model.
struct Stepper {
  std::function<std::size_t()> step;   // takes one step; returns the fluid particles stepped
  std::function<std::size_t()> fluid;  // fluid particles now
  std::function<double()> time_s;      // simulated time now
  // The fastest |u| + sqrt(g h) of any particle, which sets when a run samples its flood
  // statistics; empty for a model that keeps none.
  std::function<double()> fastest_wave_m_s;
  // Whether the last step landed on an output time, where a run samples its statistics too.
  std::function<bool()> on_output_time;
};

// The scene's own steps from its start: the steps before its first particle (an inflow not
// yet running) cost next to nothing and are not timed.
struct SceneWindow {
  std::size_t steps = 0;  // timed
  double particle_steps = 0.0;
  double seconds = 0.0;
  double dry_time_s = 0.0;          // the simulated time before the first particle
  double until_s = 0.0;             // the simulated time the window reached
  bool finished = false;            // it reached the end time
  double statistics_samples = 0.0;  // as run_pilot counts them
  bool measured() const { return particle_steps > 0.0 && seconds > 0.0; }
  double rate() const { return particle_steps / seconds; }  // particle-steps per second
};

// Steps the scene from its start for `budget_s` of wall time or to the end time, whichever
// comes first; the time before its first particle does not count. Its statistics samples are
// counted as run_pilot counts them, by `map_length_m`.
SceneWindow step_window(double end_time_s, const Stepper& scene, double map_length_m,
                        double budget_s);

// The pilot's spacing factor: 2, unless a run estimated from the scene's window at
// `window_estimate_s` (its rate, the first stable step's steps) would take a pilot at twice
// the spacing beyond `budget_s` (1/2^(dimensions + 1) of the time: 2^dimensions fewer
// particles, half the steps); then 3, which covers more of a long run's time in the budget
// but scales back less well (scale_pilot).
int pilot_factor(double window_estimate_s, int dimensions, double budget_s);

// The least-squares line seconds = per_step + per_particle_step x particles through the steps
// added; where that line cannot be drawn with both costs >= 0 (one particle count only, or a
// negative cost either way), nothing a step and the mean cost of a particle-step.
class StepCostFit {
 public:
  void add(double particles, double seconds);
  double per_step() const;
  double per_particle_step() const;

 private:
  bool separable() const;

  double n_ = 0.0, x_ = 0.0, y_ = 0.0, xx_ = 0.0, xy_ = 0.0;
};

// What a pilot run is of the scene it stands for.
struct PilotSetup {
  int factor = 2;                 // the pilot's spacing over the scene's
  double first_dt_s = 0.0;        // the pilot's first stable step
  double scene_first_dt_s = 0.0;  // the scene's
  double end_time_s = 0.0;
  // The length the scene's maps resolve (CellAverages::resolved_length_m at the scene's
  // spacing), by which a run samples its flood statistics; 0 for a model without them.
  double map_length_m = 0.0;
  double budget_s = 30.0;  // the pilot stops after this much wall time
  // The scene's window, whose stretch of simulated time the pilot measures apart.
  SceneWindow window;
  // The scene's steps in one of the pilot's as the first stable steps give it, about the
  // factor; the factor itself where either is unknown.
  double scene_steps_per_step() const;
};

struct PilotRun {
  PilotSetup setup;
  std::size_t steps = 0;
  double particle_steps = 0.0;
  double seconds = 0.0;     // stepping, all steps
  double dry_time_s = 0.0;  // the simulated time before its first particle
  double reached_s = 0.0;   // the simulated time it reached
  bool finished = false;    // reached the end time within the budget
  // Its steps and particle-steps up to the end of the scene's window.
  std::size_t window_steps = 0;
  double window_particle_steps = 0.0;
  // The samples of the flood statistics a run of the scene would take over the same time.
  double statistics_samples = 0.0;
  // A step's wall time against its particles, the least-squares line through every step:
  // seconds a step whatever its particles (sorting, search cells, the time step's reduction)
  // and seconds a particle-step.
  double seconds_per_step = 0.0;
  double seconds_per_particle_step = 0.0;
};

// Steps `pilot`, a fresh simulation of the scene coarsened by setup.factor, to the end time or
// until the budget has passed. The flood statistics' samples are counted as a run of the
// scene takes them (swe_run.cpp): one at t = 0 and at each output time, and in each of the
// pilot's steps as many as the scene's steps in it or, fewer, as often as a wave at the
// fastest speed could cross half the map length; with no fastest_wave_m_s, none.
PilotRun run_pilot(const PilotSetup& setup, const Stepper& pilot);

struct WallTimeEstimate {
  double seconds = 0.0;  // stepping, statistics and reading the scene
  double steps = 0.0;
  double particle_steps = 0.0;
  double stepping_s = 0.0;
  double statistics_samples = 0.0;
  double statistics_s = 0.0;
  bool extrapolated = false;  // the pilot stopped short of the end time
  bool calibrated = false;    // the window gave the ratios (else the first steps and factor)
  // The scene against its pilot: steps for each of the pilot's, particles a step, and the
  // cost of its steps against what the pilot's fitted line gives for them.
  double step_ratio = 0.0, particle_ratio = 0.0, cost_ratio = 0.0;
};

// The scene's run from its pilot: its steps times r_s, the scene's steps for each of the
// pilot's; its particle-steps also times `particle_ratio`, the scene's particles for each of
// the pilot's (at the start; factor^dimensions for a scene that starts dry, inflows making
// particles of the spacing's area); at c times the pilot's fitted cost. Over the window's
// stretch of simulated time, r_s is measured (the scene's steps over the pilot's) and c is
// the scene's time over what the pilot's fitted line gives for the scene's own steps and
// particle-steps there; with fewer than 10 of the pilot's steps in the window, r_s is the
// ratio of the first stable steps and c is 1. Where the particles a step differ from scene to
// pilot by more than the start's ratio (splitting at another pace) the estimate errs by as
// much; the window's own ratio of particles, tried, erred more (it holds the start of a
// cascade only). Measured on the valley flood (one thread): at twice the spacing the pilot's
// steps and particle-steps scale back to within 10 % of the run's, at 3 times to 1.2 and 1.5
// times them (the coarser particles split more as they spread into films), and a particle-step
// costs 4.5-5 us at 2 and 3 times the spacing as in the run, 6.1 us at 4 times and 8.8 us at
// 5 (a coarser particle covers more bed nodes). Plus the statistics samples at
// `seconds_per_sample` and the `reading_s` the scene took to build. A pilot that stopped short is carried to the end time in proportion to
// the simulated time it covered after its first particle came.
WallTimeEstimate scale_pilot(const PilotRun& pilot, double particle_ratio,
                             double seconds_per_sample, double reading_s);

// The scene's run when its window reached the end time: the window itself, plus the
// statistics and reading.
WallTimeEstimate whole_window(const SceneWindow& window, double seconds_per_sample,
                              double reading_s);

// The band the shipped scenes' runs fell in around the estimate, measured on one thread
// (docs/outputs.md, "Check": 0.56 to 1.54 times it, the nineteen scenes from 0.2 s to 15 min):
// a run takes between kLow and kHigh times it, and up to kFixedS more where the run is short
// enough for starting, reading and writing its file to count (Ritter's 0.23 s run, 0.12 s of
// stepping and statistics).
struct EstimateBand {
  static constexpr double kLow = 0.5;
  static constexpr double kHigh = 1.7;
  static constexpr double kFixedS = 0.5;
};

}  // namespace swemps::cli

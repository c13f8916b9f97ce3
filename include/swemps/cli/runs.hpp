#pragma once
// One run of a scene from its built simulation to its written files, with progress and a
// closing summary: shallow water (swe::Simulation) or Navier-Stokes (ns::Simulation).
// `swe-mps run` makes one for the scene's model; `swe-mps compare` makes one of each and
// follows their fronts.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "swemps/cli/output.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/simulation.hpp"

namespace swemps::cli {

struct RunReport {
  std::size_t steps = 0;
  std::size_t fluid_particles = 0;  // at the start
  // Shallow water: fluid particles at the end, the sum over steps of the particles stepped,
  // and the volume balance's relative change (the run summary's).
  std::size_t final_fluid_particles = 0, particle_steps = 0;
  double relative_volume_change = 0.0;
  // Navier-Stokes: the tank's wall and dummy particles. Shallow water has none: its walls are
  // mirrored ghosts made anew each step.
  std::size_t wall_particles = 0, dummy_particles = 0;
  double wall_s = 0.0;  // the whole run: building, stepping and writing
  std::filesystem::path output;
  // Shallow water: where the time went, as the run's closing summary logs it (the step's
  // phases, each effect, and the output: maps, statistics, gauges and files).
  swe::PhaseTimes phases;
  std::vector<swe::EffectTime> effects;
  double output_s = 0.0;
};

// Told the front position x (m) at a simulated time t (s): after every step of a
// shallow-water run, at every series sample of a Navier-Stokes run; times increase.
using FrontObserver = std::function<void(double time_s, double front_m)>;

// The shallow-water front: the largest x of a fluid particle deeper than `wet_depth_m`; NaN
// when none is.
double swe_front(const particles::SweParticles& p, double wet_depth_m);

// Runs the scene as shallow water. Throws scenario::ScenarioError, swe::SimulationError,
// OutputError.
RunReport run_swe(const scenario::Scenario& scene, const RunContext& context,
                  const FrontObserver& front = {});

// Runs the scene as Navier-Stokes in its dimension: the netCDF maps (depth = the column
// depth, ns::column_depth) and <output stem>.series.csv beside them. Throws
// scenario::ScenarioError, ns::SimulationError, OutputError.
RunReport run_ns(const scenario::Scenario& scene, const RunContext& context,
                 const FrontObserver& front = {});

// The series table of a Navier-Stokes run: <output path without extension>.series.csv.
std::filesystem::path ns_series_path(const std::filesystem::path& output);

}  // namespace swemps::cli

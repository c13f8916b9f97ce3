// A shallow-water run: scene -> swe::Simulation -> netCDF maps, gauges and volume balance.

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "swemps/cli/progress.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/swe/simulation.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// When the next series sample is due: the first multiple of `interval_s` after `time_s`.
// Samples are taken at the end of the first step that reaches one, so that sampling never
// shortens a step: the run is the same whatever the series interval.
double next_sample_time(double time_s, double interval_s) {
  // A step ending a rounding error short of a multiple counts as reaching it.
  const double multiples = std::floor(time_s / interval_s * (1.0 + 1e-12) + 1e-12);
  return (multiples + 1.0) * interval_s;
}

// The file of a shallow-water run: maps at output times; gauges, the volume balance and the
// flood statistics at every sample. Timed, for the summary.
class SweOutput {
 public:
  SweOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain,
            const swe::RegularGrid& grid, const RunContext& context)
      : grid_(grid),
        gauges_(scene.output.gauges),
        write_particles_(scene.output.write_particles),
        file_(scene, terrain, grid, context, scene.output.write_particles, "", "") {}

  void write_maps(swe::Simulation& sim) {
    const auto start = Clock::now();
    const auto& f = fields(sim);
    file_.write_maps(sim.time(), {f.depth, f.u, f.v},
                     write_particles_ ? &sim.particles() : nullptr);
    seconds_ += seconds_since(start);
  }

  // At most once a step.
  void sample(swe::Simulation& sim) {
    if (sampled_ && sampled_step_ == sim.steps()) return;
    const auto start = Clock::now();
    const auto& f = fields(sim);
    std::vector<io::GaugeSample> at_gauges;
    for (const auto& g : gauges_) {
      const auto p =
          swe::fields_at(sim.particles(), sim.kernel(), g.position_m[0], g.position_m[1]);
      const bool wet = p.depth_m > file_.wet_depth_m();
      at_gauges.push_back({p.depth_m, wet ? p.u_m_s : kNaN, wet ? p.v_m_s : kNaN});
    }
    const auto& ledger = sim.ledger();
    const io::BalanceSample balance{sim.fluid_volume(), ledger.added_m3, ledger.removed_m3,
                                    sim.relative_volume_change()};
    file_.sample(sim.time(), {f.depth, f.u, f.v}, at_gauges, balance);
    sampled_ = true;
    sampled_step_ = sim.steps();
    seconds_ += seconds_since(start);
  }

  void finish() { file_.finish(); }
  double seconds() const { return seconds_; }
  const std::filesystem::path& path() const { return file_.path(); }

 private:
  // The gridded fields of the current state, computed once per state (maps and sample share
  // them at an output time).
  const swe::GridFields& fields(swe::Simulation& sim) {
    sim.refresh();
    if (fields_step_ != sim.steps() || !has_fields_) {
      fields_ = swe::fields_on_grid(sim.particles(), sim.kernel(), grid_);
      fields_step_ = sim.steps();
      has_fields_ = true;
    }
    return fields_;
  }

  swe::RegularGrid grid_;
  std::vector<scenario::Gauge> gauges_;
  bool write_particles_;
  MapOutput file_;
  swe::GridFields fields_;
  std::size_t fields_step_ = 0, sampled_step_ = 0;
  bool has_fields_ = false, sampled_ = false;
  double seconds_ = 0.0;
};

void log_starting_volumes(const scenario::StartingVolumes& v) {
  if (!v.balance) {
    if (v.from_terrain)
      spdlog::info("water from terrain: geometric volume {:.6g} m3", v.geometric_m3);
    return;
  }
  const auto& b = *v.balance;
  const double ratio = b.volume_before_m3 > 0.0 ? b.volume_after_m3 / b.volume_before_m3 : kNaN;
  spdlog::info(
      "water from terrain: geometric volume {:.6g} m3, balanced particle volume {:.6g} m3 "
      "(ratio {:.6f})",
      b.volume_before_m3, b.volume_after_m3, ratio);
  if (b.max_depth_error_m > v.balance_tolerance_m) {
    spdlog::warn(
        "volume balancing stopped after {} iterations with a depth error of {:.3g} m (tolerance "
        "{:.3g} m): the water does not start quite at rest",
        b.iterations, b.max_depth_error_m, v.balance_tolerance_m);
  } else {
    spdlog::info("volume balancing: {} iterations, depth error {:.3g} m", b.iterations,
                 b.max_depth_error_m);
  }
  if (b.removed_particles > 0) {
    spdlog::warn(
        "volume balancing removed {} shore particles that no positive volume could balance",
        b.removed_particles);
  }
}

void log_summary(const swe::Simulation& sim, std::size_t initial_particles, double wall_s,
                 double output_s, const std::filesystem::path& path) {
  const auto& t = sim.phase_times();
  const double steps_per_s =
      wall_s > 0.0 ? static_cast<double>(sim.particle_steps()) / wall_s : 0.0;
  spdlog::info("done: {} steps to t = {:.6g} s, particles {} -> {}", sim.steps(), sim.time(),
               initial_particles, sim.particles().fluid_count());
  spdlog::info("wall time {:.3f} s, {:.4g} particle-steps/s ({} threads)", wall_s, steps_per_s,
               omp_get_max_threads());
  const auto& ledger = sim.ledger();
  spdlog::info(
      "volume: initial {:.12g} m3, in {:.6g} m3, out {:.6g} m3, now {:.12g} m3, relative change "
      "{:.3e}",
      ledger.initial_m3, ledger.added_m3, ledger.removed_m3, sim.fluid_volume(),
      sim.relative_volume_change());
  spdlog::info(
      "time per phase: sort {:.3f} s, neighbours {:.3f} s, depth {:.3f} s, gradient {:.3f} s, "
      "integrate {:.3f} s, walls {:.3f} s, output {:.3f} s",
      t.sort, t.neighbors, t.depth, t.gradient, t.integrate, t.walls, output_s);
  for (const auto& e : sim.effect_times()) {
    spdlog::info("effect '{}': {:.3f} s{}", e.name, e.seconds,
                 e.report.empty() ? "" : " (" + e.report + ")");
  }
  if (sim.wall_reflections() > 0) {
    spdlog::info("{} particle moves crossed a wall and were reflected back",
                 sim.wall_reflections());
  }
  spdlog::info("wrote {}", path.string());
}

}  // namespace

double swe_front(const particles::SweParticles& p, double wet_depth_m) {
  double front = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    if (p.depth[i] > wet_depth_m) front = std::max(front, p.x[i]);
  }
  return std::isfinite(front) ? front : kNaN;
}

RunReport run_swe(const scenario::Scenario& scene, const RunContext& context,
                  const FrontObserver& front) {
  const auto start = Clock::now();
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  const std::size_t initial_particles = sim.particles().fluid_count();
  spdlog::info("scene '{}': {} particles, end time {} s, {} walls, {} inflows, output {}",
               scene.name, initial_particles, scene.end_time_s, scene.walls.size(),
               scene.inflows.size(), scene.output.path.string());
  log_starting_volumes(built.volumes);

  const auto grid = scenario::output_grid(scene, built.terrain);
  SweOutput output(scene, built.terrain, grid, context);
  output.write_maps(sim);
  output.sample(sim);
  // The depths the front is read from are those the next step uses (refresh() is cached).
  const auto observe = [&] {
    if (!front) return;
    sim.refresh();
    front(sim.time(), swe_front(sim.particles(), scene.output.wet_depth_m));
  };
  observe();
  Progress progress(scene.end_time_s, context.progress);
  const double interval = scene.output.series_interval_s;
  double next_sample = next_sample_time(0.0, interval);
  const auto after_step = [&] {
    progress.update(sim.time(), sim.steps(), sim.particles().fluid_count());
    observe();
    if (sim.time() < next_sample * (1.0 - 1e-12)) return;
    output.sample(sim);
    next_sample = next_sample_time(sim.time(), interval);
  };
  for (const double target : scene.output.times_s) {
    sim.advance_to(target, after_step);
    output.write_maps(sim);
    output.sample(sim);
    spdlog::debug("wrote output at t = {} s", sim.time());
  }
  progress.finish();
  output.finish();
  const double wall_s = seconds_since(start);
  log_summary(sim, initial_particles, wall_s, output.seconds(), output.path());
  RunReport report;
  report.steps = sim.steps();
  report.fluid_particles = initial_particles;
  report.wall_s = wall_s;
  report.output = output.path();
  return report;
}

}  // namespace swemps::cli

#include "swemps/cli/run_command.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "swemps/cli/progress.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Runs a writer call, turning its failures into OutputError: I/O trouble (runtime_error) and
// what the writer refuses to write (invalid_argument), such as a CRS it cannot store.
template <class Call>
void writing(Call&& call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  } catch (const std::invalid_argument& e) {
    throw OutputError(e.what());
  }
}

// When the next series sample is due: the first multiple of `interval_s` after `time_s`.
// Samples are taken at the end of the first step that reaches one, so that sampling never
// shortens a step: the run is the same whatever the series interval.
double next_sample_time(double time_s, double interval_s) {
  // A step ending a rounding error short of a multiple counts as reaching it.
  const double multiples = std::floor(time_s / interval_s * (1.0 + 1e-12) + 1e-12);
  return (multiples + 1.0) * interval_s;
}

// Output writing, timed, with I/O failures turned into OutputError: maps at output times;
// gauges, the volume balance and the flood statistics at every sample.
class Output {
 public:
  Output(const scenario::Scenario& scene, const scenario::Terrain& terrain,
         const swe::RegularGrid& grid, const std::filesystem::path& scenario_file,
         const std::string& command_line)
      : grid_(grid),
        wet_depth_m_(scene.output.wet_depth_m),
        gauges_(scene.output.gauges),
        bed_m_(grid.nx * grid.ny, 0.0),
        statistics_(grid.nx * grid.ny, scene.output.wet_depth_m) {
    io::RunMetadata meta{
        scene.name,
        std::string("swe-mps ") + SWEMPS_VERSION + ", scenario " + scenario_file.string(),
        command_line, scene.numerics.gravity_m_s2};
    if (!scene.description.empty()) meta.title += ": " + scene.description;
    io::Layout layout{{grid.x0, grid.y0, grid.dx, grid.dy, grid.nx, grid.ny, terrain.crs_wkt},
                      scene.output.write_particles,
                      {}};
    for (const auto& g : gauges_)
      layout.gauges.push_back({g.name, g.position_m[0], g.position_m[1]});
    if (terrain.bed) {
      for (std::size_t k = 0; k < grid.ny; ++k) {
        for (std::size_t i = 0; i < grid.nx; ++i) {
          bed_m_[k * grid.nx + i] =
              terrain.bed->elevation(grid.x0 + static_cast<double>(i) * grid.dx,
                                     grid.y0 + static_cast<double>(k) * grid.dy);
        }
      }
    }
    writing([&] { writer_ = std::make_unique<io::NetcdfWriter>(scene.output.path, layout, meta); });
    // A scene without a bed stands on z = 0 everywhere: nothing worth a map.
    if (terrain.bed) writing([&] { writer_->write_bed(bed_m_); });
  }

  // The maps of the current state.
  void write_maps(swe::Simulation& sim) {
    const auto start = Clock::now();
    const auto& f = fields(sim);
    const std::size_t cells = f.depth.size();
    std::vector<double> surface(cells, kNaN), u(cells, kNaN), v(cells, kNaN);
    // Velocities and a water surface over a film thinner than the wet depth are noise.
    for (std::size_t c = 0; c < cells; ++c) {
      if (!(f.depth[c] > wet_depth_m_)) continue;
      surface[c] = f.depth[c] + bed_m_[c];
      u[c] = f.u[c];
      v[c] = f.v[c];
    }
    writing([&] { writer_->write(sim.time(), sim.particles(), {f.depth, surface, u, v}); });
    seconds_ += seconds_since(start);
  }

  // Gauges, volume balance and flood statistics at the current state; at most once a step.
  void sample(swe::Simulation& sim) {
    if (sampled_ && sampled_step_ == sim.steps()) return;
    const auto start = Clock::now();
    const auto& f = fields(sim);
    statistics_.update(sim.time(), f.depth, f.u, f.v);
    std::vector<io::GaugeSample> at_gauges;
    for (const auto& g : gauges_) {
      const auto p =
          swe::fields_at(sim.particles(), sim.kernel(), g.position_m[0], g.position_m[1]);
      const bool wet = p.depth_m > wet_depth_m_;
      at_gauges.push_back({p.depth_m, wet ? p.u_m_s : kNaN, wet ? p.v_m_s : kNaN});
    }
    const auto& ledger = sim.ledger();
    const io::BalanceSample balance{sim.fluid_volume(), ledger.added_m3, ledger.removed_m3,
                                    sim.relative_volume_change()};
    writing([&] { writer_->write_series(sim.time(), at_gauges, balance); });
    sampled_ = true;
    sampled_step_ = sim.steps();
    seconds_ += seconds_since(start);
  }

  void finish() {
    writing([&] {
      writer_->write_summary(statistics_);
      writer_->finish();
    });
  }

  double seconds() const { return seconds_; }
  const std::filesystem::path& path() const { return writer_->path(); }

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
  double wet_depth_m_;
  std::vector<scenario::Gauge> gauges_;
  std::vector<double> bed_m_;  // at cell centres; 0 without a bed
  maps::FloodStatistics statistics_;
  std::unique_ptr<io::NetcdfWriter> writer_;
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

void run(const Options& options, const std::string& command_line) {
  auto scene = scenario::load(options.scenario);
  if (options.output)
    scene.output.path = std::filesystem::absolute(*options.output).lexically_normal();
  if (options.threads > 0) omp_set_num_threads(options.threads);

  const auto start = Clock::now();
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  const std::size_t initial_particles = sim.particles().fluid_count();
  spdlog::info("scene '{}': {} particles, end time {} s, {} walls, {} inflows, output {}",
               scene.name, initial_particles, scene.end_time_s, scene.walls.size(),
               scene.inflows.size(), scene.output.path.string());
  log_starting_volumes(built.volumes);

  const auto grid = scenario::output_grid(scene, built.terrain);
  Output output(scene, built.terrain, grid, options.scenario, command_line);
  output.write_maps(sim);
  output.sample(sim);
  Progress progress(scene.end_time_s, options.verbosity != Verbosity::quiet);
  const double interval = scene.output.series_interval_s;
  double next_sample = next_sample_time(0.0, interval);
  const auto after_step = [&] {
    progress.update(sim.time(), sim.steps(), sim.particles().fluid_count());
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
  log_summary(sim, initial_particles, seconds_since(start), output.seconds(), output.path());
}

}  // namespace swemps::cli

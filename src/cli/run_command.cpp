#include "swemps/cli/run_command.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <limits>
#include <memory>
#include <vector>

#include "swemps/cli/progress.hpp"
#include "swemps/io/netcdf_writer.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

io::Grid to_io_grid(const swe::RegularGrid& g) { return {g.x0, g.y0, g.dx, g.dy, g.nx, g.ny, {}}; }

// Output writing, timed, with I/O failures turned into OutputError.
class Output {
 public:
  Output(const scenario::Scenario& scene, const std::filesystem::path& scenario_file,
         const std::string& command_line)
      : grid_(scenario::output_grid(scene)) {
    io::RunMetadata meta{
        scene.name,
        std::string("swe-mps ") + SWEMPS_VERSION + ", scenario " + scenario_file.string(),
        command_line, scene.numerics.gravity_m_s2};
    if (!scene.description.empty()) meta.title += ": " + scene.description;
    try {
      writer_ = std::make_unique<io::NetcdfWriter>(
          scene.output.path, io::Layout{to_io_grid(grid_), scene.output.write_particles, {}}, meta);
    } catch (const std::runtime_error& e) {
      throw OutputError(e.what());
    }
  }

  void write(swe::Simulation& sim) {
    const auto start = Clock::now();
    sim.refresh();
    const auto depth = swe::depth_on_grid(sim.particles(), sim.kernel(), grid_);
    try {
      // Surface elevation and velocity are not gridded yet: written as no data.
      const std::vector<double> no_data(depth.size(), std::numeric_limits<double>::quiet_NaN());
      writer_->write(sim.time(), sim.particles(), {depth, no_data, no_data, no_data});
    } catch (const std::runtime_error& e) {
      throw OutputError(e.what());
    }
    seconds_ += seconds_since(start);
  }

  void finish() {
    try {
      writer_->finish();
    } catch (const std::exception& e) {
      throw OutputError(e.what());
    }
  }

  double seconds() const { return seconds_; }
  const std::filesystem::path& path() const { return writer_->path(); }

 private:
  swe::RegularGrid grid_;
  std::unique_ptr<io::NetcdfWriter> writer_;
  double seconds_ = 0.0;
};

void log_summary(const swe::Simulation& sim, std::size_t initial_particles, double wall_s,
                 double output_s, const std::filesystem::path& path) {
  const auto& t = sim.phase_times();
  const double steps_per_s =
      wall_s > 0.0 ? static_cast<double>(sim.particle_steps()) / wall_s : 0.0;
  spdlog::info("done: {} steps to t = {:.6g} s, particles {} -> {}", sim.steps(), sim.time(),
               initial_particles, sim.particles().fluid_count());
  spdlog::info("wall time {:.3f} s, {:.4g} particle-steps/s ({} threads)", wall_s, steps_per_s,
               omp_get_max_threads());
  spdlog::info("volume: initial {:.12g} m3, removed {:.6g} m3, relative change {:.3e}",
               sim.ledger().initial_m3, sim.ledger().removed_m3, sim.relative_volume_change());
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
  auto sim = scenario::make_simulation(scene);
  const std::size_t initial_particles = sim.particles().fluid_count();
  spdlog::info("scene '{}': {} particles, end time {} s, {} walls, output {}", scene.name,
               initial_particles, scene.end_time_s, scene.walls.size(), scene.output.path.string());

  Output output(scene, options.scenario, command_line);
  output.write(sim);
  Progress progress(scene.end_time_s, options.verbosity != Verbosity::quiet);
  for (const double target : scene.output.times_s) {
    sim.advance_to(
        target, [&] { progress.update(sim.time(), sim.steps(), sim.particles().fluid_count()); });
    output.write(sim);
    spdlog::debug("wrote output at t = {} s", sim.time());
  }
  progress.finish();
  output.finish();
  log_summary(sim, initial_particles, seconds_since(start), output.seconds(), output.path());
}

}  // namespace swemps::cli

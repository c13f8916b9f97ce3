// Speed of the shallow-water step: particle-steps per second at 1e4, 1e5 and 1e6 particles
// on 1 and 2 threads, the time per phase, memory per particle, and what writing one map costs.
// Not a test: speed depends on the machine and its load, so it is measured here and written
// down in docs/performance.md.
//
// The scene: a dam break from a square reservoir (h0 = 1 m, lattice spacing 0.1 m) into a dry
// channel as wide and twice as long, slip walls and particle splitting (threshold 1.5): every
// part of the method a flood run uses on a flat bed. The default scheme, or the seed scheme
// with its eq 6 gradient (SWEMPS_BENCH_SCHEME=seed). The first refresh
// is not timed; then `steps` steps are, chosen so that each size does about 2e7
// particle-steps. Memory is the growth of the resident set while the simulation is alive,
// divided by the particles.
//
//   swemps-swe-speed [particles ...]        (default: 10000 100000 1000000)
//   SWEMPS_BENCH_THREADS="1 2" SWEMPS_BENCH_PARTICLE_STEPS=2e7 SWEMPS_BENCH_SCHEME=seed
//     swemps-swe-speed     (the environment variables on the same command line)

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_threads.hpp"
#include "swemps/cli/output.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Resident set size now, in bytes.
double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

// The reservoir holds side x side lattice points; the channel continues to x = 3 side.
std::string dam_break_scene(std::size_t particles, bool seed) {
  const double spacing = 0.1;
  const double side = std::round(std::sqrt(static_cast<double>(particles))) * spacing;
  std::ostringstream json;
  json << R"({ "name": "speed", "end_time": 1000.0,
    "numerics": )"
       << (seed ? R"({ "cfl": 0.5, "scheme": "seed", "alpha_e": 1.3, "gradient": "mps" })"
                : R"({ "cfl": 0.5 })")
       << R"(,
    "domain": { "x_min": 0, "x_max": )"
       << 3 * side << R"(, "y_min": 0, "y_max": )" << side << R"( },
    "water": [ { "rectangle": { "x_min": 0, "x_max": )"
       << side << R"(, "y_min": 0, "y_max": )" << side << R"( },
                 "depth": 1.0, "spacing": )"
       << spacing << R"( } ],
    "walls": [ { "polyline": [[)"
       << 3 * side << ", 0], [0, 0], [0, " << side << "], [" << 3 * side << ", " << side
       << R"(]], "condition": "slip" } ],
    "splitting": { "threshold": 1.5 },
    "output": { "path": "speed.nc", "interval": 1000.0, "grid": { "spacing": )"
       << spacing << R"( } } })";
  return json.str();
}

struct Measurement {
  std::size_t particles_start = 0, particles_end = 0, steps = 0, particle_steps = 0;
  double neighbours_per_particle = 0.0;  // at the end
  double wall_s = 0.0, bytes_per_particle = 0.0, grid_s = 0.0, write_s = 0.0;
  swemps::swe::PhaseTimes phases;
  double effects_s = 0.0, splitting_s = 0.0;
};

Measurement measure(std::size_t particles, int threads, double particle_steps_wanted, bool seed) {
  namespace fs = std::filesystem;
  using namespace swemps;
  omp_set_num_threads(threads);
  const fs::path folder = fs::temp_directory_path() / ("swemps-speed-" + std::to_string(getpid()));
  fs::create_directories(folder);
  auto scene = scenario::parse(dam_break_scene(particles, seed), folder);
  const double rss_before = resident_bytes();
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  sim.refresh();
  Measurement m;
  m.particles_start = sim.particles().fluid_count();
  const auto steps = static_cast<std::size_t>(
      std::max(10.0, std::round(particle_steps_wanted / static_cast<double>(m.particles_start))));

  const auto phases_before = sim.phase_times();
  const auto start = Clock::now();
  for (std::size_t k = 0; k < steps; ++k) sim.advance(sim.stable_time_step());
  sim.refresh();
  m.wall_s = seconds_since(start);
  m.bytes_per_particle = (resident_bytes() - rss_before) / static_cast<double>(m.particles_start);
  m.steps = steps;
  m.particle_steps = sim.particle_steps();
  m.particles_end = sim.particles().fluid_count();
  m.neighbours_per_particle =
      static_cast<double>(sim.neighbor_list().index.size()) / static_cast<double>(m.particles_end);
  const auto& p = sim.phase_times();
  // By name: a phase added to PhaseTimes must not shift the others' columns.
  m.phases.sort = p.sort - phases_before.sort;
  m.phases.neighbors = p.neighbors - phases_before.neighbors;
  m.phases.depth = p.depth - phases_before.depth;
  m.phases.gradient = p.gradient - phases_before.gradient;
  m.phases.shift = p.shift - phases_before.shift;
  m.phases.integrate = p.integrate - phases_before.integrate;
  m.phases.walls = p.walls - phases_before.walls;
  for (const auto& e : sim.effect_times()) {
    m.effects_s += e.seconds;
    if (e.name.find("split") != std::string::npos) m.splitting_s += e.seconds;
  }

  // One map written as a run writes it: gridded fields, then the netCDF file with particles.
  const auto grid = scenario::output_grid(scene, built.terrain);
  const auto grid_start = Clock::now();
  const auto fields = swe::fields_on_grid(sim.particles(), sim.kernel(), grid);
  m.grid_s = seconds_since(grid_start);
  const auto write_start = Clock::now();
  {
    scene.output.path = folder / "speed.nc";
    cli::MapOutput file(scene, built.terrain, grid, {"speed.json", "swemps-swe-speed", false}, true,
                        "", "");
    file.write_maps(sim.time(), {fields.depth, fields.u, fields.v}, &sim.particles());
    file.finish();
  }
  m.write_s = seconds_since(write_start);
  fs::remove_all(folder);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  for (int k = 1; k < argc; ++k) sizes.push_back(static_cast<std::size_t>(std::atof(argv[k])));
  if (sizes.empty()) sizes = {10'000, 100'000, 1'000'000};
  const char* wanted_env = std::getenv("SWEMPS_BENCH_PARTICLE_STEPS");
  const double wanted = wanted_env ? std::atof(wanted_env) : 2e7;
  const char* scheme_env = std::getenv("SWEMPS_BENCH_SCHEME");
  const bool seed = scheme_env != nullptr && std::string(scheme_env) == "seed";
  std::printf("scheme: %s\n\n", seed ? "seed (eq 6)" : "conservative");

  std::printf(
      "| particles | threads | steps | particles at end | neighbours per particle | wall (s) | "
      "particle-steps/s | per "
      "core | neighbours (s) | sums (s) | gradient (s) | shift (s) | sort (s) | walls (s) | "
      "integrate (s) | effects (s) | of which splitting (s) | bytes/particle | map gridding (s) | "
      "map write (s) "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::size_t n : sizes) {
    for (const int threads : swemps::bench::thread_counts({1, 2})) {
      const auto m = measure(n, threads, wanted, seed);
      const double rate = static_cast<double>(m.particle_steps) / m.wall_s;
      std::printf(
          "| %zu | %d | %zu | %zu | %.1f | %.2f | %.3g | %.3g | %.2f | %.2f | %.2f | %.2f | %.2f | "
          "%.2f | %.2f | %.2f | %.2f | %.0f | %.2f | %.2f |\n",
          m.particles_start, threads, m.steps, m.particles_end, m.neighbours_per_particle, m.wall_s,
          rate, rate / threads, m.phases.neighbors, m.phases.depth, m.phases.gradient,
          m.phases.shift, m.phases.sort, m.phases.walls, m.phases.integrate, m.effects_s,
          m.splitting_s, m.bytes_per_particle, m.grid_s, m.write_s);
      std::fflush(stdout);
    }
  }
}

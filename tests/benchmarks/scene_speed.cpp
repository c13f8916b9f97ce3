// Speed of whole shallow-water runs of real scenes: each scene run as `swe-mps run` runs it
// (building, stepping, maps, statistics, gauges, files), into a temporary folder, and where
// its time went. The lattice benchmark (swemps-swe-speed) measures the step on a flat bed; a
// flood on real terrain also pays for its bed term, its splitting and merging, its inflow and
// its few fast particles setting the step for all, which only a real scene shows.
// Not a test: speed depends on the machine and its load, so it is measured here and written
// down in docs/performance.md ("Whole runs of real scenes").
//
//   swemps-scene-speed [SCENE.json ...]   (default: the shipped valley flood)
//   SWEMPS_BENCH_THREADS="1 2" swemps-scene-speed ...   (default: one thread)
//
// One table row per scene and thread count: wall time, steps, particles at the start and the
// end, particle-steps and their rate, then seconds per phase of the step, the bed term, the
// other effects and the output.

#include <omp.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_threads.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

namespace fs = std::filesystem;

// The balanced or point bed term: the effect a real-terrain step spends most on.
bool is_bed_term(const std::string& effect_name) { return effect_name.rfind("bed slope", 0) == 0; }

void print_row(const std::string& scene, int threads, const swemps::cli::RunReport& r) {
  double bed_s = 0.0, other_effects_s = 0.0;
  for (const auto& e : r.effects) (is_bed_term(e.name) ? bed_s : other_effects_s) += e.seconds;
  const auto& t = r.phases;
  const double rate = static_cast<double>(r.particle_steps) / r.wall_s;
  std::printf(
      "| %s | %d | %.3g | %zu | %zu -> %zu | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | "
      "%.3g | %.3g | %.3g | %.3g |\n",
      scene.c_str(), threads, r.wall_s, r.steps, r.fluid_particles, r.final_fluid_particles,
      static_cast<double>(r.particle_steps), rate, rate / threads, t.neighbors, t.depth, t.gradient,
      t.shift, t.sort + t.integrate + t.walls + t.snapshots, bed_s, other_effects_s, r.output_s);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<fs::path> scenes;
  for (int k = 1; k < argc; ++k) scenes.emplace_back(argv[k]);
  if (scenes.empty()) {
    scenes.emplace_back(fs::path(SWEMPS_SOURCE_DIR) / "cases" / "valley-flood" / "scenario.json");
  }
  spdlog::set_level(spdlog::level::warn);
  std::printf(
      "| scene | threads | wall (s) | steps | particles | particle-steps | particle-steps/s | "
      "per core | neighbours (s) | depth sums (s) | gradient and force (s) | shift (s) | "
      "sort, integrate, walls, snapshots (s) | bed term (s) | other effects (s) | output (s) "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const fs::path folder =
      fs::temp_directory_path() / ("swemps-scene-speed-" + std::to_string(getpid()));
  int status = 0;
  for (const auto& file : scenes) {
    for (const int threads : swemps::bench::thread_counts({1})) {
      try {
        auto scene = swemps::scenario::load(file);
        if (scene.model != swemps::scenario::Model::swe) {
          std::fprintf(stderr, "%s: not a shallow-water scene, skipped\n", file.c_str());
          break;
        }
        fs::create_directories(folder);
        scene.output.path = folder / scene.output.path.filename();
        omp_set_num_threads(threads);
        const swemps::cli::RunContext context{file, "swemps-scene-speed", false};
        print_row(scene.name, threads, swemps::cli::run_swe(scene, context));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", file.c_str(), e.what());
        status = 1;
      }
      fs::remove_all(folder);
    }
  }
  return status;
}

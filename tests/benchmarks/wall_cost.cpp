// What buildings cost a step: a town of N buildings as walls (docs/buildings.md, "Cost").
// Not a test: speed depends on the machine and its load, so it is measured here and written
// down in docs/buildings.md.
//
// The town: N rectangular houses of 6-10 m a side, each turned by up to 30 degrees, on a
// square 14 m pitch, jittered by up to a metre (a fixed seed: the same town every run), on a
// flat bed raster; water filled to 0.3 m and moving at (0.3, 0.1) m/s fills the streets and
// yards on a 2 m lattice, with splitting and merging on. The same scene without the buildings
// is the baseline, and the houses raised 10 m into the bed the other way to have them: the
// step with walls holds fewer particles (the houses' area is dry) and ghosts along every
// wall, so the table gives the time per particle-step beside the time per step. The first
// refresh is not timed; then `steps` steps are.
//
//   swemps-wall-cost [N ...]            (default: 100 1000 10000)
//   SWEMPS_BENCH_THREADS="1 2" SWEMPS_BENCH_STEPS=10 swemps-wall-cost

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_threads.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kPitch = 14.0;  // m between house centres

std::size_t side_count(std::size_t buildings) {
  return static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(buildings))));
}

// The town's houses as a GeoJSON file in the scene's local metres.
void write_town(const fs::path& file, std::size_t buildings) {
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> size(6.0, 10.0), turn(0.0, std::numbers::pi / 6.0),
      jitter(-1.0, 1.0);
  const std::size_t side = side_count(buildings);
  std::ofstream out(file);
  out << R"({"type":"FeatureCollection","features":[)";
  for (std::size_t k = 0; k < buildings; ++k) {
    const double cx = kPitch * (static_cast<double>(k % side) + 1.0) + jitter(random);
    const double cy = kPitch * (static_cast<double>(k / side) + 1.0) + jitter(random);
    const double a = 0.5 * size(random), b = 0.5 * size(random), t = turn(random);
    const double c = std::cos(t), s = std::sin(t);
    out << (k ? "," : "") << R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon",)"
        << R"("coordinates":[[)";
    const double corners[5][2] = {{-a, -b}, {a, -b}, {a, b}, {-a, b}, {-a, -b}};
    for (int v = 0; v < 5; ++v) {
      out << (v ? "," : "") << "[" << cx + c * corners[v][0] - s * corners[v][1] << ","
          << cy + s * corners[v][0] + c * corners[v][1] << "]";
    }
    out << "]]}}";
  }
  out << "]}";
}

enum class Town { none, walls, bed };

// A flat bed raster at z = 0 over the town, 1 m cells, for the buildings raised into the bed.
void write_flat_bed(const fs::path& file, std::size_t buildings) {
  const auto cells =
      static_cast<std::size_t>(kPitch * (static_cast<double>(side_count(buildings)) + 1.0));
  swemps::terrain::GridGeometry g;
  g.columns = g.rows = cells;
  g.x_left = 0.0;
  g.y_top = static_cast<double>(cells);
  g.cell_width = g.cell_height = 1.0;
  swemps::io::write_geotiff(
      swemps::terrain::GriddedField(g, std::vector<double>(cells * cells, 0.0)), file);
}

std::string town_scene(std::size_t buildings, Town town) {
  const double extent = kPitch * (static_cast<double>(side_count(buildings)) + 1.0);
  std::ostringstream json;
  json << R"({ "name": "town", "end_time": 1000.0,
    "domain": { "x_min": 0, "x_max": )"
       << extent << R"(, "y_min": 0, "y_max": )" << extent << R"( },
    "water": [ { "fill": { "rectangle": { "x_min": 0, "x_max": )"
       << extent << R"(, "y_min": 0, "y_max": )" << extent << R"( } },
                 "surface_elevation": 0.3, "spacing": 2.0, "velocity": [0.3, 0.1] } ],
    "bed": { "raster": "flat.tif" },
    "friction": { "manning_n": 0.03 },
    "splitting": {}, "merging": {},)";
  if (town == Town::walls) json << R"( "buildings": { "file": "town.geojson", "crs": "scene" },)";
  if (town == Town::bed) {
    json << R"( "buildings": { "file": "town.geojson", "crs": "scene", "as": "bed" },)";
  }
  json << R"( "output": { "path": "town.nc", "interval": 1000.0 } })";
  return json.str();
}

struct Measurement {
  std::size_t particles = 0, segments = 0, steps = 0, ghosts = 0;
  double wall_s = 0.0, walls_s = 0.0, effects_s = 0.0;
};

Measurement measure(std::size_t buildings, Town town, int threads, std::size_t steps,
                    const fs::path& folder) {
  using namespace swemps;
  omp_set_num_threads(threads);
  auto scene = scenario::parse(town_scene(buildings, town), folder);
  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  sim.refresh();
  Measurement m;
  m.particles = sim.particles().fluid_count();
  m.segments = built.terrain.building_walls.size();
  m.steps = steps;
  const double walls_before = sim.phase_times().walls;
  double effects_before = 0.0;
  for (const auto& e : sim.effect_times()) effects_before += e.seconds;
  const auto start = Clock::now();
  for (std::size_t k = 0; k < steps; ++k) sim.advance(sim.stable_time_step());
  sim.refresh();
  m.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  m.ghosts = sim.particles().ghost_count();
  m.walls_s = sim.phase_times().walls - walls_before;
  for (const auto& e : sim.effect_times()) m.effects_s += e.seconds;
  m.effects_s -= effects_before;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> counts;
  for (int k = 1; k < argc; ++k) counts.push_back(std::strtoull(argv[k], nullptr, 10));
  if (counts.empty()) counts = {100, 1000, 10000};
  const char* steps_text = std::getenv("SWEMPS_BENCH_STEPS");
  const std::size_t steps = steps_text ? std::strtoull(steps_text, nullptr, 10) : 10;
  const fs::path folder =
      fs::temp_directory_path() / ("swemps-wall-cost-" + std::to_string(getpid()));
  fs::create_directories(folder);
  std::printf(
      "| buildings as | buildings | wall segments | threads | particles | ghosts per particle | "
      "s per step | "
      "us per particle-step | walls phase (s per step) | effects (s per step) | "
      "particle-step cost vs no buildings |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::size_t n : counts) {
    write_town(folder / "town.geojson", n);
    write_flat_bed(folder / "flat.tif", n);
    for (const int threads : swemps::bench::thread_counts({1})) {
      const Measurement base = measure(n, Town::none, threads, steps, folder);
      const Measurement walls = measure(n, Town::walls, threads, steps, folder);
      const Measurement bed = measure(n, Town::bed, threads, steps, folder);
      const auto per_particle_step = [](const Measurement& m) {
        return 1e6 * m.wall_s / static_cast<double>(m.steps * m.particles);
      };
      for (const auto* m : {&base, &walls, &bed}) {
        const double s = static_cast<double>(m->steps);
        std::printf("| %s | %zu | %zu | %d | %zu | %.2f | %.3g | %.3g | %.3g | %.3g | %+.1f %% |\n",
                    m == &base    ? "none"
                    : m == &walls ? "walls"
                                  : "raised into the bed",
                    m == &base ? 0 : n, m->segments, threads, m->particles,
                    static_cast<double>(m->ghosts) / static_cast<double>(m->particles),
                    m->wall_s / s,
                    per_particle_step(*m), m->walls_s / s, m->effects_s / s,
                    100.0 * (per_particle_step(*m) / per_particle_step(base) - 1.0));
        std::fflush(stdout);
      }
    }
  }
  fs::remove_all(folder);
  return 0;
}

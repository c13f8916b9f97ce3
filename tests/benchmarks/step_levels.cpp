// What individual time steps could save on a scene, measured before building them (issue "Real
// terrain at grid-model speed", item 3). Each scene is stepped as it runs now, every particle
// on the one global step, the smallest of eq 13 over all particles. At each step every particle
// is also given the level it would take under hierarchical block steps: its own step of eq 13
// (particle_time_step) rounded down to dt_min 2^k, k = 0 the finest, with the neighbour limiter
// (a particle's step at most twice any neighbour's, k_i <= k_j + 1, iterated to a fixed point).
// A particle updated once per own step costs dt / (dt_min 2^k_i) of an update over a global
// step dt; the sum over particles and steps, against the particle-steps taken, is the share of
// the updates block steps would leave. It counts updates only: not the drift of the particles
// between their updates, nor the neighbour searches of the finer levels, nor the
// synchronisation at output times; read it as the most block steps could save.
// Where an effect (an inflow line's step limit) sets a step below the fluid's, every particle
// takes that step (no saving).
// Not a test: docs/performance.md ("Individual time steps: what they could save") has the table.
//
//   swemps-step-levels SCENE.json [SCENE.json ...]   (one thread; no files written)

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <vector>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/operators.hpp"

namespace {

namespace fs = std::filesystem;

constexpr int kLevels = 11;  // k = 0 .. 10: steps of dt_min up to 1024 dt_min
constexpr int kCappedLevels = 4;

struct Tally {
  std::size_t steps = 0, effect_limited_steps = 0;
  double particle_steps = 0.0;
  double limited = 0.0, limited_capped = 0.0, unlimited = 0.0;  // updates under block steps
  std::array<double, kLevels> at_level{};                       // particle-steps per level
};

// k_i: the largest k with dt_min 2^k <= dt_i (at most kLevels - 1).
int level_of(double dt_i, double dt_min) {
  int k = 0;
  while (k + 1 < kLevels && dt_min * std::ldexp(1.0, k + 1) <= dt_i) ++k;
  return k;
}

// The neighbour limiter: k_i <= k_j + 1 over fluid neighbours, swept forward and backward
// until nothing changes.
void limit_by_neighbours(const swemps::neighbors::NeighborList& nl, std::size_t n,
                         std::vector<int>& level) {
  for (bool changed = true; changed;) {
    changed = false;
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t s = 0; s < n; ++s) {
        const std::size_t i = pass == 0 ? s : n - 1 - s;
        int k = level[i];
        for (const std::uint32_t j : nl.row(i)) {
          if (j < n) k = std::min(k, level[j] + 1);
        }
        if (k != level[i]) {
          level[i] = k;
          changed = true;
        }
      }
    }
  }
}

void record_step(swemps::swe::Simulation& sim, double dt, Tally& t) {
  const auto& p = sim.particles();
  const std::size_t n = p.fluid_count();
  if (n == 0) return;
  const auto& s = sim.settings();
  std::vector<double> own(n);
  for (std::size_t i = 0; i < n; ++i)
    own[i] = swemps::swe::particle_time_step(p, i, s.gravity_m_s2, s.cfl);
  const double dt_min = *std::min_element(own.begin(), own.end());
  ++t.steps;
  t.particle_steps += static_cast<double>(n);
  if (dt < dt_min * (1.0 - 1e-12) && dt == sim.stable_time_step()) {
    // An effect's limit below the fluid's (not an output time cutting the step short).
    ++t.effect_limited_steps;
    t.limited += static_cast<double>(n);
    t.limited_capped += static_cast<double>(n);
    t.unlimited += static_cast<double>(n);
    t.at_level[0] += static_cast<double>(n);
    return;
  }
  std::vector<int> level(n);
  for (std::size_t i = 0; i < n; ++i) level[i] = level_of(own[i], dt_min);
  for (std::size_t i = 0; i < n; ++i) t.unlimited += dt / (dt_min * std::ldexp(1.0, level[i]));
  limit_by_neighbours(sim.neighbor_list(), n, level);
  for (std::size_t i = 0; i < n; ++i) {
    t.limited += dt / (dt_min * std::ldexp(1.0, level[i]));
    t.limited_capped += dt / (dt_min * std::ldexp(1.0, std::min(level[i], kCappedLevels - 1)));
    t.at_level[static_cast<std::size_t>(level[i])] += 1.0;
  }
}

void measure(const fs::path& scene_path) {
  auto scene = swemps::scenario::load(scene_path);
  auto sim = swemps::scenario::make_simulation(scene);
  Tally t;
  while (sim.time() < scene.end_time_s) {
    const double dt = std::min(sim.stable_time_step(), scene.end_time_s - sim.time());
    record_step(sim, dt, t);
    sim.advance(dt);
  }
  const double steps = t.particle_steps;
  std::printf("| %s | %zu | %.3g | %.3f | %.3f | %.3f | %zu |", scene.name.c_str(), t.steps, steps,
              t.limited / steps, t.limited_capped / steps, t.unlimited / steps,
              t.effect_limited_steps);
  for (int k = 0; k < 4; ++k)
    std::printf(" %.2f /", t.at_level[static_cast<std::size_t>(k)] / steps);
  double rest = 0.0;
  for (int k = 4; k < kLevels; ++k) rest += t.at_level[static_cast<std::size_t>(k)];
  std::printf(" %.3f |\n", rest / steps);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: swemps-step-levels SCENE.json [SCENE.json ...]\n");
    return 2;
  }
  omp_set_num_threads(1);
  spdlog::set_level(spdlog::level::warn);
  std::printf(
      "| scene | steps | particle-steps | block steps, limited | limited, %d levels | without the "
      "limiter | steps an effect limits | share at k = 0 / 1 / 2 / 3 / 4 and more |\n"
      "|---|---|---|---|---|---|---|---|\n",
      kCappedLevels);
  for (int k = 1; k < argc; ++k) {
    try {
      measure(argv[k]);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", argv[k], e.what());
      return 1;
    }
  }
  return 0;
}

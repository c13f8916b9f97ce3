// Water at rest in a tank, run for a long time: how far the floor pressure strays from the
// hydrostatic pressure at every sample, and how fast the fastest particle gets
// (docs/ns-dam-break.md, "Water at rest"). Prints numbers, asserts nothing.
//
//   swemps-ns-rest [dimension 2|3] [end_time_s] [spacing_m] [key=value ...]
//
// Keys change the defaults (ns_options.hpp: source, gamma, gradient, boundary, repulsion,
// asymmetry, kernel, support, beta, courant, tolerance, preconditioner, collision), and
// trace=on prints one line per sample.
//
// The tank is 0.4 m long (3D: 0.2 m wide) with 0.2 m of water; floor probes a quarter, half
// and three quarters of the way along, on the wall particles' row half a spacing below the
// floor. The reference is rho g H: the pressure there when p = 0 holds on the top particle
// row, half a spacing below the water's edge, as the free-surface condition puts it.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ns_options.hpp"
#include "swemps/ns/measures.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"

namespace {

using namespace swemps;

bool trace = false;  // trace=on: one line per sample

// The shared keys (ns_options.hpp) and trace=on.
bool apply_option(const std::string& argument, ns::Settings& s, int dimensions) {
  if (argument == "trace=on" || argument == "trace=off") {
    trace = argument == "trace=on";
    return true;
  }
  return benchmarks::apply_ns_option(argument, s, dimensions);
}

template <int Dim>
int run(double end_time, double l0, const std::vector<std::string>& options) {
  const double length = 0.4, width = 0.2, depth = 0.2, g = 9.81, rho = 1000.0;
  ns::TankSpec<Dim> tank;
  tank.spacing_m = l0;
  tank.interior.upper[0] = length;
  if constexpr (Dim == 3) tank.interior.upper[1] = width;
  tank.interior.upper[Dim - 1] = 0.3;
  ns::Box<Dim> water = tank.interior;
  water.upper[Dim - 1] = depth;
  tank.water.push_back(water);

  ns::Settings s;
  s.spacing_m = l0;
  s.gravity_m_s2 = g;
  s.density_kg_m3 = rho;
  std::string label;
  for (const auto& option : options) {
    if (!apply_option(option, s, Dim)) {
      std::fprintf(stderr, "unknown option '%s'\n", option.c_str());
      return 2;
    }
    label += " " + option;
  }
  tank.solid_layers = static_cast<int>(std::ceil(s.pressure_kernel.support_spacings));
  std::array<double, Dim> lower{}, upper{};
  for (int d = 0; d < Dim; ++d) {
    lower[d] = -tank.solid_layers * l0;
    upper[d] = tank.interior.upper[d] + tank.solid_layers * l0;
  }
  ns::Simulation<Dim> sim(ns::fill_tank<Dim>(tank), s, lower, upper);

  std::vector<std::array<double, Dim>> probes;
  for (double f : {0.25, 0.5, 0.75}) {
    std::array<double, Dim> at{};
    at[0] = f * length;
    if constexpr (Dim == 3) at[1] = 0.5 * width;
    at[Dim - 1] = -0.5 * l0;
    probes.push_back(at);
  }
  const double reference = rho * g * depth;
  const double wave_speed = std::sqrt(g * depth);
  const double interval = 0.01;
  double worst = 0.0, worst_at = 0.0, fastest = 0.0, fastest_at = 0.0;
  double sum = 0.0;
  long samples = 0, within = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 1; k * interval <= end_time + 1e-12; ++k) {
    sim.advance_to(k * interval);
    const auto& p = sim.particles();
    for (const auto& at : probes) {
      const double pressure = ns::pressure_at<Dim>(p, sim.pressure_kernel(), at);
      const double error = std::abs(pressure / reference - 1.0);
      sum += pressure / reference;
      ++samples;
      within += error <= 0.02;
      if (error > worst) {
        worst = error;
        worst_at = sim.time();
      }
    }
    double s2 = 0.0;
    std::size_t which = 0;
    for (std::size_t i = 0; i < p.fluid; ++i) {
      double v2 = 0.0;
      for (int d = 0; d < Dim; ++d) v2 += p.velocity[d][i] * p.velocity[d][i];
      if (v2 > s2) which = i;
      s2 = std::max(s2, v2);
    }
    if (trace) {
      std::printf("t %.2f fastest %.3e at (%.4f, %.4f) p %.1f; compression left %.1e; gauges",
                  sim.time(), std::sqrt(s2), p.position[0][which], p.position[Dim - 1][which],
                  p.pressure[which], sim.last_step().poisson.compression_left);
      for (const auto& at : probes) {
        std::printf(" %.4f", ns::pressure_at<Dim>(p, sim.pressure_kernel(), at) / reference);
      }
      std::printf("\n");
    }
    if (std::sqrt(s2) > fastest) {
      fastest = std::sqrt(s2);
      fastest_at = sim.time();
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "%dD l0 %g%s: %zu fluid, %zu steps, %.1f s wall; floor p / rho g H: "
      "mean %.4f, worst |error| %.4f at t = %.2f s, %.1f %% of samples within 2 %%; fastest "
      "particle %.2e m/s = %.4f sqrt(gH) at t = %.2f s; lost %zu\n",
      Dim, l0, label.c_str(), sim.particles().fluid, sim.steps(), wall,
      sum / static_cast<double>(samples), worst, worst_at,
      100.0 * static_cast<double>(within) / static_cast<double>(samples), fastest,
      fastest / wave_speed, fastest_at, sim.totals().lost_particles);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const int dim = argc > 1 ? std::atoi(argv[1]) : 2;
  const double end_time = argc > 2 ? std::atof(argv[2]) : 10.0;
  const double l0 = argc > 3 ? std::atof(argv[3]) : (dim == 2 ? 0.01 : 0.02);
  const std::vector<std::string> options(argv + std::min(argc, 4), argv + argc);
  return dim == 3 ? run<3>(end_time, l0, options) : run<2>(end_time, l0, options);
}

// Speed of the Navier-Stokes mode on the 2D dam break used to compare particle codes: a
// water column 1.2 m long and 0.6 m high at the left end of a tank 3.216 m long, at
// l0 = 6 mm (20,000 fluid particles). Prints wall and CPU time per simulated second, steps,
// Poisson iterations per step and the time per phase. Not a test: speed depends on the
// machine and its load, so it is measured here and written down in docs/performance.md.
//
//   swemps-ns-speed [end_time_s=1.0] [key=value ...]
//
// with the keys of ns_options.hpp (tolerance=1e-6, courant=0.2, preconditioner=ic|diagonal,
// and the scheme: kernel, support, source, gradient, boundary, asymmetry, ...).

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "ns_options.hpp"
#include "swemps/ns/measures.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"

int main(int argc, char** argv) {
  using namespace swemps::ns;
  const double end_time = argc > 1 ? std::atof(argv[1]) : 1.0;
  Settings s;
  s.spacing_m = 0.006;
  for (int a = 2; a < argc; ++a) {
    if (!swemps::benchmarks::apply_ns_option(argv[a], s, 2)) {
      std::fprintf(stderr, "swemps-ns-speed: unknown option '%s' (key=value, see ns_options.hpp)\n",
                   argv[a]);
      return 2;
    }
  }

  TankSpec<2> tank;
  tank.interior.upper = {3.216, 1.2};
  tank.water.push_back({{0.0, 0.0}, {1.2, 0.6}});
  tank.spacing_m = s.spacing_m;
  tank.solid_layers = static_cast<int>(std::ceil(s.pressure_kernel.support_spacings));
  const double solid = tank.solid_layers * s.spacing_m;
  Simulation<2> sim(fill_tank<2>(tank), s, {-solid, -solid}, {3.216 + solid, 1.2 + solid});
  const auto& p = sim.particles();
  std::printf(
      "fluid %zu, wall %zu, dummy %zu; threads %d; tolerance %g, courant %g, %s operators, %s + "
      "%s\n",
      p.fluid, p.wall, p.dummy, omp_get_max_threads(), s.solver.relative_tolerance, s.courant,
      s.operators == Operators::least_squares ? "least-squares" : "MPS",
      s.operators == Operators::least_squares ? "BiCGSTAB" : "CG",
      preconditioner_name(s.solver.preconditioner));

  const auto wall_start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  for (double t = 0.1; t <= end_time + 1e-9; t += 0.1) {
    sim.advance_to(t);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    std::printf(
        "t %.1f s: steps %zu, front %.3f m, Poisson iterations/step %.1f (max %d), "
        "compression left by the last solve %.1e, wall %.1f s\n",
        t, sim.steps(), front_position<2>(sim.particles(), s.spacing_m),
        double(sim.totals().poisson_iterations) / double(sim.steps()),
        sim.totals().max_poisson_iterations, sim.last_step().poisson.compression_left, wall);
    std::fflush(stdout);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const auto& t = sim.totals();
  std::printf("wall %.1f s, cpu %.1f s for %.2f simulated s: %.1f s wall per simulated s\n", wall,
              cpu, sim.time(), wall / sim.time());
  std::printf("steps %zu (%.2f ms per step), unconverged %zu, lost %zu\n", t.steps,
              1e3 * wall / t.steps, t.unconverged_solves, t.lost_particles);
  std::printf(
      "phases (s): sort %.2f, neighbours %.2f, explicit %.2f, density %.2f, assembly %.2f, "
      "solve %.2f, correction %.2f\n",
      t.phases.sort, t.phases.neighbors, t.phases.explicit_part, t.phases.density,
      t.phases.assembly, t.phases.solve, t.phases.correction);
}

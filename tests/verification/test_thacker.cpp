// Thacker's planar surface in a paraboloid (SWASHES 2D) as shipped in cases/thacker: the
// tilted surface goes round the bowl three times, wetting and drying its sides.
// verification/thacker.hpp has the exact solution; docs/verification.md the measured numbers.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/operators.hpp"
#include "swemps/verification/thacker.hpp"

using namespace swemps;

namespace {

struct ThackerErrors {
  double worst_l1 = 0.0, worst_centroid_m = 0.0, worst_velocity_m_s = 0.0;
  double volume_change = 0.0;
  std::size_t particles_at_start = 0, particles_at_end = 0;
};

// Runs the shipped scene, as loaded and then changed by `adjust`, through its three periods,
// comparing every quarter period with the exact solution.
template <class Adjust>
ThackerErrors run_thacker(Adjust&& adjust) {
  auto scene = scenario::load(std::string(SWEMPS_SOURCE_DIR) + "/cases/thacker/scenario.json");
  adjust(scene);
  const verification::ThackerProblem problem{};
  const double period = 2.0 * std::numbers::pi / verification::thacker_omega(problem);
  REQUIRE(scene.end_time_s == Approx(3.0 * period).epsilon(1e-9));
  auto sim = scenario::make_simulation(scene);
  ThackerErrors e;
  e.particles_at_start = sim.particles().fluid_count();
  // The maps' grid: 0.02 m cells over the 4 m x 4 m domain, half the particle spacing.
  const swe::RegularGrid grid{0.01, 0.01, 0.02, 0.02, 200, 200};
  for (int quarter = 1; quarter <= 12; ++quarter) {
    const double t = quarter * period / 4.0;
    sim.advance_to(t);
    sim.refresh();
    const auto& p = sim.particles();
    const auto fields = swe::fields_on_grid(p, sim.kernel(), grid);
    double difference = 0.0, exact_sum = 0.0;
    for (std::size_t cell = 0; cell < fields.depth.size(); ++cell) {
      const double x = grid.x0 + static_cast<double>(cell % grid.nx) * grid.dx;
      const double y = grid.y0 + static_cast<double>(cell / grid.nx) * grid.dy;
      const double exact = verification::thacker_depth(problem, x, y, t);
      difference += std::abs(fields.depth[cell] - exact);
      exact_sum += exact;
    }
    // The water's centre of mass and mean velocity from the particles' volumes.
    double volume = 0.0, mx = 0.0, my = 0.0, mu = 0.0, mv = 0.0;
    for (std::size_t i = 0; i < p.fluid_count(); ++i) {
      volume += p.volume[i];
      mx += p.volume[i] * p.x[i];
      my += p.volume[i] * p.y[i];
      mu += p.volume[i] * p.u[i];
      mv += p.volume[i] * p.v[i];
    }
    double cx = 0.0, cy = 0.0, u = 0.0, v = 0.0;
    verification::thacker_centroid(problem, t, cx, cy);
    verification::thacker_velocity(problem, t, u, v);
    const double l1 = difference / exact_sum;
    const double centroid = std::hypot(mx / volume - cx, my / volume - cy);
    const double velocity = std::hypot(mu / volume - u, mv / volume - v);
    INFO("t = " << t << " s: L1 " << l1 << ", centroid off by " << centroid
                << " m, mean velocity off by " << velocity << " m/s");
    e.worst_l1 = std::max(e.worst_l1, l1);
    e.worst_centroid_m = std::max(e.worst_centroid_m, centroid);
    e.worst_velocity_m_s = std::max(e.worst_velocity_m_s, velocity);
  }
  e.volume_change = sim.relative_volume_change();
  e.particles_at_end = sim.particles().fluid_count();
  return e;
}

}  // namespace

TEST_CASE("Thacker's planar surface keeps its shape for three periods", "[verification]") {
  // The default numerics: the balanced bed term.
  const auto e = run_thacker([](scenario::Scenario&) {});
  WARN("Thacker, 0.04 m, three periods, default numerics (balanced bed term): worst L1 of depth "
       << e.worst_l1 << " of the volume, centroid off by " << e.worst_centroid_m
       << " m, mean velocity off by " << e.worst_velocity_m_s << " m/s");
  CHECK(std::abs(e.volume_change) < 1e-12);
  // No water leaves the bowl: a thin particle that ran up the side comes back down.
  CHECK(e.particles_at_end == e.particles_at_start);
  // Measured 1.6 % at worst (2.1-2.3 % before the planes' arrangement error was taken out, here
  // and when the run stepped to the shipped scene's output times: the shoreline's particles are
  // sensitive to the step sequence and to round-off); 0.66 % at the start. The balanced term keeps
  // thin particles at the exact shoreline, and the maps' kernel sum reads each of them a support
  // wide (docs/method.md, "The balanced bed term"). 3 % leaves room for round-off and fails if the
  // surface loses its shape or the oscillation damps; the bar is 5 %, and the surface read
  // by differences with neighbours alone gave 6.9 %.
  CHECK(e.worst_l1 < 0.03);
  // The orbit's phase and amplitude: measured 4.1 mm off (6.8-7.4 mm before; the orbit's
  // radius is 0.5 m); 1.5 cm is 1.7 degrees of the orbit (the difference form: 3.8 cm).
  CHECK(e.worst_centroid_m < 0.015);
  // The uniform velocity, 0.70 m/s: measured 0.006 m/s off at worst (0.013 before); 0.02 m/s
  // is 3 %.
  CHECK(e.worst_velocity_m_s < 0.02);
}

TEST_CASE("Thacker's planar surface under the point bed term", "[verification]") {
  const auto e = run_thacker(
      [](scenario::Scenario& scene) { scene.numerics.bed_term = swe::BedTerm::point; });
  WARN("Thacker, point bed term: worst L1 of depth "
       << e.worst_l1 << ", centroid off by " << e.worst_centroid_m << " m, mean velocity off by "
       << e.worst_velocity_m_s << " m/s");
  CHECK(std::abs(e.volume_change) < 1e-12);
  // Measured 1.49 % at worst (2.25 periods in), 0.66 % at the start: the kernel sum's
  // smoothing of the shoreline over a support; 0.75 % at 0.02 m, so first order. 1.8 % leaves
  // room for round-off differences between machines and fails if the surface loses its shape
  // or the oscillation damps.
  CHECK(e.worst_l1 < 0.018);
  // Measured 5.6 mm off (0.6 degree of the 0.5 m orbit's phase). 1 cm, a quarter of the
  // spacing, fails on a lag of 1.1 degrees.
  CHECK(e.worst_centroid_m < 0.01);
  // Measured 0.012 m/s off at worst.
  CHECK(e.worst_velocity_m_s < 0.02);
}

// The Navier-Stokes mode end to end: the tank's particles, the lattice constants, water at
// rest, and short dam breaks in 2D and 3D that must stay stable and move as the experiment.

#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "swemps/ns/lattice.hpp"
#include "swemps/ns/measures.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"

namespace {

using namespace swemps::ns;

constexpr double gravity = 9.81;

template <int Dim>
double max_speed(const Particles<Dim>& p) {
  double s2 = 0.0;
  for (std::size_t i = 0; i < p.fluid; ++i) {
    double v2 = 0.0;
    for (int d = 0; d < Dim; ++d) v2 += p.velocity[d][i] * p.velocity[d][i];
    s2 = std::max(s2, v2);
  }
  return std::sqrt(s2);
}

template <int Dim>
bool all_finite(const Particles<Dim>& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!std::isfinite(p.pressure[i])) return false;
    for (int d = 0; d < Dim; ++d) {
      if (!std::isfinite(p.position[d][i]) || !std::isfinite(p.velocity[d][i])) return false;
    }
  }
  return true;
}

// A square column of side a = n l0 against the left wall of a tank 5a long and 2a high
// (3D: a wide, the column spanning the width), as in Martin & Moyce (1952).
template <int Dim>
Simulation<Dim> column_collapse(int n, double a, const Settings& base) {
  const double l0 = a / n;
  TankSpec<Dim> tank;
  tank.spacing_m = l0;
  tank.solid_layers = static_cast<int>(std::ceil(base.pressure_kernel.support_spacings));
  Box<Dim> water;
  for (int d = 0; d < Dim; ++d) {
    tank.interior.upper[d] = a;
    water.upper[d] = a;
  }
  tank.interior.upper[0] = 5.0 * a;
  tank.interior.upper[Dim - 1] = 2.0 * a;
  tank.water.push_back(water);
  Settings s = base;
  s.spacing_m = l0;
  std::array<double, Dim> lower{}, upper{};
  const double solid = tank.solid_layers * l0;
  for (int d = 0; d < Dim; ++d) {
    lower[d] = -solid;
    upper[d] = tank.interior.upper[d] + solid;
  }
  return Simulation<Dim>(fill_tank<Dim>(tank), s, lower, upper);
}

}  // namespace

TEST_CASE("tank: lattice fluid and the wall and dummy layers around an open box", "[ns]") {
  TankSpec<2> tank;
  tank.interior.upper = {0.10, 0.06};  // 10 x 6 cells of 1 cm
  tank.water.push_back({{0.0, 0.0}, {0.04, 0.03}});
  tank.spacing_m = 0.01;
  tank.solid_layers = 3;
  const auto p = fill_tank<2>(tank);
  CHECK(p.fluid == 12);
  // Layer k: two side columns from z = -k up to the top (6 + k nodes each) and the floor row
  // between them (10 + 2 (k - 1) nodes). Walls are layer 1, dummies layers 2 and 3.
  CHECK(p.wall == 2 * 7 + 10);
  CHECK(p.dummy == (2 * 8 + 12) + (2 * 9 + 14));
  // Fluid at cell centres: the first row is half a spacing above the floor.
  CHECK(p.position[1][0] == Approx(0.005));
  // The water volume is exact: 12 cells of l0^2 = 0.04 x 0.03.
  CHECK(p.fluid * 0.01 * 0.01 == Approx(0.04 * 0.03));
  CHECK(p.kind(11) == Kind::fluid);
  CHECK(p.kind(12) == Kind::wall);
  CHECK(p.kind(12 + 24) == Kind::dummy);

  TankSpec<2> bad = tank;
  bad.interior.upper[0] = 0.105;  // 10.5 spacings
  CHECK_THROWS_AS(fill_tank<2>(bad), std::invalid_argument);
  bad = tank;
  bad.water[0].upper[1] = 0.08;  // above the walls
  CHECK_THROWS_AS(fill_tank<2>(bad), std::invalid_argument);

  TankSpec<3> box;
  box.interior.upper = {0.04, 0.03, 0.05};
  box.water.push_back({{0.0, 0.0, 0.0}, {0.04, 0.03, 0.02}});
  box.spacing_m = 0.01;
  box.solid_layers = 1;
  const auto q = fill_tank<3>(box);
  CHECK(q.fluid == 4 * 3 * 2);
  // One layer: the floor with its rim (6 x 5) and four side walls 5 high.
  CHECK(q.wall == 6 * 5 + 5 * (2 * 6 + 2 * 3));
  CHECK(q.dummy == 0);
}

TEST_CASE("lattice constants of the standard kernel at 2.1 l0 in 2D", "[ns]") {
  const double l0 = 0.01;
  const auto kernel =
      swemps::kernels::make_kernel<2>({swemps::kernels::KernelType::standard}, 2.1 * l0);
  const auto c = lattice_constants<2>(kernel, l0);
  // Neighbours at l0, sqrt2 l0 and 2 l0, four of each.
  CHECK(c.neighbours == 12);
  const double n0 = 4 * (2.1 - 1) + 4 * (2.1 / std::sqrt(2.0) - 1) + 4 * (2.1 / 2 - 1);
  CHECK(c.number_density == Approx(n0).epsilon(1e-13));
  const double lambda = (4 * 1.1 + 4 * 2 * (2.1 / std::sqrt(2.0) - 1) + 4 * 4 * 0.05) / n0;
  CHECK(c.lambda_m2 == Approx(lambda * l0 * l0).epsilon(1e-13));
}

TEST_CASE("ns settings out of range are refused", "[ns]") {
  Settings s;
  s.spacing_m = 0.01;
  TankSpec<2> tank;
  tank.interior.upper = {0.1, 0.1};
  tank.water.push_back({{0.0, 0.0}, {0.05, 0.05}});
  tank.spacing_m = 0.01;
  const auto particles = fill_tank<2>(tank);
  auto build = [&](const Settings& settings) {
    Simulation<2> sim(particles, settings, {-0.03, -0.03}, {0.13, 1.0});
  };
  CHECK_NOTHROW(build(s));
  Settings bad = s;
  bad.courant = 0.0;
  CHECK_THROWS_AS(build(bad), std::invalid_argument);
  bad = s;
  bad.free_surface_beta = 1.2;
  CHECK_THROWS_AS(build(bad), std::invalid_argument);
  bad = s;
  bad.pressure_kernel.support_spacings = 0.9;
  CHECK_THROWS_AS(build(bad), std::invalid_argument);
  bad = s;
  bad.solver.relative_tolerance = 0.0;
  CHECK_THROWS_AS(build(bad), std::invalid_argument);
  // The least-squares operators fit over extrapolated wall pressures only.
  bad = scheme_settings(Scheme::least_squares, 2);
  bad.spacing_m = 0.01;
  CHECK_NOTHROW(build(bad));
  bad.boundary = BoundaryPressure::poisson;
  CHECK_THROWS_AS(build(bad), std::invalid_argument);
}

TEST_CASE("ns: water at rest in a tank holds hydrostatic pressure", "[ns]") {
  // 20 x 10 particles of 1 cm: H = 0.1 m.
  const double l0 = 0.01, depth = 0.1;
  TankSpec<2> tank;
  tank.interior.upper = {0.2, 0.2};
  tank.water.push_back({{0.0, 0.0}, {0.2, depth}});
  tank.spacing_m = l0;
  Settings s;
  s.spacing_m = l0;
  Simulation<2> sim(fill_tank<2>(tank), s, {-0.03, -0.03}, {0.23, 1.0});
  sim.advance_to(0.2);
  const auto& p = sim.particles();
  REQUIRE(all_finite(p));
  CHECK(sim.totals().lost_particles == 0);
  CHECK(sim.totals().unconverged_solves == 0);
  // Floor pressure under the middle of the tank against rho g H. Standard MPS pressure is
  // noisy step to step (docs/ns-dam-break.md); 10 % is about three times the scatter seen
  // over the first 0.2 s.
  const double floor = pressure_at<2>(p, sim.pressure_kernel(), {0.1, -0.5 * l0});
  CHECK(floor == Approx(1000.0 * gravity * depth).epsilon(0.10));
  // Spurious currents stay small over this time: under 5 % of the wave speed sqrt(g H).
  // (They grow later; docs/method.md, "Navier-Stokes mode: where it falls short".)
  CHECK(max_speed(p) < 0.05 * std::sqrt(gravity * depth));
}

namespace {

// Water H deep on a 1 cm lattice in a tank of the given interior, with every numerical
// choice of `scheme` at the default support and the given gradient weights, run to end_s;
// floor gauges every 0.01 s (a quarter, half and three quarters along the first axis,
// mid-width in 3D, on the wall row as the ns run's gauges). Returns the worst
// |p / rho g H - 1| over all samples and the fastest particle seen, over sqrt(g H).
template <int Dim>
std::pair<double, double> rest_in_tank(const std::array<double, Dim>& size, double depth,
                                       double end_s, Scheme scheme = Scheme::well_balanced,
                                       std::optional<GradientWeights> weights = std::nullopt) {
  const double l0 = 0.01;
  TankSpec<Dim> tank;
  tank.spacing_m = l0;
  tank.interior.upper = size;
  Box<Dim> water = tank.interior;
  water.upper[Dim - 1] = depth;
  tank.water.push_back(water);
  Settings s = scheme_settings(scheme, Dim);
  s.spacing_m = l0;
  if (weights) s.gradient_weights = *weights;
  std::array<double, Dim> lower{}, upper{};
  for (int d = 0; d < Dim; ++d) {
    lower[d] = -0.03;
    upper[d] = size[d] + 0.03;
  }
  Simulation<Dim> sim(fill_tank<Dim>(tank), s, lower, upper);
  double worst = 0.0, fastest = 0.0;
  for (int k = 1; k * 0.01 <= end_s + 1e-9; ++k) {
    sim.advance_to(0.01 * k);
    for (double f : {0.25, 0.5, 0.75}) {
      std::array<double, Dim> at{};
      at[0] = f * size[0];
      if constexpr (Dim == 3) at[1] = 0.5 * size[1];
      at[Dim - 1] = -0.5 * l0;
      const double floor = pressure_at<Dim>(sim.particles(), sim.pressure_kernel(), at);
      worst = std::max(worst, std::abs(floor / (1000.0 * gravity * depth) - 1.0));
    }
    fastest = std::max(fastest, max_speed(sim.particles()));
  }
  REQUIRE(all_finite(sim.particles()));
  CHECK(sim.totals().lost_particles == 0);
  return {worst, fastest / std::sqrt(gravity * depth)};
}

}  // namespace

// Issue 20's bar: every floor sample within 2 % of rho g H and the fastest particle under
// 1 % of sqrt(g H), with the scenes' default scheme at its default support. Measured: 1.27 %
// and 1e-4 over 10 s in 2D (the gauge's kernel average over the wall row and the first fluid row
// reads 0.9875 rho g H at l0/H = 0.05); the standard scheme's worst sample is 7.8 times
// rho g H off and its currents reach 0.65 sqrt(g H) in the same tank.
TEST_CASE("ns: water at rest stays at rest with the well-balanced scheme, 2D, 10 s",
          "[ns][physics]") {
  const auto [worst, fastest] = rest_in_tank<2>({0.4, 0.3}, 0.2, 10.0);
  CHECK(worst < 0.02);
  CHECK(fastest < 0.01);
}

// 10 x 10 x 20 particles: l0/H = 0.05 as in 2D, the default support, the scheme's 3D
// defaults: the gradient on the kernel's slope, the multigrid's setup kept over 20 solves. On
// the weights w / r^2 a mode grows in the interior from about a second and this test fails by
// 2 s (2.5 % and 0.028 sqrt(g H); docs/ns-dam-break.md "Gradient weights"). Measured: 1.19 %
// and 3e-5 sqrt(g H) (1.18 % with the setup kept over 5 solves). The whole 10 s is a long study (-DSWEMPS_LONG_TESTS=ON, a minute and a
// half): 1.24 % and 4e-5.
TEST_CASE("ns: water at rest stays at rest with the well-balanced scheme, 3D, 2 s",
          "[ns][physics]") {
  const auto [worst, fastest] = rest_in_tank<3>({0.1, 0.1, 0.3}, 0.2, 2.0);
  CHECK(worst < 0.02);
  CHECK(fastest < 0.01);
}

TEST_CASE("ns: water at rest stays at rest with the well-balanced scheme, 3D, 10 s",
          "[ns][physics][long]") {
  const auto [worst, fastest] = rest_in_tank<3>({0.1, 0.1, 0.3}, 0.2, 10.0);
  CHECK(worst < 0.02);
  CHECK(fastest < 0.01);
}

// The same bar with the least-squares scheme: measured 1.42 % and 9e-5 sqrt(g H) over
// 10 s. In 3D at 2.1 l0 they do not hold it: a mode grows on
// the surface from about 1.5 s (docs/ns-dam-break.md, "Least-squares operators").
TEST_CASE("ns: water at rest stays at rest with the least-squares operators, 2D, 10 s",
          "[ns][physics][least-squares]") {
  const auto [worst, fastest] =
      rest_in_tank<2>({0.4, 0.3}, 0.2, 10.0, Scheme::least_squares);
  CHECK(worst < 0.02);
  CHECK(fastest < 0.01);
}

TEST_CASE("ns: a 2D column collapse stays stable and its front follows the experiment", "[ns]") {
  const double a = 0.05715;  // Martin & Moyce's 2.25 in
  Settings s;
  auto sim = column_collapse<2>(20, a, s);
  const std::size_t fluid = sim.particles().fluid;
  const double time_scale = std::sqrt(2.0 * gravity / a);  // T = t sqrt(2 g / a)
  sim.advance_to(1.0 / time_scale);
  const auto& p = sim.particles();
  REQUIRE(all_finite(p));
  CHECK(p.fluid == fluid);
  CHECK(sim.totals().unconverged_solves == 0);
  CHECK(sim.steps() > 20);
  // Nothing moves faster than a fall from twice the column height.
  CHECK(max_speed(p) < std::sqrt(2.0 * gravity * 2.0 * a));
  // At T = 1 the experiment's front lies between its values at T = 0.85 and 1.42
  // (Z = 1.22 and 1.67, data/martin_moyce_1952_square_column.csv).
  const double z = front_position<2>(p, a / 20) / a;
  CHECK(z > 1.22);
  CHECK(z < 1.67);
}

TEST_CASE("ns: a column collapse on least-squares operators stays stable and moves", "[ns]") {
  const double a = 0.05715;
  const double time_scale = std::sqrt(2.0 * gravity / a);
  {
    auto sim = column_collapse<2>(20, a, scheme_settings(Scheme::least_squares, 2));
    const std::size_t fluid = sim.particles().fluid;
    sim.advance_to(1.0 / time_scale);
    REQUIRE(all_finite(sim.particles()));
    CHECK(sim.particles().fluid == fluid);
    CHECK(sim.totals().unconverged_solves == 0);
    CHECK(max_speed(sim.particles()) < std::sqrt(2.0 * gravity * 2.0 * a));
    const double z = front_position<2>(sim.particles(), a / 20) / a;
    CHECK(z > 1.22);  // the experiment's bracket at T = 1, as above
    CHECK(z < 1.67);
  }
  auto sim = column_collapse<3>(8, a, scheme_settings(Scheme::least_squares, 3));
  const std::size_t fluid = sim.particles().fluid;
  sim.advance_to(1.0 / time_scale);
  REQUIRE(all_finite(sim.particles()));
  CHECK(sim.particles().fluid == fluid);
  CHECK(max_speed(sim.particles()) < std::sqrt(2.0 * gravity * 2.0 * a));
  const double z = front_position<3>(sim.particles(), a / 8) / a;
  CHECK(z > 1.1);
  CHECK(z < 1.8);
}

TEST_CASE("ns: a 3D column collapse stays stable", "[ns]") {
  const double a = 0.05715;
  Settings s;
  auto sim = column_collapse<3>(8, a, s);
  const std::size_t fluid = sim.particles().fluid;
  CHECK(fluid == 8 * 8 * 8);
  const double time_scale = std::sqrt(2.0 * gravity / a);
  sim.advance_to(1.0 / time_scale);
  const auto& p = sim.particles();
  REQUIRE(all_finite(p));
  CHECK(p.fluid == fluid);
  CHECK(sim.totals().unconverged_solves == 0);
  CHECK(max_speed(p) < std::sqrt(2.0 * gravity * 2.0 * a));
  const double z = front_position<3>(p, a / 8) / a;
  CHECK(z > 1.1);  // it has moved: at 8 particles across, less precisely than in 2D
  CHECK(z < 1.8);
}

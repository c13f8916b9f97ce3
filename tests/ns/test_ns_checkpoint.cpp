// The Navier-Stokes state record: a simulation saved part way, restored into one built anew
// from the same scene and stepped on, ends bit for bit where one stepped straight through
// does; a record of another tank is refused.

#include <catch2/catch.hpp>
#include <cmath>

#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"
#include "swemps/swe/state_record.hpp"

namespace {

using namespace swemps;

// A column of water `cells` spacings square (3D: a cube) against the left wall of a tank
// three times as long and twice as high: it collapses, so every field changes each step.
template <int Dim>
ns::Simulation<Dim> collapsing_column(int cells, ns::SourceTerm source) {
  constexpr double spacing_m = 0.01;
  const double side_m = cells * spacing_m;
  ns::TankSpec<Dim> tank;
  tank.spacing_m = spacing_m;
  ns::Box<Dim> water;
  for (int d = 0; d < Dim; ++d) {
    tank.interior.upper[d] = side_m;
    water.upper[d] = side_m;
  }
  tank.interior.upper[0] = 3.0 * side_m;
  tank.interior.upper[Dim - 1] = 2.0 * side_m;
  tank.water.push_back(water);
  ns::Settings settings;
  settings.spacing_m = spacing_m;
  settings.source = source;
  // Sorts fall inside both halves of the run, and the save lands between two of them.
  settings.sort_interval = 7;
  std::array<double, Dim> lower{}, upper{};
  const double solid_m = tank.solid_layers * spacing_m;
  for (int d = 0; d < Dim; ++d) {
    lower[d] = -solid_m;
    upper[d] = tank.interior.upper[d] + solid_m;
  }
  return ns::Simulation<Dim>(ns::fill_tank<Dim>(tank), settings, lower, upper);
}

template <int Dim>
void require_same(const ns::Simulation<Dim>& a, const ns::Simulation<Dim>& b) {
  const auto& p = a.particles();
  const auto& q = b.particles();
  REQUIRE(p.fluid == q.fluid);
  REQUIRE(p.wall == q.wall);
  for (int d = 0; d < Dim; ++d) {
    CHECK(p.position[d] == q.position[d]);
    CHECK(p.velocity[d] == q.velocity[d]);
  }
  CHECK(p.pressure == q.pressure);
  CHECK(a.time() == b.time());
  CHECK(a.steps() == b.steps());
  CHECK(a.totals().poisson_iterations == b.totals().poisson_iterations);
  CHECK(a.totals().lost_particles == b.totals().lost_particles);
  CHECK(a.last_step().poisson.relative_residual == b.last_step().poisson.relative_residual);
  CHECK(a.stable_time_step() == b.stable_time_step());
}

template <int Dim>
void check_restart(int cells, ns::SourceTerm source, int steps, int saved_after) {
  auto straight = collapsing_column<Dim>(cells, source);
  auto first = collapsing_column<Dim>(cells, source);
  for (int k = 0; k < steps; ++k) straight.advance(straight.stable_time_step());
  for (int k = 0; k < saved_after; ++k) first.advance(first.stable_time_step());
  swe::StateWriter out;
  first.save_state(out);

  auto restored = collapsing_column<Dim>(cells, source);
  swe::StateReader in(out.bytes(), "the test record");
  restored.restore_state(in);
  in.expect_end();
  for (int k = saved_after; k < steps; ++k) restored.advance(restored.stable_time_step());
  // The particles did move: the comparison is not of two states at rest.
  CHECK(restored.particles().position[0] != first.particles().position[0]);
  require_same(straight, restored);
}

}  // namespace

TEST_CASE("ns state: a restored 2D simulation steps on bit for bit", "[ns][checkpoint]") {
  SECTION("number-density source") { check_restart<2>(8, ns::SourceTerm::number_density, 40, 17); }
  SECTION("mixed source") { check_restart<2>(8, ns::SourceTerm::mixed, 40, 17); }
}

TEST_CASE("ns state: a restored 3D simulation steps on bit for bit", "[ns][checkpoint]") {
  check_restart<3>(4, ns::SourceTerm::number_density, 16, 9);
}

TEST_CASE("ns state: a record of another tank or dimension is refused", "[ns][checkpoint]") {
  auto small = collapsing_column<2>(6, ns::SourceTerm::number_density);
  small.advance(small.stable_time_step());
  swe::StateWriter out;
  small.save_state(out);
  auto large = collapsing_column<2>(8, ns::SourceTerm::number_density);
  swe::StateReader in(out.bytes(), "the test record");
  CHECK_THROWS_WITH(large.restore_state(in), Catch::Contains("another scene"));
  // The refused record left the simulation as it was built.
  CHECK(large.steps() == 0);

  auto cube = collapsing_column<3>(4, ns::SourceTerm::number_density);
  swe::StateReader in3(out.bytes(), "the test record");
  CHECK_THROWS_AS(cube.restore_state(in3), swe::StateError);
}

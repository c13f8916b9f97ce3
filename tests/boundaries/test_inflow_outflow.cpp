// Tests of the discharge hydrograph, the inflow line and the outflow lines: exact volumes,
// where rows of new particles go, which particles leave, and the volume balance of a whole run.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "../support/effect_stepper.hpp"
#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/boundaries/inflow_line.hpp"
#include "swemps/boundaries/outflow_line.hpp"
#include "swemps/particles/seeding.hpp"
#include "swemps/swe/bed.hpp"
#include "swemps/swe/simulation.hpp"

using namespace swemps;
using boundaries::Hydrograph;
using boundaries::InflowLine;
using boundaries::InflowLineSettings;
using boundaries::OutflowLines;
using Vec = std::array<double, 2>;

namespace {

using Stepper = testing::EffectStepper;

// A line across x = 0 from y = 0 to y = 1, the water entering towards +x.
InflowLineSettings line_at_x0(double spacing, std::optional<double> depth) {
  InflowLineSettings s;
  s.from = {0.0, 0.0};
  s.to = {0.0, 1.0};
  s.direction = {1.0, 0.0};
  s.spacing_m = spacing;
  s.depth_m = depth;
  return s;
}

}  // namespace

TEST_CASE("hydrograph: linear between points, held beyond the ends", "[hydrograph]") {
  const Hydrograph h({{10.0, 1.0}, {20.0, 3.0}, {40.0, 3.0}, {50.0, 0.0}});
  CHECK(h.discharge(-100.0) == 1.0);
  CHECK(h.discharge(10.0) == 1.0);
  CHECK(h.discharge(15.0) == 2.0);
  CHECK(h.discharge(20.0) == 3.0);
  CHECK(h.discharge(30.0) == 3.0);
  CHECK(h.discharge(47.5) == 0.75);
  CHECK(h.discharge(50.0) == 0.0);
  CHECK(h.discharge(1e9) == 0.0);
}

TEST_CASE("hydrograph: volumes are the exact integrals of the piecewise-linear discharge",
          "[hydrograph]") {
  const Hydrograph h({{10.0, 1.0}, {20.0, 3.0}, {40.0, 3.0}, {50.0, 0.0}});
  // Pieces: 10 s at 1 before the start, 20 m3 on [10, 20], 60 on [20, 40], 15 on [40, 50].
  CHECK(h.volume(0.0, 10.0) == 10.0);
  CHECK(h.volume(10.0, 50.0) == 95.0);
  CHECK(h.volume(0.0, 60.0) == 105.0);  // 0 after the end
  CHECK(h.volume(15.0, 45.0) == Approx(12.5 + 60.0 + 11.25).epsilon(1e-15));
  CHECK(h.volume(12.0, 14.0) == Approx(2.0 * 1.6).epsilon(1e-15));  // inside one piece
  CHECK(h.volume(5.0, 5.0) == 0.0);
  CHECK(h.volume(45.0, 15.0) == -h.volume(15.0, 45.0));
  CHECK(h.volume(-5.0, 3.0) == 8.0);  // wholly before the first point
  CHECK(h.volume(55.0, 70.0) == 0.0);

  // Any subdivision adds up to the whole, to round-off.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> step(0.001, 0.7);
  double t = -3.0, sum = 0.0;
  while (t < 57.0) {
    const double next = std::min(57.0, t + step(random));
    sum += h.volume(t, next);
    t = next;
  }
  CHECK(sum == Approx(h.volume(-3.0, 57.0)).epsilon(1e-13));
  CHECK(h.volume(-3.0, 57.0) == Approx(13.0 + 95.0).epsilon(1e-15));

  const Hydrograph constant({{4.0, 2.5}});  // one point: a constant discharge
  CHECK(constant.discharge(-7.0) == 2.5);
  CHECK(constant.discharge(70.0) == 2.5);
  CHECK(constant.volume(-2.0, 8.0) == 25.0);
}

TEST_CASE("hydrograph: wrong points are refused, naming the point", "[hydrograph]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(Hydrograph({}), std::invalid_argument);
  CHECK_THROWS_WITH(Hydrograph({{0, 1}, {1, 2}, {1, 3}}),
                    Catch::Contains("point 3") && Catch::Contains("not after"));
  CHECK_THROWS_WITH(Hydrograph({{0, 1}, {2, 2}, {1, 3}}), Catch::Contains("point 3"));
  CHECK_THROWS_WITH(Hydrograph({{0, 1}, {1, -0.1}}),
                    Catch::Contains("point 2") && Catch::Contains("negative"));
  CHECK_THROWS_WITH(Hydrograph({{nan, 1}}), Catch::Contains("point 1"));
  CHECK_THROWS_WITH(Hydrograph({{0, 1}, {1, nan}}), Catch::Contains("point 2"));
  CHECK_THROWS_AS(Hydrograph({{0, std::numeric_limits<double>::infinity()}}),
                  std::invalid_argument);
}

TEST_CASE("inflow: rows at the slots, one spacing apart, with the nominal volume", "[inflow]") {
  // Binary-exact numbers: q = Q / L = 0.0625 m2/s at h_in = 0.0625 m gives u_in = 1 m/s, so a
  // step of 1/32 s advances the strip by a quarter spacing and every 4th step completes a row.
  const double l = 0.125, h_in = 0.0625, q = 0.0625, dt = 1.0 / 32.0;
  auto settings = line_at_x0(l, h_in);
  auto bed = std::make_shared<swe::PlaneBed>(2.0, Vec{0.1, -0.2}, Vec{0.0, 0.0});
  settings.bed = bed;
  InflowLine inflow(settings, Hydrograph({{0.0, q}}));
  REQUIRE(inflow.slot_count() == 8);
  CHECK(inflow.slot(0) == Vec{0.0, 0.0625});
  CHECK(inflow.slot(7) == Vec{0.0, 0.9375});

  Stepper s;
  for (int k = 0; k < 3; ++k) s.step(inflow, k * dt, dt);
  CHECK(s.particles.fluid_count() == 0);  // the strip has advanced only 3/4 of a spacing
  CHECK(inflow.pending_volume() == 3.0 * q * dt);
  CHECK(inflow.strip_advance() == 0.09375);
  s.step(inflow, 3 * dt, dt);
  REQUIRE(s.particles.fluid_count() == 8);
  const auto& p = s.particles;
  for (std::size_t i = 0; i < 8; ++i) {
    CHECK(p.x[i] == 0.5 * l);  // half a spacing inside the line
    CHECK(p.y[i] == inflow.slot(i)[1]);
    CHECK(p.u[i] == 1.0);
    CHECK(p.v[i] == 0.0);
    CHECK(p.depth[i] == h_in);
    CHECK(p.volume[i] == h_in * l * l);  // depth x the area it stands for
    CHECK(p.initial_area[i] == l * l);
    CHECK(p.bed[i] == Approx(bed->elevation(p.x[i], p.y[i])));
  }
  CHECK(inflow.pending_volume() == 0.0);
  CHECK(inflow.volume_added() == 4.0 * q * dt);
  CHECK(s.ledger.added_m3 == inflow.volume_added());

  for (int k = 4; k < 40; ++k) s.step(inflow, k * dt, dt);
  CHECK(inflow.rows_emitted() == 10);
  CHECK(inflow.particles_added() == 80);
  CHECK(s.particles.fluid_count() == 80);
  CHECK(s.ledger.added_m3 == Approx(q * 40 * dt).epsilon(1e-15));
  CHECK(s.particles.total_fluid_volume() == Approx(s.ledger.added_m3).epsilon(1e-15));
  CHECK_THAT(inflow.report(), Catch::Contains("10 rows, 80 particles"));
}

TEST_CASE("inflow: a long step emits several rows, stacked where they would have moved",
          "[inflow]") {
  // u_in = 1 m/s; a step of 3.25 spacings completes 3 rows, and the strip has moved a quarter
  // spacing beyond the newest one.
  const double l = 0.125, h_in = 0.0625, q = 0.0625, dt = 3.25 * l;
  InflowLine inflow(line_at_x0(l, h_in), Hydrograph({{0.0, q}}));
  Stepper s;
  s.step(inflow, 0.0, dt);
  REQUIRE(s.particles.fluid_count() == 3 * 8);
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t k = 0; k < 8; ++k) {
      const std::size_t i = 8 * r + k;
      CHECK(s.particles.x[i] == Approx(0.5 * l + 0.25 * l + r * l).epsilon(1e-15));
      CHECK(s.particles.volume[i] == Approx(h_in * l * l).epsilon(1e-14));
    }
  }
  CHECK(inflow.strip_advance() == Approx(0.25 * l).epsilon(1e-14));
  CHECK(inflow.pending_volume() == Approx(q * 0.25 * l).epsilon(1e-14));
  CHECK(inflow.volume_added() + inflow.pending_volume() == Approx(q * dt).epsilon(1e-15));
}

TEST_CASE("inflow: the default depth is critical", "[inflow]") {
  // L = 2 m, Q = 0.2 m3/s: q = 0.1 m2/s, h_c = (q^2 / g)^(1/3), u = q / h_c = sqrt(g h_c).
  InflowLineSettings settings;
  settings.from = {1.0, 0.0};
  settings.to = {1.0, 2.0};
  settings.direction = {-3.0, 0.0};  // any length: normalised
  settings.spacing_m = 0.1;
  InflowLine inflow(settings, Hydrograph({{0.0, 0.2}}));
  Stepper s;
  s.settings.gravity_m_s2 = 9.81;
  s.step(inflow, 0.0, 1.0);
  const double h_c = std::cbrt(0.01 / 9.81);
  CHECK(boundaries::critical_depth_m(0.1, 9.81) == Approx(h_c).epsilon(1e-15));
  REQUIRE(s.particles.fluid_count() > 0);
  REQUIRE(s.particles.fluid_count() % 20 == 0);
  for (std::size_t i = 0; i < s.particles.fluid_count(); ++i) {
    CHECK(s.particles.depth[i] == Approx(h_c).epsilon(1e-14));
    CHECK(s.particles.u[i] == Approx(-std::sqrt(9.81 * h_c)).epsilon(1e-14));  // Froude 1
    CHECK(-s.particles.u[i] * s.particles.depth[i] == Approx(0.1).epsilon(1e-14));
    CHECK(s.particles.x[i] < 1.0);  // entering towards -x
    CHECK(s.particles.volume[i] == Approx(h_c * 0.1 * 0.1).epsilon(1e-12));
  }
}

TEST_CASE("inflow: zero discharge lets nothing in", "[inflow]") {
  for (const auto depth : {std::optional<double>{}, std::optional<double>{0.1}}) {
    InflowLine inflow(line_at_x0(0.1, depth), Hydrograph({{0.0, 0.0}}));
    Stepper s;
    for (int k = 0; k < 100; ++k) s.step(inflow, 0.01 * k, 0.01);
    CHECK(s.particles.fluid_count() == 0);
    CHECK(inflow.pending_volume() == 0.0);
    CHECK(inflow.volume_added() == 0.0);
    CHECK(inflow.strip_advance() == 0.0);
    CHECK(s.ledger.added_m3 == 0.0);
  }
}

TEST_CASE("inflow: created volume is the integral of Q over many uneven steps", "[inflow]") {
  // A triangular flood (0 -> 0.3 -> 0 m3/s over 90 s) through a slanted line, critical
  // depth, steps drawn at random: after every step the ledger, the particles and the effect
  // agree, and added + pending is the hydrograph's volume so far.
  const Hydrograph flood({{0.0, 0.0}, {30.0, 0.3}, {90.0, 0.0}});
  InflowLineSettings settings;
  settings.from = {2.0, 1.0};
  settings.to = {2.9, 2.2};  // L = 1.5 m
  settings.direction = {0.8, -0.6};
  settings.spacing_m = 0.1;
  InflowLine inflow(settings, flood);
  REQUIRE(inflow.slot_count() == 15);
  Stepper s;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> step(0.002, 0.06);
  double t = 0.0, worst = 0.0;
  while (t < 95.0) {
    const double dt = step(random);
    s.step(inflow, t, dt);
    t += dt;
    const double expected = flood.volume(0.0, t);
    if (expected > 0.0) {
      worst = std::max(
          worst, std::abs(inflow.volume_added() + inflow.pending_volume() - expected) / expected);
    }
    REQUIRE(s.ledger.added_m3 == inflow.volume_added());
  }
  CHECK(worst < 1e-12);
  CHECK(flood.volume(0.0, t) == Approx(13.5).epsilon(1e-15));
  CHECK(s.particles.total_fluid_volume() == Approx(inflow.volume_added()).epsilon(1e-12));
  CHECK(s.particles.fluid_count() == 15 * inflow.rows_emitted());
  // What is left pending when the flood has passed is less than one row's water.
  CHECK(inflow.pending_volume() < 0.01 * 15 * 0.1 * 0.1);
  // Every particle entered beside the line, on its inner side, within reach of a step.
  const auto& p = s.particles;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double inside = (p.x[i] - 2.0) * 0.8 + (p.y[i] - 1.0) * -0.6;
    CHECK(inside >= 0.05 - 1e-12);
    CHECK(inside < 0.15 + 1e-12);
    CHECK(p.u[i] * 0.6 + p.v[i] * 0.8 == Approx(0.0).margin(1e-14));  // normal to the line
  }
}

TEST_CASE("inflow: settings are validated", "[inflow]") {
  const Hydrograph q({{0.0, 1.0}});
  auto bad = line_at_x0(0.1, {});
  bad.direction = {1.0, 0.01};
  CHECK_THROWS_WITH(InflowLine(bad, q), Catch::Contains("not normal"));
  bad = line_at_x0(0.1, {});
  bad.direction = {0.0, 0.0};
  CHECK_THROWS_AS(InflowLine(bad, q), std::invalid_argument);
  bad = line_at_x0(0.0, {});
  CHECK_THROWS_WITH(InflowLine(bad, q), Catch::Contains("spacing"));
  bad = line_at_x0(0.1, -0.2);
  CHECK_THROWS_WITH(InflowLine(bad, q), Catch::Contains("depth"));
  bad = line_at_x0(0.1, {});
  bad.to = bad.from;
  CHECK_THROWS_WITH(InflowLine(bad, q), Catch::Contains("length"));
  // A line shorter than the spacing still has one slot, at its middle.
  auto short_line = line_at_x0(5.0, {});
  CHECK(InflowLine(short_line, q).slot_count() == 1);
  CHECK(InflowLine(short_line, q).slot(0) == Vec{0.0, 0.5});
}

TEST_CASE("outflow: the segment test", "[outflow]") {
  const Vec a{1.0, -1.0}, b{1.0, 1.0};
  CHECK(OutflowLines::touches(a, b, {0.5, 0.0}, {1.5, 0.0}));          // crossing
  CHECK(OutflowLines::touches(a, b, {1.5, 0.3}, {0.5, 0.1}));          // crossing back
  CHECK(OutflowLines::touches(a, b, {0.5, 0.0}, {1.0, 0.5}));          // ending on it
  CHECK(OutflowLines::touches(a, b, {1.0, 0.5}, {0.5, 0.0}));          // starting on it
  CHECK(OutflowLines::touches(a, b, {0.0, 2.0}, {2.0, 0.0}));          // through its end point
  CHECK(OutflowLines::touches(a, b, {1.0, -2.0}, {1.0, -0.5}));        // sliding onto it
  CHECK(OutflowLines::touches(a, b, {1.0, 0.25}, {1.0, 0.25}));        // resting on it
  CHECK_FALSE(OutflowLines::touches(a, b, {0.5, -2.0}, {0.5, 2.0}));   // parallel, beside it
  CHECK_FALSE(OutflowLines::touches(a, b, {0.5, 0.0}, {0.999, 0.0}));  // short of it
  CHECK_FALSE(OutflowLines::touches(a, b, {0.5, 1.5}, {1.5, 1.5}));    // past its end
  CHECK_FALSE(OutflowLines::touches(a, b, {1.0, 1.5}, {1.0, 3.0}));    // on its line, beyond
}

TEST_CASE("outflow: exactly the particles whose path touches a line leave", "[outflow]") {
  // A straight line x = 1 (-1 <= y <= 1) and a roof-shaped polyline with its vertex at (4, 1).
  OutflowLines outflow({{{1.0, -1.0}, {1.0, 1.0}}, {{3.0, 0.0}, {4.0, 1.0}, {5.0, 0.0}}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Path {
    Vec before, after;
    bool leaves;
  };
  const std::vector<Path> paths{
      {{0.5, 0.0}, {1.5, 0.0}, true},    // crosses
      {{1.5, 0.5}, {0.5, 0.5}, true},    // crosses the other way
      {{0.9, 0.2}, {0.9, 0.8}, false},   // moves parallel beside it
      {{0.5, -0.3}, {1.0, -0.3}, true},  // ends exactly on it
      {{0.5, 0.7}, {0.99, 0.7}, false},  // stops short
      {{0.5, 1.5}, {1.5, 1.5}, false},   // passes beyond its end
      {{4.0, 2.0}, {4.0, 0.5}, true},    // through the polyline's vertex
      {{3.2, 0.8}, {3.9, 0.8}, true},    // into the roof through its first segment
      {{3.9, 0.5}, {4.1, 0.5}, false},   // inside the roof, touching neither segment
      {{nan, 0.0}, {1.5, 0.0}, false},   // broken: left for the finiteness check
  };
  Stepper s;
  std::vector<double> before_x, before_y;
  double leaving_m3 = 0.0;
  std::size_t leaving = 0;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const double volume = std::ldexp(1.0, -static_cast<int>(k));  // distinct: 1, 1/2, 1/4 ...
    // The bed field carries the case number through the removal.
    s.particles.add_fluid(paths[k].after[0], paths[k].after[1], 0, 0, volume, 0.1, 0.01,
                          static_cast<double>(k));
    before_x.push_back(paths[k].before[0]);
    before_y.push_back(paths[k].before[1]);
    if (paths[k].leaves) {
      leaving_m3 += volume;
      ++leaving;
    }
  }
  s.ledger.removed_m3 = 0.5;  // booked earlier by something else: added to, not replaced
  s.step(outflow, 0.0, 0.1, before_x, before_y);
  CHECK(outflow.removed_particles() == leaving);
  CHECK(outflow.volume_removed() == leaving_m3);
  CHECK(s.ledger.removed_m3 == 0.5 + leaving_m3);
  std::vector<double> kept;
  for (std::size_t i = 0; i < s.particles.fluid_count(); ++i) kept.push_back(s.particles.bed[i]);
  CHECK(kept == std::vector<double>{2, 4, 5, 8, 9});

  // A particle moving in small steps leaves in the step whose path crosses the line, though
  // neither end of that path is on it.
  Stepper t;
  t.particles.add_fluid(0.9, 0.0, 3.0, 0.0, 0.25, 0.1, 0.01, 0.0);
  std::vector<double> x0{0.6}, y0{0.0};
  t.step(outflow, 0.0, 0.1, x0, y0);
  CHECK(t.particles.fluid_count() == 1);
  x0 = {0.9};
  t.particles.x[0] = 1.2;
  t.step(outflow, 0.1, 0.1, x0, y0);
  CHECK(t.particles.fluid_count() == 0);
  CHECK(t.ledger.removed_m3 == 0.25);
  CHECK_THAT(outflow.report(), Catch::Contains(std::to_string(leaving + 1) + " particles"));
}

TEST_CASE("outflow: particles added this step are tested where they are", "[outflow]") {
  OutflowLines outflow({{{1.0, -1.0}, {1.0, 1.0}}});
  Stepper s;
  s.particles.add_fluid(0.5, 0.0, 0, 0, 1.0, 0.1, 0.01, 0.0);  // moved, stays
  s.particles.add_fluid(1.0, 0.5, 0, 0, 2.0, 0.1, 0.01, 1.0);  // added on the line: leaves
  s.particles.add_fluid(1.1, 0.5, 0, 0, 4.0, 0.1, 0.01, 2.0);  // added beside it: stays
  const std::vector<double> x0{0.4}, y0{0.0};
  s.step(outflow, 0.0, 0.1, x0, y0);
  CHECK(s.particles.fluid_count() == 2);
  CHECK(s.ledger.removed_m3 == 2.0);
  // More earlier positions than particles: something before this effect removed particles.
  const std::vector<double> x3{0, 0, 0}, y3{0, 0, 0};
  CHECK_THROWS_AS(s.step(outflow, 0.1, 0.1, x3, y3), std::logic_error);
  CHECK_THROWS_AS(OutflowLines({}), std::invalid_argument);
  CHECK_THROWS_AS(OutflowLines({{{0.0, 0.0}}}), std::invalid_argument);
  CHECK_THROWS_WITH(OutflowLines({{{0.0, 0.0}, {1.0, 0.0}}, {{2.0, 0.0}, {2.0, 0.0}}}),
                    Catch::Contains("outflow line 2") && Catch::Contains("point 2"));
}

TEST_CASE("inflow to outflow in a closed channel: the volume balance closes every step",
          "[inflow][outflow]") {
  // A walled channel 4 m x 1 m with a little water at its upstream end. A flood enters
  // through the upstream end (x = 0), runs down and leaves through a line across x = 2.5.
  const double l = 0.05;
  const auto lattice = particles::fill_polygon({{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}}, l);
  particles::SweParticles p;
  for (const auto& q : lattice.points) {
    p.add_fluid(q[0], q[1], 0.0, 0.0, 0.03 * lattice.cell_area_m2, 0.03, lattice.cell_area_m2, 0);
  }
  const Vec a{0, 0}, b{4, 0}, c{4, 1}, d{0, 1};
  boundaries::GhostWalls walls({{a, b, boundaries::WallCondition::slip},
                                {b, c, boundaries::WallCondition::slip},
                                {c, d, boundaries::WallCondition::slip},
                                {d, a, boundaries::WallCondition::slip}});
  const Hydrograph flood({{0.0, 0.01}, {2.0, 0.04}, {6.0, 0.02}});
  InflowLineSettings in;
  in.name = "upstream";
  in.from = a;
  in.to = d;
  in.direction = {1.0, 0.0};
  in.spacing_m = l;
  auto outflow =
      std::make_unique<OutflowLines>(std::vector<boundaries::Polyline>{{{2.5, 0}, {2.5, 1}}});
  auto inflow = std::make_unique<InflowLine>(in, flood);
  const OutflowLines& out = *outflow;
  const InflowLine& inl = *inflow;
  std::vector<std::unique_ptr<swe::Effect>> effects;
  effects.push_back(std::move(outflow));  // first: it reads the positions before the move
  effects.push_back(std::move(inflow));
  swe::Simulation sim(std::move(p), {}, std::move(walls), std::move(effects));
  const double initial = sim.fluid_volume();

  double worst_balance = 0.0, worst_inflow = 0.0;
  std::size_t steps_checked = 0;
  while (out.removed_particles() < 100 && sim.time() < 20.0) {
    sim.advance(sim.stable_time_step());
    const auto& ledger = sim.ledger();
    REQUIRE(ledger.added_m3 == inl.volume_added());
    REQUIRE(ledger.removed_m3 == out.volume_removed());
    REQUIRE(ledger.initial_m3 == initial);
    const double expected = initial + ledger.added_m3 - ledger.removed_m3;
    worst_balance = std::max(worst_balance, std::abs(sim.fluid_volume() - expected) / expected);
    const double flooded = flood.volume(0.0, sim.time());
    worst_inflow = std::max(
        worst_inflow, std::abs(inl.volume_added() + inl.pending_volume() - flooded) / flooded);
    ++steps_checked;
  }
  INFO("t = " << sim.time() << " s after " << steps_checked << " steps");
  CHECK(out.removed_particles() >= 100);  // the water reached the outflow
  CHECK(inl.rows_emitted() > 20);
  CHECK(worst_balance < 1e-12);
  CHECK(worst_inflow < 1e-12);
  CHECK(std::abs(sim.relative_volume_change()) < 1e-12);
  // Nothing left past the outflow line, and nothing behind the walls.
  const auto& q = sim.particles();
  for (std::size_t i = 0; i < q.fluid_count(); ++i) {
    CHECK(q.x[i] > 0.0);
    CHECK(q.x[i] < 2.5);
    CHECK(q.y[i] > 0.0);
    CHECK(q.y[i] < 1.0);
  }
  const auto times = sim.effect_times();
  REQUIRE(times.size() == 2);
  CHECK(times[1].name == "upstream");
  CHECK_THAT(times[0].report, Catch::Contains("left through outflow lines"));
}

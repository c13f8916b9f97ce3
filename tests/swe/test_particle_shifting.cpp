// Particle shifting (swe/particle_shifting.hpp): no shift at rest or on an even lattice,
// walls included; a particle that leaves a column of a stretched lattice is moved on into the
// gap; none at the water's edge; never more than the cap.

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/swe/conservative_scheme.hpp"
#include "swemps/swe/particle_shifting.hpp"
#include "swemps/swe/simulation.hpp"

using namespace swemps;

namespace {

// Water 1 m deep on a lattice dx x dy over [0, width] x [0, 1], every particle moving at
// (u, 0); `nudge` moves the particle nearest (width / 2, 0.5) by (nudge, 0).
particles::SweParticles columns(double width, double dx, double dy, double u, double nudge) {
  particles::SweParticles p;
  const double area = dx * dy;
  const auto nx = static_cast<int>(std::lround(width / dx));
  const auto ny = static_cast<int>(std::lround(1.0 / dy));
  for (int i = 0; i < nx; ++i)
    for (int k = 0; k < ny; ++k) {
      double x = (i + 0.5) * dx;
      const double y = (k + 0.5) * dy;
      if (i == nx / 2 && k == ny / 2) x += nudge;
      p.add_fluid(x, y, u, 0.0, area, 1.0, area, 0);
    }
  return p;
}

boundaries::GhostWalls box(double width, bool closed) {
  const std::array<double, 2> a{0, 0}, b{width, 0}, c{width, 1}, d{0, 1};
  const auto slip = boundaries::WallCondition::slip;
  if (!closed) return boundaries::GhostWalls({{a, b, slip}, {d, c, slip}});
  return boundaries::GhostWalls({{a, b, slip}, {b, c, slip}, {c, d, slip}, {d, a, slip}});
}

struct Shifts {
  std::vector<double> x, y;
};

// The shifts of a step of dt from the refreshed state of `sim`.
Shifts shifts_of(swe::Simulation& sim, double beta, double dt) {
  sim.refresh();
  const auto& p = sim.particles();
  Shifts s{std::vector<double>(p.fluid_count()), std::vector<double>(p.fluid_count())};
  swe::ConcentrationField field;
  const auto shape = swe::Settings{}.kernel;
  swe::concentration_field(p, sim.neighbor_list(), shape, field);
  std::vector<double> celerity(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) celerity[i] = std::sqrt(9.81 * p.depth[i]);
  swe::particle_shift(p, sim.neighbor_list(), shape, beta, dt, field, celerity, s.x, s.y);
  return s;
}

std::size_t nearest(const particles::SweParticles& p, double x, double y) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < p.fluid_count(); ++i)
    if (std::hypot(p.x[i] - x, p.y[i] - y) < std::hypot(p.x[best] - x, p.y[best] - y)) best = i;
  return best;
}

}  // namespace

TEST_CASE("particle shifting: none at rest, none on an even lattice up to its walls",
          "[swe][shifting]") {
  const double spacing = 0.05;
  for (const double u : {0.0, 1.0}) {
    CAPTURE(u);
    swe::Simulation sim(columns(2.0, spacing, spacing, u, 0.0), swe::Settings{}, box(2.0, true),
                        {});
    const auto s = shifts_of(sim, 2.0, 0.01);
    double largest = 0.0;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      largest = std::max(largest, std::hypot(s.x[i], s.y[i]));
    // At rest D = 0 exactly. Moving, the lattice and its mirror images behind the walls are
    // even, so grad C is round-off: 1e-12 of a spacing bounds it with margin.
    if (u == 0.0) CHECK(largest == 0.0);
    CHECK(largest < 1e-12 * spacing);
  }
}

TEST_CASE("particle shifting: a particle leaving a column is moved on into the gap",
          "[swe][shifting]") {
  // Columns 0.125 m apart of particles 0.025 m apart: the lattice a dam break stretches five
  // times along the flow. A particle nudged 5 mm off its column is shifted further the same
  // way (C is highest on the columns), so the gaps fill as they open.
  const double dx = 0.125, dy = 0.025;
  for (const double nudge : {0.005, -0.005}) {
    CAPTURE(nudge);
    swe::Simulation sim(columns(2.0, dx, dy, 1.0, nudge), swe::Settings{}, box(2.0, true), {});
    const auto s = shifts_of(sim, 2.0, 0.01);
    const auto& p = sim.particles();
    const std::size_t i = nearest(p, 1.0 + dx / 2 + nudge, 0.5 + dy / 2);
    REQUIRE(std::abs(p.x[i] - (1.0 + dx / 2 + nudge)) < 1e-12);
    CHECK(s.x[i] * nudge > 0.0);
    CHECK(std::abs(s.x[i]) > 1e-4 * dx);  // a real shift, not round-off
    // Symmetric in y about the nudged particle's row: no sideways shift of it.
    CHECK(std::abs(s.y[i]) < 1e-9 * std::abs(s.x[i]));
  }
}

TEST_CASE("particle shifting: slow water is shifted as the square of its speed",
          "[swe][shifting]") {
  // The stretched columns of the test above, 1 m deep (celerity 3.13 m/s), moving at speeds
  // either side of Froude 0.1 (kSlowFroude). Above it the shift grows as |u|; below it as |u|^2,
  // so that about rest the shift is of second order (a round-off velocity moves nothing).
  const double dx = 0.125, dy = 0.025, nudge = 0.005;
  const auto shift_at = [&](double u) {
    swe::Simulation sim(columns(2.0, dx, dy, u, nudge), swe::Settings{}, box(2.0, true), {});
    const auto s = shifts_of(sim, 2.0, 0.01);
    const auto& p = sim.particles();
    return s.x[nearest(p, 1.0 + dx / 2 + nudge, 0.5 + dy / 2)];
  };
  const double celerity = std::sqrt(9.81);
  const double slow = 0.02 * celerity, fast = 0.2 * celerity;
  REQUIRE(shift_at(slow) > 0.0);
  CHECK(shift_at(2.0 * slow) / shift_at(slow) == Approx(4.0).epsilon(1e-9));
  CHECK(shift_at(2.0 * fast) / shift_at(fast) == Approx(2.0).epsilon(1e-9));
  // Continuous at Froude 0.1.
  const double edge = swe::kSlowFroude * celerity;
  CHECK(shift_at(edge * (1.0 - 1e-9)) == Approx(shift_at(edge)).epsilon(1e-6));
}

TEST_CASE("particle shifting: none at the water's edge, never more than the cap",
          "[swe][shifting]") {
  // A moving patch with walls only along its sides: its two ends are edges of the water.
  const double spacing = 0.05;
  swe::Simulation sim(columns(1.0, spacing, spacing, 1.0, 0.02), swe::Settings{}, box(1.0, false),
                      {});
  const double beta = 1e6;  // every shift that is not zero reaches the cap
  const auto s = shifts_of(sim, beta, 0.01);
  const auto& p = sim.particles();
  std::size_t capped = 0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double length = std::hypot(s.x[i], s.y[i]);
    const double cap = swe::kLargestShift * std::sqrt(p.area[i]);
    CHECK(length <= cap * (1.0 + 1e-12));
    capped += length > 0.5 * cap;
    // The outermost column at each end has its support cut in half: C is about 0.5-0.7.
    if (p.x[i] < spacing || p.x[i] > 1.0 - spacing) CHECK(length == 0.0);
  }
  CHECK(capped > 0);  // the nudged particle and its neighbours are shifted
}

TEST_CASE("particle shifting: the scheme's force pass sums the same concentration field",
          "[swe][shifting]") {
  // The conservative scheme sums C and grad C in its force pass; its shifts must be those of
  // the field summed on its own (up to the order of additions: 1e-12 of a shift).
  const double spacing = 0.05;
  auto water = columns(2.0, 0.1, 0.04, 1.0, 0.01);
  for (std::size_t i = 0; i < water.fluid_count(); ++i) water.v[i] = 0.3 * std::sin(7.0 * i);
  swe::Simulation sim(std::move(water), swe::Settings{}, box(2.0, true), {});
  const auto reference = shifts_of(sim, 2.0, 0.01);
  auto p = sim.particles();
  swe::ConservativeScheme scheme(swe::Settings{});
  std::vector<double> ax(p.fluid_count()), ay(p.fluid_count()), sx(ax.size()), sy(ax.size());
  scheme.surface_acceleration(p, sim.neighbor_list(), 9.81, ax, ay);
  REQUIRE(scheme.regularising_shift(p, sim.neighbor_list(), 0.01, sx, sy));
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < sx.size(); ++i) {
    largest = std::max(largest, std::hypot(reference.x[i], reference.y[i]));
    worst = std::max(worst, std::hypot(sx[i] - reference.x[i], sy[i] - reference.y[i]));
  }
  CHECK(largest > 1e-4 * spacing);  // the columns and the sideways velocities do shift
  CHECK(worst <= 1e-12 * largest);
}

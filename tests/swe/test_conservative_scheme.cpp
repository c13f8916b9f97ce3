// Properties of the conservative shallow-water scheme (swe/conservative_scheme.hpp): true
// depths on three arrangements, the depth iteration, equal and opposite pair forces, momentum
// and energy, rest, and splitting with per-particle radii.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/splitting/particle_splitting.hpp"
#include "swemps/swe/conservative_scheme.hpp"
#include "swemps/swe/operators.hpp"
#include "swemps/swe/simulation.hpp"

using namespace swemps;

namespace {

enum class Arrangement { square, hexagonal, jittered };

// Water `depth` deep over [0, width] x [0, height], one particle per area spacing^2 on the
// arrangement, each carrying depth x its area: uniform water whose true depth is `depth`.
// Hexagonal rows are spacing * sqrt(sqrt(3)/2) * ... apart so that the area per particle is
// still spacing^2; jittered particles are moved off the square lattice by up to 10 % of the
// spacing in each direction (a seeded generator, so the test is reproducible).
particles::SweParticles water(Arrangement arrangement, double width, double height, double depth,
                              double spacing) {
  particles::SweParticles p;
  const double area = spacing * spacing;
  const auto add = [&](double x, double y) { p.add_fluid(x, y, 0, 0, depth * area, depth, area, 0); };
  if (arrangement == Arrangement::hexagonal) {
    // Side a with (sqrt(3)/2) a^2 = spacing^2; rows sqrt(3)/2 a apart, every other one shifted.
    const double a = spacing * std::sqrt(2.0 / std::sqrt(3.0));
    const double row = 0.5 * std::sqrt(3.0) * a;
    const int columns = static_cast<int>(std::lround(width / a));
    const int rows = static_cast<int>(std::lround(height / row));
    for (int k = 0; k < rows; ++k)
      for (int i = 0; i < columns; ++i) add((i + (k % 2 == 0 ? 0.25 : 0.75)) * width / columns,
                                            (k + 0.5) * height / rows);
    // The lattice fitted to the box: the particles' volumes share the box's water exactly.
    for (std::size_t i = 0; i < p.fluid_count(); ++i) {
      const double fitted = width * height / static_cast<double>(p.fluid_count());
      p.volume[i] = depth * fitted;
      p.area[i] = p.initial_area[i] = fitted;
    }
    return p;
  }
  std::mt19937 random(17);
  std::uniform_real_distribution<double> jitter(-0.1 * spacing, 0.1 * spacing);
  const int columns = static_cast<int>(std::lround(width / spacing));
  const int rows = static_cast<int>(std::lround(height / spacing));
  for (int k = 0; k < rows; ++k)
    for (int i = 0; i < columns; ++i) {
      double x = (i + 0.5) * spacing, y = (k + 0.5) * spacing;
      if (arrangement == Arrangement::jittered) {
        x += jitter(random);
        y += jitter(random);
      }
      add(x, y);
    }
  return p;
}

boundaries::GhostWalls closed_box(double width, double height) {
  const std::array<double, 2> a{0, 0}, b{width, 0}, c{width, height}, d{0, height};
  const auto slip = boundaries::WallCondition::slip;
  return boundaries::GhostWalls({{a, b, slip}, {b, c, slip}, {c, d, slip}, {d, a, slip}});
}

swe::Settings conservative() {
  swe::Settings s;
  s.scheme = swe::SchemeKind::conservative;
  return s;
}

double distance_to_box(double x, double y, double width, double height) {
  return std::min({x, y, width - x, height - y});
}

double max_speed(const particles::SweParticles& p) {
  double s = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) s = std::max(s, std::hypot(p.u[i], p.v[i]));
  return s;
}

const char* name(Arrangement a) {
  return a == Arrangement::square ? "square" : a == Arrangement::hexagonal ? "hexagonal" : "jittered";
}

}  // namespace

TEST_CASE("conservative scheme: uniform water sums to its depth", "[swe][conservative]") {
  const auto arrangement =
      GENERATE(Arrangement::square, Arrangement::hexagonal, Arrangement::jittered);
  constexpr double width = 2.0, height = 1.0, depth = 0.25, spacing = 0.05;
  swe::Simulation sim(water(arrangement, width, height, depth, spacing), conservative(),
                      closed_box(width, height), {});
  sim.refresh();
  const auto& p = sim.particles();
  struct Errors {
    double sum = 0.0, squares = 0.0, worst = 0.0;
    int count = 0;
    void add(double e) {
      sum += e;
      squares += e * e;
      worst = std::max(worst, std::abs(e));
      ++count;
    }
  } interior, wall, grid_interior, grid_wall;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const bool inside = distance_to_box(p.x[i], p.y[i], width, height) > 3 * spacing;
    (inside ? interior : wall).add(p.depth[i] / depth - 1.0);
  }
  // Gridded: cell centres one spacing apart, offset from the particles.
  const swe::RegularGrid grid{0.35 * spacing, 0.35 * spacing, spacing, spacing,
                              static_cast<std::size_t>(width / spacing),
                              static_cast<std::size_t>(height / spacing)};
  const auto gridded = swe::depth_on_grid(p, sim.kernel(), grid);
  for (std::size_t c = 0; c < gridded.size(); ++c) {
    const double x = grid.x0 + static_cast<double>(c % grid.nx) * grid.dx;
    const double y = grid.y0 + static_cast<double>(c / grid.nx) * grid.dy;
    const bool inside = distance_to_box(x, y, width, height) > 3 * spacing;
    (inside ? grid_interior : grid_wall).add(gridded[c] / depth - 1.0);
  }
  const auto text = [](const Errors& e) {
    return "mean " + std::to_string(e.sum / e.count) + " rms " +
           std::to_string(std::sqrt(e.squares / e.count)) + " max " + std::to_string(e.worst);
  };
  INFO(name(arrangement) << ": particle interior " << text(interior) << "; walls " << text(wall)
                         << "; grid interior " << text(grid_interior) << "; walls "
                         << text(grid_wall));
  // Square and hexagonal lattices: the cubic spline's lattice sum at h = 1.3 spacings
  // (docs/kernels.md: 0.005 % square, 0.36 % hexagonal at particles; 0.04-0.4 % between
  // them). 0.5 % is the bar for the interior. The square lattice continues exactly
  // into its mirror images, so it holds up to the walls; a hexagonal one does not (its rows
  // are not symmetric about a wall), and a jittered one has particle-scale depth noise of its
  // own (equal volumes on unequal cells): for those the bar is on the mean, the bias the
  // kernel adds (their scatter is in docs/method.md).
  if (arrangement != Arrangement::jittered) {
    CHECK(interior.worst < 0.005);
    CHECK(grid_interior.worst < 0.005);
  }
  if (arrangement == Arrangement::square) {
    CHECK(wall.worst < 0.005);
    CHECK(grid_wall.worst < 0.005);
  }
  CHECK(std::abs(interior.sum / interior.count) < 0.005);
  CHECK(std::abs(grid_interior.sum / grid_interior.count) < 0.005);
}

TEST_CASE("conservative scheme: depth, radius and grad-h factor agree", "[swe][conservative]") {
  // A blob of disordered water, no walls: each particle's depth is the kernel sum at its own
  // radius kappa sqrt(V / d), and Omega is the derivative of that sum, checked against a
  // central difference of it.
  auto p = water(Arrangement::jittered, 1.0, 1.0, 0.3, 0.05);
  for (std::size_t i = 0; i < p.fluid_count(); ++i) p.volume[i] *= 1.0 + 0.5 * std::sin(7.0 * p.x[i]);
  const auto settings = conservative();
  swe::Simulation sim(p, settings, {}, {});
  sim.refresh();
  const auto& q = sim.particles();
  const auto& scheme = dynamic_cast<const swe::ConservativeScheme&>(sim.scheme());
  CHECK(scheme.last_most_iterations() <= 20);
  const auto summed = [&](std::size_t i, double h) {
    double d = 0.0;
    for (std::size_t j = 0; j < q.fluid_count(); ++j)
      d += q.volume[j] * kernels::CubicSpline<2>::w(std::hypot(q.x[j] - q.x[i], q.y[j] - q.y[i]), h);
    return d;
  };
  for (std::size_t i = 0; i < q.fluid_count(); i += 37) {
    const double h = q.smoothing_length[i];
    // The depth is the sum at the radius it was taken with (to round-off), and that radius
    // belongs to the depth to the iteration's tolerance of 1e-10.
    CHECK(q.depth[i] == Approx(summed(i, h)).epsilon(1e-12));
    CHECK(h == Approx(settings.kappa * std::sqrt(q.volume[i] / q.depth[i])).epsilon(1e-8));
    // Omega = 1 - dS/dd with S(d) = sum at h(d): central difference in d.
    const double d = q.depth[i], step = 1e-6 * d;
    const auto s_of = [&](double depth) {
      return summed(i, settings.kappa * std::sqrt(q.volume[i] / depth));
    };
    const double omega = 1.0 - (s_of(d + step) - s_of(d - step)) / (2.0 * step);
    CHECK(q.omega[i] == Approx(omega).epsilon(1e-5));
  }
}

TEST_CASE("conservative scheme: pair forces are equal and opposite", "[swe][conservative]") {
  // Disordered water with unequal volumes and velocities, no walls: every particle has its own
  // radius, and yet sum_i V_i a_i vanishes to round-off, the pressure and the dissipation
  // alike; and the neighbour rows are symmetric.
  auto p = water(Arrangement::jittered, 1.0, 0.6, 0.3, 0.04);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    p.volume[i] *= 1.0 + 0.4 * unit(random);
    p.u[i] = unit(random);
    p.v[i] = unit(random);
  }
  swe::Simulation sim(p, conservative(), {}, {});
  sim.refresh();
  auto q = sim.particles();
  const auto& nl = sim.neighbor_list();
  std::vector<double> ax(q.fluid_count()), ay(q.fluid_count());
  swe::ConservativeScheme scheme(conservative());
  scheme.surface_acceleration(q, nl, 9.81, ax, ay);
  double fx = 0.0, fy = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < q.fluid_count(); ++i) {
    fx += q.volume[i] * ax[i];
    fy += q.volume[i] * ay[i];
    scale += q.volume[i] * std::hypot(ax[i], ay[i]);
  }
  REQUIRE(scale > 0.0);
  // Each pair's two terms cancel exactly but are summed in different orders: round-off of a
  // few ulps per term, over ~25 terms per particle.
  CHECK(std::abs(fx) < 1e-12 * scale);
  CHECK(std::abs(fy) < 1e-12 * scale);
  for (std::size_t i = 0; i < q.fluid_count(); ++i) {
    for (const std::uint32_t j : nl.row(i)) {
      const auto row = nl.row(j);
      CHECK(std::find(row.begin(), row.end(), i) != row.end());
    }
  }
}


namespace {

double momentum_x(const particles::SweParticles& p) {
  double m = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) m += p.volume[i] * p.u[i];
  return m;
}
double momentum_y(const particles::SweParticles& p) {
  double m = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) m += p.volume[i] * p.v[i];
  return m;
}
// sum_i V_i (|u_i|^2 / 2 + g d_i / 2): kinetic energy and the potential energy of the summed
// depths, per unit density, of a refreshed state.
double energy(swe::Simulation& sim) {
  sim.refresh();
  const auto& p = sim.particles();
  const double g = sim.settings().gravity_m_s2;
  double e = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i)
    e += p.volume[i] * (0.5 * (p.u[i] * p.u[i] + p.v[i] * p.v[i]) + 0.5 * g * p.depth[i]);
  return e;
}

}  // namespace

TEST_CASE("conservative scheme: a free column conserves momentum", "[swe][conservative]") {
  // A column of water collapsing and drifting with no wall and no bed: nothing outside acts on
  // it, so its momentum stays what it was while it spreads and its particles' radii grow.
  auto p = water(Arrangement::square, 0.6, 0.4, 0.5, 0.04);
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    p.u[i] = 0.3 + 0.2 * p.y[i];
    p.v[i] = -0.1 + 0.3 * p.x[i];
  }
  swe::Simulation sim(p, conservative(), {}, {});
  const double mx = momentum_x(sim.particles()), my = momentum_y(sim.particles());
  sim.advance_to(0.5);
  REQUIRE(sim.steps() > 30);
  INFO("momentum drift " << momentum_x(sim.particles()) - mx << ", "
                         << momentum_y(sim.particles()) - my);
  // Round-off: each step adds sums of ~1e3 terms of size V |a| dt ~ 1e-5; 1e-13 of the
  // momentum's scale (V |u| ~ 0.04 m^4/s) is some hundred ulps per step.
  CHECK(std::abs(momentum_x(sim.particles()) - mx) < 1e-13);
  CHECK(std::abs(momentum_y(sim.particles()) - my) < 1e-13);
}

TEST_CASE("conservative scheme: energy never grows in a closed box", "[swe][conservative]") {
  // A dam break in a closed, frictionless box: the bore runs into the far wall and back.
  // Energy can only go into the dissipation of approaching pairs.
  constexpr double width = 2.0, height = 0.4;
  auto p = water(Arrangement::square, 0.6, height, 0.4, 0.04);
  swe::Simulation sim(p, conservative(), closed_box(width, height), {});
  const double e0 = energy(sim);
  double largest = e0;
  while (!sim.reached(3.0)) {
    sim.step_towards(3.0);
    largest = std::max(largest, energy(sim));
  }
  const double e1 = energy(sim);
  INFO("energy: start " << e0 << ", largest " << largest << ", end " << e1);
  // Pressure forces conserve energy and the dissipation only removes it; what is left is the
  // round-off of the energy sum (1e-12 relative).
  CHECK(largest <= e0 * (1.0 + 1e-12));
  CHECK(e1 < e0);
}

TEST_CASE("conservative scheme: water at rest stays at rest", "[swe][conservative][physics]") {
  // 20,000 steps (180 s) in a closed box on each arrangement. None of them starts in exact
  // balance: the square lattice is an equilibrium but not the arrangement of least energy,
  // the hexagonal one is unbalanced at the walls and the jittered one everywhere. Each
  // rearranges (at most 0.02, 0.3 and 0.15 m/s, measured: docs/method.md) and comes to rest
  // at lower energy: the forces conserve energy and only the dissipation of approaching pairs
  // changes it. Energy is checked every 100 steps against the start, to the round-off of its
  // sum (1e-12 relative); the end state must be at rest to round-off of the forces (~1e-14
  // m/s measured; 1e-10 m/s is far below any physical motion).
  const auto arrangement =
      GENERATE(Arrangement::square, Arrangement::hexagonal, Arrangement::jittered);
  constexpr double width = 0.6, height = 0.4;
  swe::Simulation sim(water(arrangement, width, height, 0.5, 0.04), conservative(),
                      closed_box(width, height), {});
  const double e0 = energy(sim);
  double largest = e0;
  for (int k = 0; k < 20000; ++k) {
    sim.advance(sim.stable_time_step());
    if (k % 100 == 0) largest = std::max(largest, energy(sim));
  }
  INFO(name(arrangement) << ": energy " << e0 << " -> " << energy(sim) << ", largest " << largest);
  CHECK(largest <= e0 * (1.0 + 1e-12));
  CHECK(energy(sim) < e0);
  CHECK(max_speed(sim.particles()) < 1e-10);
}

TEST_CASE("conservative scheme: daughters of a split get their own radius", "[swe][conservative]") {
  // A dam break whose front thins past 1.5 A_0: splitting fires, the daughters take the radius
  // of their own area, and volume stays exact.
  constexpr double width = 3.0, height = 0.3;
  auto p = water(Arrangement::square, 0.6, height, 0.3, 0.03);
  const auto box = closed_box(width, height);
  std::vector<std::unique_ptr<swe::Effect>> effects;
  effects.push_back(std::make_unique<splitting::ParticleSplitting>(
      splitting::SplittingSettings{},
      std::vector<boundaries::WallSegment>(box.segments().begin(), box.segments().end())));
  const auto settings = conservative();
  swe::Simulation sim(p, settings, box, std::move(effects));
  const std::size_t start = sim.particles().fluid_count();
  sim.advance_to(0.6);
  sim.refresh();
  const auto& q = sim.particles();
  REQUIRE(q.fluid_count() > start);
  CHECK(std::abs(sim.relative_volume_change()) < 1e-13);
  for (std::size_t i = 0; i < q.fluid_count(); ++i) {
    const double area = std::min(q.area[i], settings.area_ratio_cap() * q.initial_area[i]);
    CHECK(q.smoothing_length[i] == Approx(settings.kappa * std::sqrt(area)).epsilon(1e-8));
  }
}

TEST_CASE("conservative scheme: a few depths summed again are those of summing all",
          "[swe][conservative]") {
  // The depths of a repair (neighbors/row_repair.hpp): the particles named are summed as a
  // sum of every particle sums them, bit for bit, and the others are left as they were.
  auto start = water(Arrangement::jittered, 1.0, 1.0, 0.3, 0.05);
  for (std::size_t i = 0; i < start.fluid_count(); ++i) {
    start.volume[i] *= 1.0 + 0.2 * std::sin(5.0 * start.y[i]);
    start.smoothing_length[i] = conservative().kappa * std::sqrt(start.area[i]);
  }
  // Every pair within 0.3 m: wider than any support here (2 x 1.3 x 0.05 x 1.05 and some).
  const auto nl = neighbors::brute_force_neighbors<2>(
      {std::span<const double>(start.x), std::span<const double>(start.y)}, start.fluid_count(),
      0.3);
  swe::ConservativeScheme scheme(conservative());
  // Summed until the radii settle, then the volumes nudged, as a step leaves them.
  for (int pass = 0; pass < 10 && !scheme.sum_depth(start, nl); ++pass) {
  }
  REQUIRE(scheme.sum_depth(start, nl));
  for (std::size_t i = 0; i < start.fluid_count(); ++i)
    start.volume[i] *= 1.0 + 0.01 * std::cos(9.0 * start.x[i]);
  auto all = start;
  REQUIRE(scheme.sum_depth(all, nl));
  auto some = start;
  const std::vector<std::uint32_t> which{3, 40, 41, 250};
  REQUIRE(scheme.sum_depth_of(some, nl, which));
  CHECK(scheme.outgrown().empty());
  for (std::size_t i = 0; i < start.fluid_count(); ++i) {
    const bool named = std::find(which.begin(), which.end(), i) != which.end();
    const auto& expected = named ? all : start;
    CHECK(some.depth[i] == expected.depth[i]);
    CHECK(some.area[i] == expected.area[i]);
    CHECK(some.smoothing_length[i] == expected.smoothing_length[i]);
    CHECK(some.omega[i] == expected.omega[i]);
  }
  // A particle searched with a third of its radius outgrows that search, and is named.
  auto narrow = start;
  narrow.smoothing_length[40] /= 3.0;
  CHECK_FALSE(scheme.sum_depth_of(narrow, nl, which));
  CHECK(std::vector<std::uint32_t>(scheme.outgrown().begin(), scheme.outgrown().end()) ==
        std::vector<std::uint32_t>{40});
}

// Tests of ghost-particle walls: placement, velocities, corners, and that no particle ever
// crosses a wall.

#include <catch2/catch.hpp>
#include <cmath>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/particles/seeding.hpp"
#include "swemps/swe/simulation.hpp"

using namespace swemps;
using boundaries::GhostWalls;
using boundaries::WallCondition;

namespace {

particles::SweParticles one_particle(double x, double y, double u, double v) {
  particles::SweParticles p;
  p.add_fluid(x, y, u, v, 0.01, 0.25, 0.04, 0.0);
  return p;
}

}  // namespace

TEST_CASE("a particle near a straight wall gets one mirrored ghost", "[boundaries]") {
  // Wall along y = 0 (tangent +x, normal +y).
  GhostWalls slip({{{0.0, 0.0}, {10.0, 0.0}, WallCondition::slip}});
  GhostWalls no_slip({{{0.0, 0.0}, {10.0, 0.0}, WallCondition::no_slip}});
  auto p = one_particle(2.0, 0.3, 1.5, -0.7);
  slip.add_ghosts(p, 0.5);
  REQUIRE(p.ghost_count() == 1);
  CHECK(p.x[1] == Approx(2.0));
  CHECK(p.y[1] == Approx(-0.3));
  CHECK(p.u[1] == Approx(1.5));  // slip: tangential equal
  CHECK(p.v[1] == Approx(0.7));  // normal opposite
  CHECK(p.source[1] == 0);
  CHECK(p.volume[1] == p.volume[0]);
  p.drop_ghosts();
  no_slip.add_ghosts(p, 0.5);
  REQUIRE(p.ghost_count() == 1);
  CHECK(p.u[1] == Approx(-1.5));  // no-slip: tangential opposite
  CHECK(p.v[1] == Approx(0.7));
  p.drop_ghosts();
  // Out of reach, or beyond the segment's ends: no ghost.
  auto far = one_particle(2.0, 0.6, 0.0, 0.0);
  slip.add_ghosts(far, 0.5);
  CHECK(far.ghost_count() == 0);
  auto beyond = one_particle(10.2, 0.1, 0.0, 0.0);
  slip.add_ghosts(beyond, 0.5);
  CHECK(beyond.ghost_count() == 0);
}

TEST_CASE("a slanted wall mirrors across its own line", "[boundaries]") {
  GhostWalls wall({{{0.0, 0.0}, {1.0, 1.0}, WallCondition::slip}});
  auto p = one_particle(0.6, 0.4, 1.0, 0.0);
  wall.add_ghosts(p, 0.5);
  REQUIRE(p.ghost_count() == 1);
  CHECK(p.x[1] == Approx(0.4));
  CHECK(p.y[1] == Approx(0.6));
  // Velocity (1, 0) mirrored across the line y = x becomes (0, 1).
  CHECK(p.u[1] == Approx(0.0).margin(1e-15));
  CHECK(p.v[1] == Approx(1.0));
}

TEST_CASE("a particle in a corner gets a ghost for each wall and one across both", "[boundaries]") {
  // One polyline: (10,0) -> (0,0) -> (0,1), the corner of the dam-break tank.
  GhostWalls walls({{{10.0, 0.0}, {0.0, 0.0}, WallCondition::slip},
                    {{0.0, 0.0}, {0.0, 1.0}, WallCondition::slip}});
  auto p = one_particle(0.05, 0.15, 0.3, 0.2);
  walls.add_ghosts(p, 0.26);
  REQUIRE(p.ghost_count() == 3);
  std::vector<std::array<double, 4>> ghosts;
  for (std::size_t k = 1; k < p.size(); ++k) ghosts.push_back({p.x[k], p.y[k], p.u[k], p.v[k]});
  auto has = [&](double x, double y, double u, double v) {
    return std::any_of(ghosts.begin(), ghosts.end(), [&](const auto& g) {
      return std::abs(g[0] - x) < 1e-12 && std::abs(g[1] - y) < 1e-12 &&
             std::abs(g[2] - u) < 1e-12 && std::abs(g[3] - v) < 1e-12;
    });
  };
  CHECK(has(0.05, -0.15, 0.3, -0.2));
  CHECK(has(-0.05, 0.15, -0.3, 0.2));
  CHECK(has(-0.05, -0.15, -0.3, -0.2));
}

TEST_CASE("collinear segments joined end to end give one ghost, not two", "[boundaries]") {
  GhostWalls walls({{{0.0, 0.0}, {1.0, 0.0}, WallCondition::slip},
                    {{1.0, 0.0}, {2.0, 0.0}, WallCondition::slip}});
  auto p = one_particle(1.0, 0.1, 0.0, 0.0);
  walls.add_ghosts(p, 0.5);
  CHECK(p.ghost_count() == 1);
}

TEST_CASE("path-wall crossing", "[boundaries]") {
  const boundaries::WallSegment wall{{0.0, 0.0}, {1.0, 0.0}, WallCondition::slip};
  CHECK(GhostWalls::crosses(wall, {0.5, 0.1}, {0.5, -0.1}));
  CHECK(GhostWalls::crosses(wall, {0.5, 0.1}, {0.5, 0.0}));  // ending on the wall counts
  CHECK_FALSE(GhostWalls::crosses(wall, {0.5, 0.1}, {0.5, 0.05}));
  CHECK_FALSE(GhostWalls::crosses(wall, {1.5, 0.1}, {1.5, -0.1}));  // past the end
  CHECK_FALSE(GhostWalls::crosses(wall, {0.2, 0.1}, {0.8, 0.1}));   // parallel
}

TEST_CASE("a particle pushed through a wall is reflected back", "[boundaries]") {
  GhostWalls walls({{{0.0, 0.0}, {10.0, 0.0}, WallCondition::slip}});
  auto p = one_particle(2.0, 0.05, 1.0, -2.0);
  walls.add_ghosts(p, 0.5);
  p.drop_ghosts();
  const std::vector<double> old_x{p.x[0]}, old_y{p.y[0]};
  p.x[0] += 0.1;
  p.y[0] -= 0.2;  // now at y = -0.15
  CHECK(walls.keep_inside(p, old_x, old_y) == 1);
  CHECK(p.y[0] == Approx(0.15));
  CHECK(p.v[0] == Approx(2.0));  // bounced
  CHECK(p.u[0] == Approx(1.0));
}

TEST_CASE("no particle crosses a wall: a fast jet hits a wall", "[boundaries][swe]") {
  // Water shot at 4 m/s (Froude ~ 4) into a closed box: the ghost layer and the crossing
  // guard together must keep every particle inside at every step.
  const auto lattice =
      particles::fill_polygon({{0.2, 0.2}, {0.8, 0.2}, {0.8, 0.8}, {0.2, 0.8}}, 0.04);
  particles::SweParticles p;
  for (const auto& pt : lattice.points) {
    p.add_fluid(pt[0], pt[1], 4.0, 1.0, 0.1 * lattice.cell_area_m2, 0.1, lattice.cell_area_m2, 0.0);
  }
  const std::array<double, 2> a{0, 0}, b{2, 0}, c{2, 1}, d{0, 1};
  GhostWalls walls({{a, b, WallCondition::slip},
                    {b, c, WallCondition::slip},
                    {c, d, WallCondition::no_slip},
                    {d, a, WallCondition::slip}});
  swe::Simulation sim(std::move(p), {}, std::move(walls), {});
  std::size_t escaped = 0;
  sim.advance_to(1.5, [&] {
    const auto& q = sim.particles();
    for (std::size_t i = 0; i < q.fluid_count(); ++i) {
      if (!(q.x[i] > 0.0 && q.x[i] < 2.0 && q.y[i] > 0.0 && q.y[i] < 1.0)) ++escaped;
    }
  });
  CHECK(escaped == 0);
  CHECK(sim.steps() > 20);
  CHECK(std::abs(sim.relative_volume_change()) < 1e-14);
}

TEST_CASE("a particle beyond the ends of a building's walls cannot step round its corner",
          "[boundaries]") {
  // A square building [0, 4] x [0, 4]: the particle north-east of its corner (4, 4) is beyond
  // the end of both walls that meet there, and its step to the south-west ends inside.
  const std::vector<boundaries::WallSegment> walls{{{0.0, 0.0}, {4.0, 0.0}},
                                                   {{4.0, 0.0}, {4.0, 4.0}},
                                                   {{4.0, 4.0}, {0.0, 4.0}},
                                                   {{0.0, 4.0}, {0.0, 0.0}}};
  GhostWalls building(walls);
  for (const auto& [x, y] :
       {std::array{4.05, 4.05}, std::array{4.2, 4.01}, std::array{4.01, 4.2}}) {
    auto p = one_particle(x, y, -1.0, -1.0);
    building.add_ghosts(p, 0.5);
    p.drop_ghosts();
    const std::vector<double> old_x{p.x[0]}, old_y{p.y[0]};
    p.x[0] -= 0.3;
    p.y[0] -= 0.3;
    CHECK(building.keep_inside(p, old_x, old_y) == 1);
    INFO("from (" << x << ", " << y << ") to (" << p.x[0] << ", " << p.y[0] << ")");
    CHECK_FALSE((p.x[0] < 4.0 && p.y[0] < 4.0));
  }
}

TEST_CASE("no ghost stands beyond a building thinner than twice its particle's distance",
          "[boundaries]") {
  // A terrace 2 m deep, y in [0, 2]: a particle 1.5 m in front of it is mirrored 1.5 m into
  // it; one 2.5 m in front would be mirrored to 0.5 m beyond its back wall, into the gardens.
  const std::vector<boundaries::WallSegment> walls{{{-20.0, 0.0}, {20.0, 0.0}},
                                                   {{20.0, 0.0}, {20.0, 2.0}},
                                                   {{20.0, 2.0}, {-20.0, 2.0}},
                                                   {{-20.0, 2.0}, {-20.0, 0.0}}};
  GhostWalls terrace(walls);
  auto near = one_particle(0.0, -1.5, 0.0, 0.0);
  terrace.add_ghosts(near, 3.0);
  REQUIRE(near.ghost_count() == 1);
  CHECK(near.y[1] == Approx(1.5));
  auto far = one_particle(0.0, -2.5, 0.0, 0.0);
  terrace.add_ghosts(far, 3.0);
  CHECK(far.ghost_count() == 0);
}

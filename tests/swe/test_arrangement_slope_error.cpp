// The arrangement's slope error (swe/arrangement_slope_error.hpp): an error common to the
// planes of a neighbourhood is taken out and the levels' slope put in its place; the
// particle-scale part of the slopes is kept; shore planes are left as they are; water at
// rest stays at rest.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/swe/arrangement_slope_error.hpp"
#include "swemps/swe/simulation.hpp"

using namespace swemps;

namespace {

constexpr int kSide = 20;  // particles per side of the patch, spacing 1 m, 1 m deep

swe::Simulation patch() {
  particles::SweParticles p;
  for (int i = 0; i < kSide; ++i)
    for (int k = 0; k < kSide; ++k) p.add_fluid(i + 0.5, k + 0.5, 0.0, 0.0, 1.0, 1.0, 1.0, 0);
  swe::Simulation sim(std::move(p), swe::Settings{},
                      boundaries::GhostWalls(std::vector<boundaries::WallSegment>{}), {});
  sim.refresh();
  return sim;
}

// Planes for every particle of `sim`: level a + b . x, slope b + error(i), all interior.
template <class Error>
swe::ParticlePlanes planes_of(const particles::SweParticles& p, double bx, double by, Error error) {
  swe::ParticlePlanes planes;
  planes.resize(p.fluid_count());
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const auto [ex, ey] = error(i);
    planes.level[i] = 3.0 + bx * p.x[i] + by * p.y[i];
    planes.slope_x[i] = bx + ex;
    planes.slope_y[i] = by + ey;
    planes.interior[i] = 1;
  }
  return planes;
}

// Whether x lies two kernel radii (2 x 1.3 m) or more inside the patch: its neighbours and
// theirs are all there.
bool deep_inside(double x, double y) {
  const double margin = 2.0 * 2.6;
  return x > margin && y > margin && x < kSide - margin && y < kSide - margin;
}

}  // namespace

TEST_CASE("a slope error common to a neighbourhood gives way to the levels' slope",
          "[swe][balanced-bed]") {
  auto sim = patch();
  const auto& p = sim.particles();
  const auto shape = swe::Settings{}.kernel;
  // Levels rising 1e-3 to the east and 2e-4 to the north; every plane flat (an error of the
  // levels' slope exactly), as a staircase's planes are.
  auto planes = planes_of(p, 1e-3, 2e-4, [](std::size_t) { return std::pair{-1e-3, -2e-4}; });
  swe::ArrangementSlopeError error;
  error.remove(p, sim.neighbor_list(), shape, planes);
  // A linear level is read exactly by the least-squares gradient, edge particles included, and
  // a uniform error is its own average: every slope is the levels' to round-off.
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    CAPTURE(p.x[i], p.y[i]);
    CHECK(planes.slope_x[i] == Approx(1e-3).margin(1e-15));
    CHECK(planes.slope_y[i] == Approx(2e-4).margin(1e-15));
  }
}

TEST_CASE("the particle-scale part of the planes' slopes is kept", "[swe][balanced-bed]") {
  auto sim = patch();
  const auto& p = sim.particles();
  // Level water (G = 0), slopes alternating from particle to particle (the kernel average of a
  // checkerboard is zero on a lattice) beside a uniform error.
  const double amplitude = 1e-4, uniform = 3e-4;
  const auto sign = [&](std::size_t i) {
    return (std::lround(p.x[i] - 0.5) + std::lround(p.y[i] - 0.5)) % 2 == 0 ? 1.0 : -1.0;
  };
  auto planes = planes_of(p, 0.0, 0.0, [&](std::size_t i) {
    return std::pair{uniform + sign(i) * amplitude, 0.0};
  });
  swe::ArrangementSlopeError error;
  error.remove(p, sim.neighbor_list(), swe::Settings{}.kernel, planes);
  int checked = 0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    if (!deep_inside(p.x[i], p.y[i])) continue;
    CAPTURE(p.x[i], p.y[i]);
    // The uniform part goes; the alternating part stays but for the checkerboard's average
    // over the kernel (5e-4 of it for the cubic spline at kappa 1.3).
    CHECK(planes.slope_x[i] == Approx(sign(i) * amplitude).margin(1e-2 * amplitude));
    CHECK(std::abs(planes.slope_y[i]) < 1e-15);
    ++checked;
  }
  CHECK(checked > 50);
}

TEST_CASE("shore planes keep their slopes, and level water with flat planes stays so",
          "[swe][balanced-bed]") {
  auto sim = patch();
  const auto& p = sim.particles();
  SECTION("at rest") {
    auto planes = planes_of(p, 0.0, 0.0, [](std::size_t) { return std::pair{0.0, 0.0}; });
    swe::ArrangementSlopeError error;
    error.remove(p, sim.neighbor_list(), swe::Settings{}.kernel, planes);
    for (std::size_t i = 0; i < p.fluid_count(); ++i) {
      CHECK(planes.slope_x[i] == 0.0);
      CHECK(planes.slope_y[i] == 0.0);
    }
  }
  SECTION("a shore") {
    // The western half's planes are a shore's: neither corrected nor part of the average; the
    // eastern half sees its own errors only.
    auto planes = planes_of(p, 0.0, 0.0, [](std::size_t) { return std::pair{5e-4, 0.0}; });
    for (std::size_t i = 0; i < p.fluid_count(); ++i) planes.interior[i] = p.x[i] > kSide / 2;
    planes.level[0] = std::numeric_limits<double>::quiet_NaN();  // a plane that held nothing
    swe::ArrangementSlopeError error;
    error.remove(p, sim.neighbor_list(), swe::Settings{}.kernel, planes);
    for (std::size_t i = 0; i < p.fluid_count(); ++i) {
      CAPTURE(p.x[i], p.y[i]);
      CHECK(planes.slope_x[i] == Approx(p.x[i] > kSide / 2 ? 0.0 : 5e-4).margin(1e-15));
    }
  }
}

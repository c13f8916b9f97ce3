// Tests of particle merging: which particles pair, and that a merge conserves volume and
// momentum and puts the merged particle at the pair's centre of volume.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "swemps/splitting/particle_merging.hpp"
#include "swemps/swe/effect.hpp"

using namespace swemps;

namespace {

// Particles as the topology stage sees them: summed (area and radius set), no ghosts.
struct Scene {
  particles::SweParticles p;
  neighbors::NeighborList nl;  // the topology stage has none
  swe::ParticleKernel kernel{swe::KernelShape::spiky};
  std::vector<double> ax, ay;
  swe::Settings settings;
  swe::VolumeLedger ledger;

  // A particle of area `ratio` A_0 (A_0 = 0.01 m^2) and radius kappa sqrt(A), kappa = 1.3.
  void add(double x, double y, double ratio, double volume = 0.002, double u = 0.0,
           double v = 0.0) {
    const double area = ratio * 0.01;
    p.add_fluid(x, y, u, v, volume, volume / area, 0.01, -1.0 + x);
    p.area.back() = area;
    p.smoothing_length.back() = 1.3 * std::sqrt(area);
  }
  void merge(splitting::ParticleMerging& effect) {
    swe::StepContext context{p, nl, kernel, ax, ay, settings, ledger, 0.0, 0.01};
    effect.apply(context);
  }
};

}  // namespace

TEST_CASE("two small particles merge into one at their centre of volume", "[merging]") {
  Scene s;
  // Areas 0.3 A_0 and 0.4 A_0, radii 0.071 and 0.082 m, 0.05 m apart.
  s.add(0.0, 0.0, 0.3, 0.001, 1.0, -0.5);
  s.add(0.05, 0.0, 0.4, 0.003, -1.0, 0.5);
  const double r_a = s.p.smoothing_length[0], r_b = s.p.smoothing_length[1];
  splitting::ParticleMerging effect({0.5}, {});
  s.merge(effect);
  REQUIRE(s.p.fluid_count() == 1);
  CHECK(effect.merges() == 1);
  CHECK(s.p.volume[0] == 0.004);
  CHECK(s.p.x[0] == Approx(0.0375).margin(1e-15));  // (0.001 * 0 + 0.003 * 0.05) / 0.004
  CHECK(s.p.y[0] == 0.0);
  CHECK(s.p.u[0] * 0.004 == Approx(0.001 * 1.0 - 0.003 * 1.0).margin(1e-17));
  CHECK(s.p.v[0] * 0.004 == Approx(-0.001 * 0.5 + 0.003 * 0.5).margin(1e-17));
  CHECK(s.p.area[0] == Approx(0.007).margin(1e-17));
  CHECK(s.p.depth[0] == Approx(0.004 / 0.007));
  CHECK(s.p.smoothing_length[0] == Approx(std::hypot(r_a, r_b)));
  CHECK(s.p.bed[0] == Approx(-1.0 + 0.0375));  // the centre of volume's, for a plane bed
  CHECK(s.p.initial_area[0] == 0.01);
  CHECK(s.ledger.removed_m3 == 0.0);  // nothing left the domain
}

namespace {

// How many of two particles on the x axis, each given as (x, A / A_0), are left after one
// merge pass.
std::size_t left_of_pair(std::array<double, 2> a, std::array<double, 2> b) {
  Scene s;
  s.add(a[0], 0.0, a[1]);
  s.add(b[0], 0.0, b[1]);
  splitting::ParticleMerging effect({0.5}, {});
  s.merge(effect);
  return s.p.fluid_count();
}

}  // namespace

TEST_CASE("merging needs a small particle, a partner within reach, and no wall between",
          "[merging]") {
  splitting::ParticleMerging effect({0.5}, {});
  // A small particle beside one of its reference area stays.
  CHECK(left_of_pair({0.0, 0.3}, {0.05, 1.0}) == 2);
  // The threshold is strict.
  CHECK(left_of_pair({0.0, 0.5}, {0.05, 0.5}) == 2);
  // Two small particles beyond both radii (0.058 and 0.082 m) stay.
  CHECK(left_of_pair({0.0, 0.2}, {0.09, 0.4}) == 2);
  // A tiny particle (radius 0.041 m) merges with one of nearly full size within the larger's
  // radius (0.116 m): together 0.9 A_0 of their 2 A_0.
  CHECK(left_of_pair({0.0, 0.1}, {0.08, 0.8}) == 1);
  // But not where the pair would reach the threshold times both reference areas (1.0 A_0).
  CHECK(left_of_pair({0.0, 0.1}, {0.08, 0.9}) == 2);
  // A wall between two small particles keeps them apart; without it they merge.
  Scene s;
  s.add(-0.02, 0.0, 0.3);
  s.add(0.02, 0.0, 0.3);
  const boundaries::WallSegment wall{{0.0, -1.0}, {0.0, 1.0}, boundaries::WallCondition::slip};
  splitting::ParticleMerging walled({0.5}, {wall});
  s.merge(walled);
  CHECK(s.p.fluid_count() == 2);
  s.merge(effect);
  CHECK(s.p.fluid_count() == 1);
}

TEST_CASE("a merged particle's reference area is the mean of the pair's", "[merging]") {
  Scene s;
  s.add(0.0, 0.0, 0.3, 0.001);
  s.add(0.05, 0.0, 0.3, 0.003);
  s.p.initial_area[1] = 0.02;  // the same area, 0.003 m^2, is 0.15 of this A_0
  splitting::ParticleMerging effect({0.5}, {});
  s.merge(effect);
  REQUIRE(s.p.fluid_count() == 1);
  CHECK(s.p.initial_area[0] == Approx(0.015));
  CHECK(s.p.area[0] < 0.5 * 2.0 * s.p.initial_area[0]);
}

TEST_CASE("a particle merges with its nearest partner, once per step", "[merging]") {
  Scene s;
  // Three in a row: b is nearer to c than to a. a (the lowest index) goes first and takes
  // its nearest, b; c is left, though it is within reach of b.
  s.add(0.0, 0.0, 0.3);   // a
  s.add(0.05, 0.0, 0.3);  // b
  s.add(0.09, 0.0, 0.3);  // c
  s.add(0.5, 0.5, 0.3);   // alone
  splitting::ParticleMerging effect({0.5}, {});
  s.merge(effect);
  REQUIRE(s.p.fluid_count() == 3);
  CHECK(s.p.x[0] == Approx(0.025));
  CHECK(s.p.x[1] == 0.09);
  CHECK(s.p.x[2] == 0.5);
  CHECK(s.p.area[0] == Approx(0.006));
  // The next step, c joins the merged pair: 0.9 A_0 of the two particles' 2 A_0 together.
  s.merge(effect);
  REQUIRE(s.p.fluid_count() == 2);
  CHECK(s.p.area[0] == Approx(0.009));
  CHECK(s.p.x[0] == Approx((0.025 * 2.0 + 0.09) / 3.0));
  // Nothing is small enough any more.
  s.merge(effect);
  CHECK(s.p.fluid_count() == 2);
  CHECK(effect.merges() == 2);
  CHECK(effect.report() == "2 merges");
}

TEST_CASE("merging a crowd conserves volume and momentum and halves it", "[merging]") {
  Scene s;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002), volume(0.001, 0.004),
      speed(-2.0, 2.0);
  // 20 x 20 particles 0.03 m apart, each at 0.25 A_0 (radius 0.065 m): every one a candidate
  // with four partners within reach.
  for (int k = 0; k < 20; ++k)
    for (int i = 0; i < 20; ++i)
      s.add(0.03 * i + jitter(random), 0.03 * k + jitter(random), 0.25, volume(random),
            speed(random), speed(random));
  const auto totals = [&s] {
    std::array<double, 5> t{};  // volume, momentum x and y, centre of volume x and y
    for (std::size_t i = 0; i < s.p.fluid_count(); ++i) {
      t[0] += s.p.volume[i];
      t[1] += s.p.volume[i] * s.p.u[i];
      t[2] += s.p.volume[i] * s.p.v[i];
      t[3] += s.p.volume[i] * s.p.x[i];
      t[4] += s.p.volume[i] * s.p.y[i];
    }
    return t;
  };
  const auto before = totals();
  splitting::ParticleMerging effect({0.5}, {});
  s.merge(effect);
  const auto after = totals();
  // Nearly every particle finds a partner; a greedy pairing leaves a few alone where all
  // their neighbours are taken (measured: 199 pairs, 2 alone).
  CHECK(effect.merges() >= 190);
  CHECK(s.p.fluid_count() == 400 - effect.merges());
  CHECK(after[0] == Approx(before[0]).epsilon(1e-14));
  CHECK(after[1] == Approx(before[1]).epsilon(1e-13));
  CHECK(after[2] == Approx(before[2]).epsilon(1e-13));
  CHECK(after[3] == Approx(before[3]).epsilon(1e-14));
  CHECK(after[4] == Approx(before[4]).epsilon(1e-14));
  for (std::size_t i = 0; i < s.p.fluid_count(); ++i) CHECK(s.p.area[i] < 0.01);
}

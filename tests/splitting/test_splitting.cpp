// Tests of dynamic particle splitting: the split direction (appendix A), conservation of
// volume and momentum, and that no daughter lands behind a wall.

#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/splitting/particle_splitting.hpp"
#include "swemps/swe/effect.hpp"

using namespace swemps;
using splitting::MomentMatrix;
using splitting::split_direction;

namespace {

// Particles plus everything a StepContext needs, with a brute-force neighbour list.
struct Scene {
  particles::SweParticles p;
  neighbors::NeighborList nl;
  // The seed scheme's kernel at one radius for all, r_e = 0.13 m.
  static constexpr double radius = 0.13;
  swe::ParticleKernel kernel{swe::KernelShape::spiky};
  std::vector<double> ax, ay;
  swe::Settings settings;
  swe::VolumeLedger ledger;

  void add(double x, double y, double u = 0.0, double v = 0.0, double volume = 0.0025,
           double area = 0.01, double initial_area = 0.01) {
    p.add_fluid(x, y, u, v, volume, volume / area, initial_area, 0.0);
    p.area.back() = area;
    p.smoothing_length.back() = radius;
  }
  void link() {
    nl = neighbors::brute_force_neighbors<2>(
        {std::span<const double>(p.x), std::span<const double>(p.y)}, p.fluid_count(),
        swe::ParticleKernel::support(radius));
    ax.assign(p.fluid_count(), 0.0);
    ay.assign(p.fluid_count(), 0.0);
  }
  void split(splitting::ParticleSplitting& effect) {
    link();
    swe::StepContext context{p, nl, kernel, ax, ay, settings, ledger, 0.0, 0.0};
    effect.apply(context);
  }
};

double parallelism(std::array<double, 2> t, std::array<double, 2> expected) {
  const double len = std::hypot(expected[0], expected[1]);
  return std::abs(t[0] * expected[0] + t[1] * expected[1]) / len;  // |cos| of the angle
}

// A lattice of spacing 0.1 around the origin, with a linear velocity and depth field.
Scene lattice_with_gradients(int half_width, double initial_area) {
  Scene s;
  for (int k = -half_width; k <= half_width; ++k)
    for (int i = -half_width; i <= half_width; ++i) {
      const double x = 0.1 * i, y = 0.1 * k;
      const double h = 0.25 + 0.05 * x - 0.02 * y;
      s.p.add_fluid(x, y, 1.0 + 0.5 * x + 0.2 * y, -0.3 + 0.1 * x, h * 0.01, h, initial_area, 0.0);
      s.p.area.back() = 0.01;  // A = V / h
      s.p.smoothing_length.back() = Scene::radius;
    }
  return s;
}

}  // namespace

TEST_CASE("split direction: eigenvector of the larger or the smaller eigenvalue", "[splitting]") {
  using splitting::SplitAxis;
  for (const auto axis : {SplitAxis::major, SplitAxis::minor}) {
    // The minor axis is the major one turned by 90 degrees.
    auto expect = [axis](std::array<double, 2> major) {
      return axis == SplitAxis::major ? major : std::array<double, 2>{-major[1], major[0]};
    };
    CHECK(parallelism(split_direction({4.0, 0.0, 1.0}, axis), expect({1, 0})) == Approx(1.0));
    CHECK(parallelism(split_direction({1.0, 0.0, 4.0}, axis), expect({0, 1})) == Approx(1.0));
    CHECK(parallelism(split_direction({2.0, 2.0, 2.0}, axis), expect({1, 1})) == Approx(1.0));
    CHECK(parallelism(split_direction({2.0, -2.0, 2.0}, axis), expect({1, -1})) == Approx(1.0));
    // A general matrix: check the eigen-equation C t = lambda t directly.
    const MomentMatrix c{3.0, 1.2, 0.5};
    const auto t = split_direction(c, axis);
    const double root = std::sqrt(2.5 * 2.5 + 4 * 1.2 * 1.2);
    const double lambda = 0.5 * (3.5 + (axis == SplitAxis::major ? root : -root));
    CHECK(c.xx * t[0] + c.xy * t[1] == Approx(lambda * t[0]));
    CHECK(c.xy * t[0] + c.yy * t[1] == Approx(lambda * t[1]));
    CHECK(std::hypot(t[0], t[1]) == Approx(1.0));
    // Isotropic: any direction is right; the answer must still be a unit vector.
    const auto iso = split_direction({1.0, 0.0, 1.0}, axis);
    CHECK(std::hypot(iso[0], iso[1]) == Approx(1.0));
  }
}

TEST_CASE("split direction from hand-made neighbour sets", "[splitting]") {
  using splitting::SplitAxis;
  auto direction_of = [](const std::vector<std::array<double, 2>>& neighbours, SplitAxis axis) {
    Scene s;
    s.add(0.0, 0.0);
    for (const auto& q : neighbours) s.add(q[0], q[1]);
    s.link();
    return split_direction(splitting::moment_matrix(s.p, s.nl, s.kernel, 0), axis);
  };
  const double d = 0.08;
  // Neighbours spread along x (a row), along y (a column), along the diagonal: the major axis
  // follows them, the minor axis points across.
  const std::vector<std::array<double, 2>> row{
      {d, 0}, {-d, 0}, {2 * d, 0}, {-2 * d, 0}, {0, 0.5 * d}};
  const std::vector<std::array<double, 2>> column{
      {0, d}, {0, -d}, {0, 2 * d}, {0, -2 * d}, {0.5 * d, 0}};
  const std::vector<std::array<double, 2>> diagonal{
      {d, d}, {-d, -d}, {2 * d, 2 * d}, {0.3 * d, -0.3 * d}};
  CHECK(parallelism(direction_of(row, SplitAxis::major), {1, 0}) == Approx(1.0));
  CHECK(parallelism(direction_of(row, SplitAxis::minor), {0, 1}) == Approx(1.0));
  CHECK(parallelism(direction_of(column, SplitAxis::major), {0, 1}) == Approx(1.0));
  CHECK(parallelism(direction_of(column, SplitAxis::minor), {1, 0}) == Approx(1.0));
  CHECK(parallelism(direction_of(diagonal, SplitAxis::major), {1, 1}) == Approx(1.0));
  CHECK(parallelism(direction_of(diagonal, SplitAxis::minor), {1, -1}) == Approx(1.0));
  // A particle at the head of a front moving in +x: neighbours beside it in its row (spacing
  // 0.1) and a row behind that has fallen back by 1.5 spacings, nothing ahead. The major axis
  // lies along the front (y); the minor axis points into the gap along the flow (x), the
  // direction the default splits in (docs/splitting.md).
  const std::vector<std::array<double, 2>> front{{0, 0.1},   {0, -0.1},    {0, 0.2},     {0, -0.2},
                                                 {-0.15, 0}, {-0.15, 0.1}, {-0.15, -0.1}};
  CHECK(parallelism(direction_of(front, SplitAxis::major), {0, 1}) == Approx(1.0));
  CHECK(parallelism(direction_of(front, SplitAxis::minor), {1, 0}) == Approx(1.0));
  // A ring of eight: the moment matrix is a multiple of the identity.
  std::vector<std::array<double, 2>> ring;
  for (int k = 0; k < 8; ++k)
    ring.push_back({d * std::cos(k * M_PI / 4), d * std::sin(k * M_PI / 4)});
  Scene s;
  s.add(0.0, 0.0);
  for (const auto& q : ring) s.add(q[0], q[1]);
  s.link();
  const auto c = splitting::moment_matrix(s.p, s.nl, s.kernel, 0);
  CHECK(c.xx == Approx(c.yy).epsilon(1e-12));
  CHECK(std::abs(c.xy) < 1e-12 * c.xx);
}

TEST_CASE("a single split conserves volume exactly and momentum to round-off", "[splitting]") {
  // Only the centre particle is over the threshold (its reference area is small).
  auto s = lattice_with_gradients(3, 0.01);
  const std::size_t centre = 24;  // (0, 0) in a 7 x 7 lattice
  REQUIRE(s.p.x[centre] == 0.0);
  REQUIRE(s.p.y[centre] == 0.0);
  s.p.initial_area[centre] = 0.005;
  const double volume = s.p.total_fluid_volume();
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < s.p.fluid_count(); ++i) {
    mx += s.p.volume[i] * s.p.u[i];
    my += s.p.volume[i] * s.p.v[i];
  }
  const double area = s.p.area[centre];
  const double parent_volume = s.p.volume[centre];
  splitting::ParticleSplitting effect({}, {});
  s.split(effect);
  REQUIRE(effect.splits() == 1);
  REQUIRE(s.p.fluid_count() == 50);
  // The parent's volume is shared out exactly (no rounding); the total differs at most by
  // the order of summation.
  const std::size_t b = 49;
  CHECK(s.p.volume[centre] + s.p.volume[b] == parent_volume);
  CHECK(s.p.total_fluid_volume() == Approx(volume).epsilon(1e-15));
  double mx2 = 0.0, my2 = 0.0;
  for (std::size_t i = 0; i < s.p.fluid_count(); ++i) {
    mx2 += s.p.volume[i] * s.p.u[i];
    my2 += s.p.volume[i] * s.p.v[i];
  }
  CHECK(mx2 == Approx(mx).epsilon(1e-14));
  CHECK(my2 == Approx(my).epsilon(1e-14));
  // eq 10: daughters alpha_s sqrt(A) apart, symmetric about the parent, halving its area.
  CHECK(std::hypot(s.p.x[centre] - s.p.x[b], s.p.y[centre] - s.p.y[b]) ==
        Approx(0.7 * std::sqrt(area)));
  CHECK(s.p.x[centre] + s.p.x[b] == Approx(0.0).margin(1e-15));
  CHECK(s.p.y[centre] + s.p.y[b] == Approx(0.0).margin(1e-15));
  CHECK(s.p.area[b] == Approx(area / 2));
  CHECK(s.p.initial_area[b] == s.p.initial_area[centre]);  // the scene's resolution is kept
  // Both daughters are first searched with the parent's radius (the depth iteration then
  // finds each one's own): the radius of half the area could be too short a search.
  CHECK(s.p.smoothing_length[centre] == Scene::radius);
  CHECK(s.p.smoothing_length[b] == Scene::radius);
  // eq 12: on the daughters' line the velocity differs by the gradient times the offset; the
  // field is u = 1 + 0.5 x + 0.2 y, exactly represented by eq 6 on a symmetric lattice.
  const double dx = s.p.x[centre] - s.p.x[b], dy = s.p.y[centre] - s.p.y[b];
  CHECK(s.p.u[centre] - s.p.u[b] == Approx(0.5 * dx + 0.2 * dy).epsilon(1e-9));
  // The deeper side (h grows with x, falls with y) gets the larger volume.
  const double deeper = 0.05 * dx - 0.02 * dy;
  CHECK((s.p.volume[centre] - s.p.volume[b]) * deeper > 0.0);
}

TEST_CASE("splitting in bulk conserves volume exactly and momentum to round-off", "[splitting]") {
  auto s = lattice_with_gradients(10, 0.001);  // every particle far over the threshold
  const std::size_t n = s.p.fluid_count();
  const double volume = s.p.total_fluid_volume();
  const std::vector<double> parent_volume = s.p.volume;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += s.p.volume[i] * s.p.u[i];
    my += s.p.volume[i] * s.p.v[i];
  }
  splitting::ParticleSplitting effect({}, {});
  s.split(effect);
  REQUIRE(effect.splits() == n);
  REQUIRE(s.p.fluid_count() == 2 * n);
  for (std::size_t i = 0; i < n; ++i) CHECK(s.p.volume[i] + s.p.volume[n + i] == parent_volume[i]);
  double mx2 = 0.0, my2 = 0.0;
  for (std::size_t i = 0; i < 2 * n; ++i) {
    mx2 += s.p.volume[i] * s.p.u[i];
    my2 += s.p.volume[i] * s.p.v[i];
    CHECK(s.p.volume[i] > 0.0);
  }
  // Each parent's volume is split exactly; the totals differ only by summation order.
  CHECK(s.p.total_fluid_volume() == Approx(volume).epsilon(1e-15));
  CHECK(mx2 == Approx(mx).epsilon(1e-14));
  CHECK(my2 == Approx(my).epsilon(1e-14));
}

TEST_CASE("the particle cap stops splitting", "[splitting]") {
  auto s = lattice_with_gradients(3, 0.001);
  splitting::SplittingSettings settings;
  settings.max_particles = 55;
  splitting::ParticleSplitting effect(settings, {});
  s.split(effect);
  CHECK(s.p.fluid_count() == 55);
  CHECK(effect.refused_at_cap() == 49 - 6);
}

TEST_CASE("a daughter never lands behind a wall", "[splitting][boundaries]") {
  // A column of particles next to the wall x = 0 (neighbours spread along x, towards the
  // wall), each 0.02 m from it: splitting along x would put a daughter behind it.
  const boundaries::WallSegment wall{{0.0, -1.0}, {0.0, 1.0}, boundaries::WallCondition::slip};
  Scene s;
  for (int i = 0; i < 5; ++i) s.add(0.02 + 0.05 * i, 0.0, 0.0, 0.0, 0.0025, 0.01, 0.001);
  splitting::ParticleSplitting effect({}, {wall});
  s.split(effect);
  CHECK(effect.splits() + effect.refused_at_walls() == 5);
  CHECK(effect.splits() > 0);
  for (std::size_t i = 0; i < s.p.fluid_count(); ++i) CHECK(s.p.x[i] > 0.0);
  // The particle nearest the wall was split along the wall instead.
  CHECK(s.p.x[0] == Approx(0.02));
}

TEST_CASE("no split of a film below the depth floor, nor of a particle at the radius cap",
          "[splitting]") {
  // Every particle has grown to ten times its A_0 (0.001); each one's volume over A_0 is
  // ten times its depth, 2.29 to 2.71 m across the lattice.
  auto s = lattice_with_gradients(3, 0.001);
  const std::size_t n = s.p.fluid_count();
  SECTION("the depth floor") {
    splitting::SplittingSettings settings;
    settings.min_depth_m = 2.5;
    std::size_t above = 0;
    for (std::size_t i = 0; i < n; ++i) above += s.p.volume[i] >= 2.5 * s.p.initial_area[i];
    REQUIRE(above > 0);
    REQUIRE(above < n);
    splitting::ParticleSplitting effect(settings, {});
    s.split(effect);
    CHECK(effect.splits() == above);
  }
  SECTION("the radius cap") {
    splitting::SplittingSettings settings;
    settings.radius_cap_area_ratio = 8.0;  // A = 10 A_0: past it
    splitting::ParticleSplitting capped(settings, {});
    s.split(capped);
    CHECK(capped.splits() == 0);
    settings.radius_cap_area_ratio = 12.0;
    splitting::ParticleSplitting below(settings, {});
    s.split(below);
    CHECK(below.splits() == n);
  }
}

#include <catch2/catch.hpp>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "swemps/particles/swe_particles.hpp"

using swemps::particles::SweParticles;

namespace {

// Particle i gets field values that differ per field and per particle, so any
// misalignment between fields after a permutation shows up as a wrong value.
void add_tagged(SweParticles& p, int i) {
  const double b = 100.0 * i;
  p.add_fluid(b + 1, b + 2, b + 3, b + 4, b + 5, b + 6, b + 7, b + 8);
}

// Checks that index k holds the fields of tagged particle `tag`.
void require_tagged(const SweParticles& p, std::size_t k, int tag) {
  const double b = 100.0 * tag;
  CHECK(p.x[k] == b + 1);
  CHECK(p.y[k] == b + 2);
  CHECK(p.u[k] == b + 3);
  CHECK(p.v[k] == b + 4);
  CHECK(p.volume[k] == b + 5);
  CHECK(p.depth[k] == b + 6);
  CHECK(p.area[k] == b + 7);
  CHECK(p.initial_area[k] == b + 7);
  CHECK(p.bed[k] == b + 8);
}

void require_sizes(const SweParticles& p, std::size_t n) {
  CHECK(p.size() == n);
  CHECK(p.x.size() == n);
  CHECK(p.y.size() == n);
  CHECK(p.u.size() == n);
  CHECK(p.v.size() == n);
  CHECK(p.volume.size() == n);
  CHECK(p.depth.size() == n);
  CHECK(p.area.size() == n);
  CHECK(p.initial_area.size() == n);
  CHECK(p.bed.size() == n);
  CHECK(p.number_density.size() == n);
  CHECK(p.source.size() == n);
}

SweParticles make_tagged(int n) {
  SweParticles p;
  for (int i = 0; i < n; ++i) add_tagged(p, i);
  return p;
}

}  // namespace

TEST_CASE("SweParticles add_fluid fills every field", "[particles]") {
  SweParticles p = make_tagged(3);
  require_sizes(p, 3);
  CHECK(p.fluid_count() == 3);
  CHECK(p.ghost_count() == 0);
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    require_tagged(p, k, i);
    CHECK(p.number_density[k] == 0.0);
    CHECK(p.source[k] == static_cast<std::uint32_t>(i));
  }
}

TEST_CASE("SweParticles ghosts copy their source and are dropped", "[particles]") {
  SweParticles p = make_tagged(3);
  p.number_density[1] = 42.0;
  p.area[1] = 9.5;  // a changed area must be copied, not the initial one

  p.add_ghost(1, -1.0, -2.0, -3.0, -4.0);
  p.add_ghost(0, -5.0, -6.0, -7.0, -8.0);
  require_sizes(p, 5);
  CHECK(p.fluid_count() == 3);
  CHECK(p.ghost_count() == 2);

  CHECK(p.x[3] == -1.0);
  CHECK(p.y[3] == -2.0);
  CHECK(p.u[3] == -3.0);
  CHECK(p.v[3] == -4.0);
  CHECK(p.volume[3] == 105.0);
  CHECK(p.depth[3] == 106.0);
  CHECK(p.area[3] == 9.5);
  CHECK(p.initial_area[3] == 107.0);
  CHECK(p.bed[3] == 108.0);
  CHECK(p.number_density[3] == 42.0);
  CHECK(p.source[3] == 1);
  CHECK(p.x[4] == -5.0);
  CHECK(p.volume[4] == 5.0);
  CHECK(p.source[4] == 0);

  SECTION("the fluid block is unaffected and ghosts are not counted as fluid volume") {
    require_tagged(p, 0, 0);
    CHECK(p.total_fluid_volume() == 5.0 + 105.0 + 205.0);
  }
  SECTION("drop_ghosts truncates to the fluid particles") {
    p.drop_ghosts();
    require_sizes(p, 3);
    CHECK(p.ghost_count() == 0);
    for (int i = 0; i < 3; ++i)
      CHECK(p.source[static_cast<std::size_t>(i)] == static_cast<std::uint32_t>(i));
    add_tagged(p, 3);  // fluid may be added again once ghosts are gone
    CHECK(p.fluid_count() == 4);
  }
  SECTION("operations that need a ghost-free store refuse") {
    CHECK_THROWS_AS(p.add_fluid(0, 0, 0, 0, 1, 1, 1, 0), std::logic_error);
    const std::vector<std::uint32_t> order{2, 1, 0};
    CHECK_THROWS_AS(p.reorder(order), std::logic_error);
    const std::vector<std::uint8_t> flags(3, 0);
    CHECK_THROWS_AS(p.remove(flags), std::logic_error);
    require_sizes(p, 5);
  }
}

TEST_CASE("SweParticles add_ghost rejects a non-fluid source", "[particles]") {
  SweParticles p = make_tagged(2);
  CHECK_THROWS(p.add_ghost(2, 0, 0, 0, 0));
  p.add_ghost(0, 0, 0, 0, 0);
  CHECK_THROWS(p.add_ghost(2, 0, 0, 0, 0));  // index 2 is now a ghost
}

TEST_CASE("SweParticles reorder permutes all fields together", "[particles]") {
  SweParticles p = make_tagged(5);
  p.number_density = {10, 11, 12, 13, 14};
  const std::vector<std::uint32_t> order{3, 0, 4, 1, 2};
  p.reorder(order);
  require_sizes(p, 5);
  CHECK(p.fluid_count() == 5);
  for (std::size_t k = 0; k < order.size(); ++k) {
    require_tagged(p, k, static_cast<int>(order[k]));
    CHECK(p.number_density[k] == 10.0 + order[k]);
    CHECK(p.source[k] == k);
  }
}

TEST_CASE("SweParticles reorder rejects a bad order", "[particles]") {
  SweParticles p = make_tagged(3);
  const std::vector<std::uint32_t> short_order{0, 1};
  CHECK_THROWS_AS(p.reorder(short_order), std::logic_error);
  const std::vector<std::uint32_t> repeated{0, 0, 1};
  CHECK_THROWS_AS(p.reorder(repeated), std::logic_error);
  const std::vector<std::uint32_t> out_of_range{0, 1, 3};
  CHECK_THROWS_AS(p.reorder(out_of_range), std::logic_error);
  for (int i = 0; i < 3; ++i) require_tagged(p, static_cast<std::size_t>(i), i);
}

TEST_CASE("SweParticles remove keeps the order of the survivors", "[particles]") {
  SweParticles p = make_tagged(6);
  p.number_density = {10, 11, 12, 13, 14, 15};
  const std::vector<std::uint8_t> flags{1, 0, 0, 1, 0, 1};
  p.remove(flags);
  require_sizes(p, 3);
  CHECK(p.fluid_count() == 3);
  const int survivors[] = {1, 2, 4};
  for (std::size_t k = 0; k < 3; ++k) {
    require_tagged(p, k, survivors[k]);
    CHECK(p.number_density[k] == 10.0 + survivors[k]);
    CHECK(p.source[k] == k);
  }

  SECTION("a flag vector of the wrong size is refused") {
    const std::vector<std::uint8_t> wrong(4, 0);
    CHECK_THROWS_AS(p.remove(wrong), std::logic_error);
    require_sizes(p, 3);
  }
  SECTION("removing everything leaves an empty store") {
    const std::vector<std::uint8_t> all(3, 1);
    p.remove(all);
    require_sizes(p, 0);
    CHECK(p.fluid_count() == 0);
    CHECK(p.total_fluid_volume() == 0.0);
  }
}

TEST_CASE("SweParticles total_fluid_volume sums in index order", "[particles]") {
  SweParticles p;
  CHECK(p.total_fluid_volume() == 0.0);
  const double volumes[] = {0.1, 0.2, 0.3, 1e-17, 5.0};
  double expected = 0.0;
  for (double vol : volumes) {
    p.add_fluid(0, 0, 0, 0, vol, 1, vol, 0);
    expected += vol;
  }
  CHECK(p.total_fluid_volume() == expected);  // exact: same order, same rounding
}

// The memory a scene asks for, counted before anything is allocated: particles from the water's
// area and spacing, splitting's headroom, the output grid's cells; and the refusal of a scene
// that needs more than the machine has, at the key to change, with the numbers.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "../support/broken_scenes.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/memory_check.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

using Catch::Matchers::Contains;
using swemps::scenario::MemoryNeed;
using swemps::scenario::ScenarioError;
using swemps::testing::parse_text;

// 10 m x 1 m of water at 0.1 m (1,000 particles) and a triangle of 2 m^2 at 0.2 m (50), on a
// 0.5 m grid over a 20 m x 2 m domain (160 cells).
const std::string kTwoBodies = R"({
  "end_time": 1,
  "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 2},
  "water": [
    {"rectangle": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1}, "depth": 0.1,
     "spacing": 0.1},
    {"polygon": [[12, 0], [14, 0], [12, 2]], "depth": 0.1, "spacing": 0.2}
  ],
  "output": {"grid": {"spacing": 0.5}}
})";

MemoryNeed need_of(const std::string& text) {
  const auto scene = parse_text(text);
  swemps::scenario::Terrain terrain;
  terrain.domain = scene.domain;
  return swemps::scenario::swe_memory_need(scene, terrain);
}

std::string with_splitting(const std::string& splitting) {
  std::string text = kTwoBodies;
  text.insert(text.rfind('}'), ", \"splitting\": " + splitting);
  return text;
}

}  // namespace

TEST_CASE("a scene's memory is counted from its water, spacing and grid", "[scenario][memory]") {
  const MemoryNeed need = need_of(kTwoBodies);
  CHECK(need.particles == Approx(1050.0));
  CHECK(need.peak_particles == need.particles);
  CHECK(need.grid_cells == 160.0);
  CHECK(need.bytes() == Approx(1050.0 * swemps::scenario::kBytesPerParticle +
                               160.0 * swemps::scenario::bytes_per_grid_cell(4)));
  // The first body asks for most: its spacing is the key to change.
  CHECK(need.json_path == "/water/0/spacing");
  CHECK_THAT(need.largest_share, Contains("1000 particles of /water/0 at a spacing of 0.1 m"));
}

TEST_CASE("splitting adds its headroom: the cap, or a doubling without one", "[scenario][memory]") {
  CHECK(need_of(with_splitting("{}")).peak_particles ==
        Approx(swemps::scenario::kSplittingGrowth * 1050.0));
  CHECK(need_of(with_splitting(R"({"max_particles": 5000})")).peak_particles == 5000.0);
  // A cap below the starting count caps nothing at the start.
  CHECK(need_of(with_splitting(R"({"max_particles": 10})")).peak_particles == Approx(1050.0));
}

TEST_CASE("a scene that needs more than the machine has is refused with the numbers",
          "[scenario][memory]") {
  const MemoryNeed need = need_of(with_splitting("{}"));
  const auto needed = static_cast<std::uint64_t>(std::ceil(need.bytes()));
  CHECK_NOTHROW(swemps::scenario::check_fits_in_memory(need, needed));
  CHECK_NOTHROW(swemps::scenario::check_fits_in_memory(need, 0));  // unknown: no refusal
  try {
    swemps::scenario::check_fits_in_memory(need, needed / 2);
    FAIL("a scene twice the memory was not refused");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path() == "/water/0/spacing");
    const std::string message = e.what();
    CHECK_THAT(message, Contains("about 1050 particles (2100 with splitting's headroom)"));
    CHECK_THAT(message, Contains("160 output grid cells, needing about 2.13 MB"));
    CHECK_THAT(message, Contains("fits in the 1.07 MB of memory swe-mps may use here"));
  }
}

TEST_CASE("the output grid is blamed when it asks for most", "[scenario][memory]") {
  std::string text = kTwoBodies;
  text.replace(text.find("\"spacing\": 0.5"), 14, "\"spacing\": 0.001");
  const MemoryNeed need = need_of(text);
  CHECK(need.grid_cells == Approx(4e7));
  CHECK(need.json_path == "/output/grid");
  CHECK_THAT(need.largest_share, Contains("4e+07 cells of the output grid (0.001 m x 0.001 m)"));
}

TEST_CASE("a Navier-Stokes tank counts its fluid, wall and dummy particles", "[scenario][memory]") {
  // A 3D tank 1 m x 0.5 m x 0.5 m high at 0.05 m: 20 x 10 x 10 interior nodes; 3 solid layers
  // around the sides and below give 26 x 16 x 13 nodes in the box. Water 0.5 m x 0.5 m x 0.2 m
  // deep: 10 x 10 x 4 fluid nodes.
  const auto scene = parse_text(R"({
    "end_time": 0.1, "model": "ns", "ns": {"spacing": 0.05, "tank_height": 0.5},
    "domain": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 0.5},
    "water": [{"rectangle": {"x_min": 0, "x_max": 0.5, "y_min": 0, "y_max": 0.5}, "depth": 0.2}]
  })");
  const auto tank = swemps::scenario::ns_tank<3>(scene);
  const MemoryNeed need = swemps::scenario::ns_memory_need<3>(scene, tank);
  CHECK(need.particles == Approx(400.0 + 26.0 * 16.0 * 13.0 - 2000.0));
  CHECK(need.json_path == "/ns/spacing");
}

TEST_CASE("the machine's memory is found", "[scenario][memory]") {
  // Linux always tells; a machine with less than a megabyte runs nothing.
  CHECK(swemps::scenario::usable_memory_bytes() > 1'000'000u);
}

TEST_CASE("bytes read in decimal units", "[scenario][memory]") {
  CHECK(swemps::scenario::bytes_text(512) == "512 B");
  CHECK(swemps::scenario::bytes_text(2.53e10) == "25.3 GB");
  CHECK(swemps::scenario::bytes_text(1.1e16) == "11 PB");
}

// The pilot scene `swe-mps check` runs: every particle spacing widened by the factor, a
// splitting cap divided by its square, nothing else changed; a tank that the wider spacing
// cannot tile is refused.

#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "../support/broken_scenes.hpp"
#include "swemps/scenario/coarsen.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

using swemps::scenario::coarsened;
using swemps::scenario::ScenarioError;
using swemps::testing::parse_text;

const std::string kFlood = R"({
  "end_time": 100,
  "domain": {"x_min": 0, "x_max": 200, "y_min": 0, "y_max": 40},
  "water": [{"rectangle": {"x_min": 0, "x_max": 50, "y_min": 0, "y_max": 40}, "depth": 1,
             "spacing": 2}],
  "inflow": [{"name": "west", "line": [[0, 10], [0, 30]], "hydrograph": [[0, 5], [100, 5]],
              "spacing": 4, "depth": 0.5}],
  "splitting": {"max_particles": 1000},
  "friction": {"manning_n": 0.03},
  "output": {"path": "out.nc", "interval": 50}
})";

}  // namespace

TEST_CASE("a coarsened scene widens every spacing and keeps the rest", "[scenario][coarsen]") {
  const auto scene = parse_text(kFlood);
  const auto coarse = coarsened(scene, 3);
  CHECK(coarse.water.at(0).spacing_m == 6.0);
  CHECK(coarse.inflows.at(0).spacing_m == 12.0);
  // 1000 / 9, rounded up: the cap stops splitting at the same share of the water.
  CHECK(coarse.splitting->max_particles == 112);
  CHECK(coarse.end_time_s == scene.end_time_s);
  CHECK(coarse.inflows.at(0).depth_m == scene.inflows.at(0).depth_m);
  CHECK(coarse.water.at(0).polygon == scene.water.at(0).polygon);
  CHECK(coarse.output.times_s == scene.output.times_s);

  const auto same = coarsened(scene, 1);
  CHECK(same.water.at(0).spacing_m == 2.0);
  CHECK(same.splitting->max_particles == 1000);
  CHECK_THROWS_AS(coarsened(scene, 0), std::invalid_argument);
}

TEST_CASE("a coarsened tank keeps whole spacings or is refused", "[scenario][coarsen]") {
  // 0.4 m long and 0.2 m high at 0.01 m: 2 and 4 divide 40 and 20, 3 does not.
  const auto tank = parse_text(R"({
    "end_time": 0.1, "model": "ns", "dimension": 2,
    "ns": {"spacing": 0.01, "tank_height": 0.2},
    "domain": {"x_min": 0, "x_max": 0.4, "y_min": 0, "y_max": 0.1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 0.1, "y_min": 0, "y_max": 0.1},
               "depth": 0.1}],
    "output": {"path": "tank.nc"}})");
  CHECK(coarsened(tank, 2).ns->settings.spacing_m == Approx(0.02));
  CHECK(coarsened(tank, 4).ns->settings.spacing_m == Approx(0.04));
  CHECK_THROWS_AS(coarsened(tank, 3), ScenarioError);
}

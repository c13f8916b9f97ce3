// The shipped urban case (cases/urban-block, docs/buildings.md) through its storm's rise: the
// first 7 minutes, while rain makes the particles, they run off the roofs' edges into the
// streets and the first water leaves the block. No particle may ever stand inside a house,
// rain must fall on the ground only, and every drop that reached the water must be in it or
// have left (the volume ledger to round-off).

#include <catch2/catch.hpp>
#include <filesystem>

#include "swemps/hydrology/rain.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace fs = std::filesystem;

TEST_CASE("urban block: the storm's rise keeps out of the houses and loses no water",
          "[verification][buildings]") {
  const auto scene =
      swemps::scenario::load(fs::path(SWEMPS_SOURCE_DIR) / "cases/urban-block/scenario.json");
  auto built = swemps::scenario::build(scene);
  const auto& houses = *built.terrain.building_footprints;
  REQUIRE(houses.size() == 246);
  REQUIRE(built.terrain.building_walls.size() == 4 * 246);
  auto& sim = built.simulation;
  const swemps::hydrology::Rain* rain = nullptr;
  for (const auto& e : sim.effects()) {
    if (!rain) rain = dynamic_cast<const swemps::hydrology::Rain*>(e.get());
  }
  REQUIRE(rain);
  // 120 x 120 cells of 2.5 m; those whose centres lie under a roof get no rain.
  std::size_t roof_cells = 0;
  for (std::size_t k = 0; k < 120 * 120; ++k) {
    const double x = 755000.0 + 2.5 * (static_cast<double>(k % 120) + 0.5);
    const double y = 4043500.0 + 2.5 * (static_cast<double>(k / 120) + 0.5);
    roof_cells += houses.contains(x, y) ? 1 : 0;
  }
  CHECK(roof_cells > 2000);
  CHECK(rain->cell_count() == 120 * 120 - roof_cells);

  std::size_t inside = 0, checks = 0;
  while (sim.time() < 420.0) {
    sim.step_towards(420.0);
    const auto& p = sim.particles();
    for (std::size_t i = 0; i < p.fluid_count(); ++i) inside += houses.contains(p.x[i], p.y[i]);
    ++checks;
  }
  CHECK(checks > 100);
  CHECK(inside == 0);
  const auto& ledger = sim.ledger();
  CHECK(ledger.rain_m3 > 100.0);
  CHECK(ledger.removed_m3 > 0.0);
  CHECK(sim.fluid_volume() == Approx(ledger.expected_m3()).epsilon(1e-12));
  CHECK(rain->volume_added() == Approx(ledger.rain_m3).epsilon(1e-12));
}

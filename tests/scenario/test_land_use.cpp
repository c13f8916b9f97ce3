// Land use as the roughness: a raster of classes and a table of each class's Manning's n,
// turned by build into the roughness map the friction samples; one-line errors for a class
// the table lacks and for a table that is not one.

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::scenario::ScenarioError;

namespace {

// 20 m x 10 m of 1 m cells: class 1 (grass) west of x = 10 m, 2 (road) east of it, and class 9
// in the cells east of x = 19 m when `stray` (the domain's last column).
void write_classes(const std::filesystem::path& path, bool stray) {
  swemps::io::write_geotiff(swemps::testing::sampled_field(20, 10, 1.0,
                                                           [&](double x, double) {
                                                             if (stray && x > 19.0) return 9.0;
                                                             return x < 10.0 ? 1.0 : 2.0;
                                                           }),
                            path);
}

json land_use_scene(const json& friction) {
  json s = json::parse(R"({
    "name": "land-use", "end_time": 1,
    "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10},
    "water": [{"rectangle": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10},
               "depth": 0.5, "spacing": 1}],
    "output": {"path": "out.nc"}
  })");
  s["friction"] = friction;
  return s;
}

std::string refusal(const json& scene, const std::filesystem::path& base) {
  try {
    swemps::scenario::build(swemps::scenario::parse(scene.dump(), base, "land-use"));
  } catch (const ScenarioError& e) {
    return e.json_path() + " | " + e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("land use: each class's Manning's n from the table, over the class's cells",
          "[scenario][friction][land-use]") {
  swemps::testing::TempDir dir("land-use");
  write_classes(dir.path() / "classes.tif", false);
  const auto scene =
      swemps::scenario::parse(land_use_scene(json::parse(R"({"land_use_raster": "classes.tif",
                                     "land_use_manning_n": {"1": 0.035, "2": 0.015,
                                                            "7": 0.1}})"))
                                  .dump(),
                              dir.path(), "land-use");
  const auto& spec = std::get<swemps::scenario::LandUseSpec>(*scene.manning_n);
  CHECK(spec.manning_n.size() == 3);
  CHECK(spec.manning_n.at(2) == 0.015);
  auto built = swemps::scenario::build(scene);
  REQUIRE(built.terrain.roughness);
  const auto& n = *built.terrain.roughness;
  CHECK(n.sample(3.5, 5.5) == Approx(0.035));
  CHECK(n.sample(15.5, 5.5) == Approx(0.015));
  // Between the cell centres either side of the class boundary, n is linear, as any
  // roughness map's.
  CHECK(n.sample(10.0, 5.5) == Approx(0.025));
  bool friction = false;
  for (const auto& e : built.simulation.effects()) friction |= e->name() == "Manning friction";
  CHECK(friction);
}

TEST_CASE(
    "land use: a class the table lacks, and a table that is not one, are refused in one "
    "line",
    "[scenario][friction][land-use]") {
  swemps::testing::TempDir dir("land-use-bad");
  write_classes(dir.path() / "stray.tif", true);
  write_classes(dir.path() / "classes.tif", false);
  CHECK_THAT(refusal(land_use_scene(json::parse(R"({"land_use_raster": "stray.tif",
                                      "land_use_manning_n": {"1": 0.035, "2": 0.015}})")),
                     dir.path()),
             Contains("/friction/land_use_raster | ") && Contains("the land-use class 9") &&
                 Contains("the table lists 1, 2"));
  CHECK_THAT(refusal(land_use_scene(json::parse(R"({"land_use_raster": "classes.tif",
                                      "land_use_manning_n": {"grass": 0.035}})")),
                     dir.path()),
             Contains("/friction/land_use_manning_n/grass | "));
  CHECK_THAT(refusal(land_use_scene(json::parse(R"({"land_use_raster": "classes.tif",
                                      "land_use_manning_n": {"1": -0.035}})")),
                     dir.path()),
             Contains("/friction/land_use_manning_n/1 | "));
  CHECK_THAT(
      refusal(land_use_scene(json::parse(R"({"land_use_raster": "classes.tif"})")), dir.path()),
      Contains("/friction/land_use_manning_n | "));
  CHECK_THAT(refusal(land_use_scene(json::parse(R"({"manning_n": 0.03,
                                      "land_use_raster": "classes.tif",
                                      "land_use_manning_n": {"1": 0.035}})")),
                     dir.path()),
             Contains("/friction | ") && Contains("exactly one of"));
  CHECK_THAT(refusal(land_use_scene(json::parse(R"({"manning_n": 0.03,
                                      "land_use_manning_n": {"1": 0.035}})")),
                     dir.path()),
             Contains("/friction/land_use_manning_n | "));
}

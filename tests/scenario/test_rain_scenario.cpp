// The "rain" section of a scene: what it reads, its defaults, the one-line errors for bad
// rain, and the effect a built scene runs.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/temp_dir.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::scenario::ScenarioError;

namespace {

json rain_scene(const json& rain) {
  json s = json::parse(R"({
    "name": "rain-test", "end_time": 10,
    "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10},
    "output": {"path": "out.nc"}
  })");
  s["rain"] = rain;
  return s;
}

swemps::scenario::Scenario parse(const json& scene, const std::filesystem::path& base = ".") {
  return swemps::scenario::parse(scene.dump(), base, "rain-test");
}

// The error a scene is refused with: its path and message.
std::string refusal(const json& scene, const std::filesystem::path& base = ".") {
  try {
    swemps::scenario::build(parse(scene, base));
  } catch (const ScenarioError& e) {
    return e.json_path() + " | " + e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("a scene with rain and no water reads the rain and its defaults", "[scenario][rain]") {
  const auto s = parse(rain_scene(json::parse(R"({"rate_mm_h": 25, "spacing": 0.5})")));
  REQUIRE(s.rain.size() == 1);
  const auto& rain = s.rain.front();
  CHECK(rain.name == "rain");
  CHECK(rain.key_path == "/rain");
  const auto& rate = std::get<std::vector<std::array<double, 2>>>(rain.rate_mm_h);
  CHECK(rate == std::vector<std::array<double, 2>>{{0.0, 25.0}});
  CHECK(rain.spacing_m == 0.5);
  CHECK(rain.creation_depth_m == swemps::hydrology::RainSettings::kDefaultCreationDepthM);
  CHECK(std::get<double>(rain.initial_loss_mm) == 0.0);
  CHECK(std::get<double>(rain.continuing_loss_mm_h) == 0.0);
  CHECK_FALSE(rain.green_ampt);
  CHECK(rain.polygon.empty());
  // The defaults are written into the scene as run.
  CHECK_THAT(s.as_read_json, Contains("\"creation_depth\""));
}

TEST_CASE("rain as an array, each with its series, polygon and losses", "[scenario][rain]") {
  const auto s = parse(rain_scene(json::parse(R"([
    {"name": "west", "rate_mm_h": [[0, 0], [600, 50], [1200, 0]], "spacing": 1,
     "polygon": [[0, 0], [10, 0], [10, 10], [0, 10]],
     "initial_loss_mm": 10, "continuing_loss_mm_h": 2.5, "creation_depth": 0.002},
    {"name": "east", "rate_mm_h": 5, "spacing": 1}
  ])")));
  REQUIRE(s.rain.size() == 2);
  CHECK(s.rain[0].key_path == "/rain/0");
  CHECK(s.rain[0].polygon.size() == 4);
  CHECK(std::get<double>(s.rain[0].initial_loss_mm) == 10.0);
  CHECK(std::get<double>(s.rain[0].continuing_loss_mm_h) == 2.5);
  CHECK(s.rain[0].creation_depth_m == 0.002);
  auto built = swemps::scenario::build(s);
  std::size_t rains = 0;
  for (const auto& effect : built.simulation.effects()) {
    if (const auto* rain = dynamic_cast<const swemps::hydrology::Rain*>(effect.get())) {
      ++rains;
      CHECK(rain->cell_count() == (rain->name() == "west" ? 100u : 200u));
    }
  }
  CHECK(rains == 2);
}

TEST_CASE("bad rain is refused in one line at its key", "[scenario][rain]") {
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_mm_h": -3, "spacing": 1})"))),
             Contains("/rain/rate_mm_h | ") && Contains("a rain rate >= 0 (mm/h)"));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_mm_h": [[0, 1], [60, 2], [30, 1]],
                                                "spacing": 1})"))),
             Contains("/rain/rate_mm_h/2/0 | ") && Contains("strictly increasing"));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_mm_h": [[0, 1], [60, -2]], "spacing": 1})"))),
             Contains("/rain/rate_mm_h/1/1 | "));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"spacing": 1})"))),
             Contains("/rain | ") && Contains("exactly one of"));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_mm_h": 1})"))),
             Contains("/rain/spacing | ") && Contains("required when the scene has no water"));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_mm_h": 1, "spacing": 1,
                                                "initial_loss_mm": -1})"))),
             Contains("/rain/initial_loss_mm | "));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_mm_h": 1, "spacing": 1,
                                                "polygon": [[50, 50], [60, 50], [60, 60]]})"))),
             Contains("/rain | ") && Contains("holds no cell centre"));
  CHECK_THAT(refusal(rain_scene(json::parse(R"([{"name": "a", "rate_mm_h": 1, "spacing": 1},
                                                {"name": "a", "rate_mm_h": 2, "spacing": 1}])"))),
             Contains("/rain/1/name | "));
}

TEST_CASE("a rain series from a CSV file in mm/h", "[scenario][rain]") {
  swemps::testing::TempDir dir("rain-csv");
  std::ofstream(dir.path() / "storm.csv") << "time_s,rain_mm_h\n0,0\n600,40\n1200,0\n";
  std::ofstream(dir.path() / "inches.csv") << "time_s,rain_in_h\n0,0\n600,2\n";
  std::ofstream(dir.path() / "unordered.csv") << "t [s], rain [mm/h]\n0,1\n600,2\n300,1\n";
  const auto good = rain_scene(json::parse(R"({"rate_csv": "storm.csv", "spacing": 1})"));
  auto built = swemps::scenario::build(parse(good, dir.path()));
  const swemps::hydrology::Rain* rain = nullptr;
  for (const auto& effect : built.simulation.effects()) {
    if (!rain) rain = dynamic_cast<const swemps::hydrology::Rain*>(effect.get());
  }
  REQUIRE(rain != nullptr);
  const auto* uniform = dynamic_cast<const swemps::hydrology::UniformRainRate*>(&rain->rate());
  REQUIRE(uniform != nullptr);
  CHECK(uniform->series().discharge(600.0) ==
        Approx(40.0 * swemps::hydrology::kMetresPerSecondPerMmPerHour));

  CHECK_THAT(
      refusal(rain_scene(json::parse(R"({"rate_csv": "inches.csv", "spacing": 1})")), dir.path()),
      Contains("/rain/rate_csv | ") && Contains("must be in mm/h"));
  CHECK_THAT(refusal(rain_scene(json::parse(R"({"rate_csv": "unordered.csv", "spacing": 1})")),
                     dir.path()),
             Contains("/rain/rate_csv | ") && Contains("is not after the previous time"));
}

// Scenario files: broken scenes must fail with a message that points at the problem, valid
// scenes must arrive field by field, and omitted keys must take their documented defaults.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "../support/broken_scenes.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/scenario/ensemble_file.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

using swemps::testing::Broken;
using swemps::testing::check_broken;
using swemps::testing::parse_text;

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::scenario::PlaneBedSpec;
using swemps::scenario::ProfileBedSpec;
using swemps::scenario::ScenarioError;
using swemps::scenario::UniformDepth;
using swemps::scenario::VolumeRule;

// The smallest valid scene; broken cases are small edits of it, so each fails for one reason.
json minimal_scene() {
  return json::parse(R"({
    "end_time": 0.5,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 4.65, "y_min": 0, "y_max": 1},
               "depth": 0.25, "spacing": 0.1}]
  })");
}

std::string edited(const std::function<void(json&)>& edit) {
  json scene = minimal_scene();
  edit(scene);
  return scene.dump(2);
}

std::vector<Broken> broken_scenes() {
  return {
      {"syntax error", "{\n  \"end_time\": 0.5,\n  \"domain\": {\"x_min\": 0,, \"x_max\": 1}\n}",
       "", "invalid JSON at line 3, column 25: syntax error"},
      {"comment", "{\"end_time\": 0.5 // seconds\n}", "", "invalid JSON at line 1"},
      {"empty text", "", "", "expected valid JSON"},
      {"not an object", "[1, 2]", "", "found an array of 2 elements"},
      {"misspelt water key", edited([](json& s) {
         s["water"][0].erase("depth");
         s["water"][0]["dpeth"] = 0.25;
       }),
       "/water/0/dpeth", "did you mean \"depth\"?"},
      {"misspelt top-level key", edited([](json& s) { s["end_tme"] = 1.0; }), "/end_tme",
       "did you mean \"end_time\"?"},
      {"unrelated unknown key", edited([](json& s) {
         s["numerics"] = {{"zzzzzz", 1}};
       }),
       "/numerics/zzzzzz",
       "one of the keys scheme, cfl, alpha_e, max_area_ratio, gradient, kappa, kernel, "
       "dissipation, "
       "shifting, bed_term, min_time_step, eddy_viscosity"},
      {"missing end_time", edited([](json& s) { s.erase("end_time"); }), "/end_time",
       "found nothing (key missing), expected a number > 0 (seconds)"},
      {"missing domain", edited([](json& s) { s.erase("domain"); }), "/domain", "key missing"},
      {"missing water", edited([](json& s) { s.erase("water"); }), "/water", "key missing"},
      {"empty water", edited([](json& s) { s["water"] = json::array(); }), "/water",
       "found an empty array"},
      {"negative depth", edited([](json& s) { s["water"][0]["depth"] = -0.3; }), "/water/0/depth",
       "scenario error at /water/0/depth: found -0.3, expected a number > 0 (metres)"},
      {"zero spacing", edited([](json& s) { s["water"][0]["spacing"] = 0; }), "/water/0/spacing",
       "found 0, expected a number > 0"},
      {"spacing wider than the water", edited([](json& s) { s["water"][0]["spacing"] = 2.0; }),
       "/water/0/spacing", "at most 1"},
      {"string for a number", edited([](json& s) { s["end_time"] = "abc"; }), "/end_time",
       "found a string \"abc\""},
      {"boolean for a number", edited([](json& s) { s["gravity"] = true; }), "/gravity",
       "found true"},
      {"number too large", "{\"end_time\": 1e999}", "", "number overflow parsing '1e999'"},
      {"velocity of wrong length", edited([](json& s) {
         s["water"][0]["velocity"] = {1, 2, 3};
       }),
       "/water/0/velocity", "found an array of 3 elements, expected a [u, v] pair"},
      {"both rectangle and polygon", edited([](json& s) {
         s["water"][0]["polygon"] = {{0, 0}, {1, 0}, {1, 1}};
       }),
       "/water/0", "both \"rectangle\" and \"polygon\""},
      {"neither rectangle nor polygon", edited([](json& s) { s["water"][0].erase("rectangle"); }),
       "/water/0", "neither \"rectangle\" nor \"polygon\""},
      {"bow-tie polygon", edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
       }),
       "/water/0/polygon", "intersecting"},
      {"polygon turning back on itself", edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {2, 0}, {1, 0}, {1, 1}};
       }),
       "/water/0/polygon", "turning back"},
      {"closed polygon", edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}};
       }),
       "/water/0/polygon/0", "do not repeat the first vertex"},
      {"polygon with two vertices", edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {1, 0}};
       }),
       "/water/0/polygon", "at least 3"},
      {"water outside the domain", edited([](json& s) {
         s["water"][0].erase("rectangle");
         s["water"][0]["polygon"] = {{0, 0}, {11, 0}, {11, 1}};
       }),
       "/water/0/polygon/1", "outside the domain"},
      {"domain x_min >= x_max", edited([](json& s) { s["domain"]["x_min"] = 10; }), "/domain/x_max",
       "expected a number > x_min"},
      {"cfl above 1", edited([](json& s) {
         s["numerics"] = {{"cfl", 1.5}};
       }),
       "/numerics/cfl", "found 1.5, expected a number in (0, 1]"},
      {"alpha_e far too large", edited([](json& s) {
         s["numerics"] = {{"scheme", "seed"}, {"alpha_e", 10}};
       }),
       "/numerics/alpha_e", "a number in [1, 3]"},
      {"bad gradient name", edited([](json& s) {
         s["numerics"] = {{"scheme", "seed"}, {"gradient", "sumation"}};
       }),
       "/numerics/gradient", "one of \"mps\", \"summation\" (did you mean \"summation\"?)"},
      {"bad wall condition", edited([](json& s) {
         s["walls"] = {{{"polyline", {{0, 0}, {0, 1}}}, {"condition", "sticky"}}};
       }),
       "/walls/0/condition", "one of \"slip\", \"no_slip\""},
      {"wall with one point", edited([](json& s) {
         s["walls"] = {{{"polyline", {{0, 0}}}}};
       }),
       "/walls/0/polyline", "at least 2"},
      {"wall with a repeated point", edited([](json& s) {
         s["walls"] = {{{"polyline", {{0, 0}, {0, 0}}}}};
       }),
       "/walls/0/polyline/1", "different from the one before"},
      {"output time beyond end_time", edited([](json& s) {
         s["output"] = {{"times", {0.1, 0.7}}};
       }),
       "/output/times/1", "found 0.7, expected a time in (0, end_time = 0.5]"},
      {"both times and interval", edited([](json& s) {
         s["output"] = {{"times", {0.1}}, {"interval", 0.1}};
       }),
       "/output", "at most one of \"times\" or \"interval\""},
      {"part of the grid box", edited([](json& s) {
         s["output"] = {{"grid", {{"x_min", 1}}}};
       }),
       "/output/grid", "all four of x_min, x_max, y_min, y_max, or none"},
      {"particles not a boolean", edited([](json& s) {
         s["output"] = {{"particles", "yes"}};
       }),
       "/output/particles", "true or false"},
      {"duplicate key", R"({"end_time": 0.5, "water": [{"depth": 1, "depth": 2}]})",
       "/water/0/depth", "a second time"},
      {"arrays nested 100 deep",
       R"({"end_time": 0.5, "x": )" + std::string(100, '[') + std::string(100, ']') + "}",
       "/x/0/0/0", "found containers nested more than 64 levels deep"},
  };
}

// The minimal scene with one extra top-level key, given as JSON text.
std::string with_key(const std::string& key, const std::string& value) {
  return edited([&](json& s) { s[key] = json::parse(value); });
}

// Broken bed, friction and splitting sections. Here `path` is the whole json_path(), so a
// message that points at the parent object (or at the wrong point) fails.
std::vector<Broken> broken_effect_scenes() {
  return {
      {"misspelt friction key", with_key("frction", R"({"manning_n": 0.01})"), "/frction",
       "did you mean \"friction\"?"},
      {"bed not an object", with_key("bed", R"([[0, 0], [1, 1]])"), "/bed",
       "found an array of 2 elements, expected an object with exactly one of \"plane\", "
       "\"profile_x\" or \"raster\""},
      {"bed with both plane and profile_x",
       with_key("bed", R"({"plane": {"slope": [0.1, 0]}, "profile_x": [[0, 0], [1, 1]]})"), "/bed",
       "found both \"plane\" and \"profile_x\", expected exactly one of \"plane\", "
       "\"profile_x\" or \"raster\""},
      {"bed with neither plane nor profile_x", with_key("bed", "{}"), "/bed",
       "found none of \"plane\", \"profile_x\" or \"raster\", expected exactly one of"},
      {"misspelt bed kind", with_key("bed", R"({"plane_": {}})"), "/bed/plane_",
       "did you mean \"plane\"?"},
      {"misspelt plane key", with_key("bed", R"({"plane": {"slop": [0.1, 0]}})"), "/bed/plane/slop",
       "one of the keys elevation, slope, origin (did you mean \"slope\"?)"},
      {"plane slope of wrong length", with_key("bed", R"({"plane": {"slope": [0.1]}})"),
       "/bed/plane/slope", "found an array of 1 element, expected a [dz/dx, dz/dy] pair"},
      {"plane elevation not a number", with_key("bed", R"({"plane": {"elevation": "0"}})"),
       "/bed/plane/elevation", "found a string \"0\", expected a number (metres)"},
      {"profile_x with one point", with_key("bed", R"({"profile_x": [[0, 0]]})"), "/bed/profile_x",
       "found an array of 1 element, expected an array of at least 2"},
      {"profile_x with x decreasing", with_key("bed", R"({"profile_x": [[1, 0], [0.5, 1]]})"),
       "/bed/profile_x/1", "found x = 0.5, expected x greater than the previous point's 1"},
      {"profile_x with x repeated further on",
       with_key("bed", R"({"profile_x": [[0, 0], [3.4, 0], [3.4, 0.5], [10, 0.66]]})"),
       "/bed/profile_x/2", "strictly increasing"},
      {"profile_x point of wrong length", with_key("bed", R"({"profile_x": [[0, 0], [1, 2, 3]]})"),
       "/bed/profile_x/1", "found an array of 3 elements"},
      {"eddy viscosity of zero", with_key("numerics", R"({"eddy_viscosity": 0})"),
       "/numerics/eddy_viscosity", "found 0, expected a number > 0 (m^2/s)"},
      {"area bound below 1", with_key("numerics", R"({"max_area_ratio": 0.5})"),
       "/numerics/max_area_ratio", "found 0.5, expected a number in [1, 100]"},
      {"friction as a bare number", with_key("friction", "0.001"), "/friction",
       "found 0.001, expected an object with \"manning_n\""},
      {"friction without manning_n", with_key("friction", "{}"), "/friction/manning_n",
       "found nothing (key missing), expected a number > 0 (s m^-1/3)"},
      {"zero manning_n", with_key("friction", R"({"manning_n": 0})"), "/friction/manning_n",
       "found 0, expected a number > 0 (s m^-1/3)"},
      {"negative manning_n", with_key("friction", R"({"manning_n": -0.01})"), "/friction/manning_n",
       "found -0.01, expected a number > 0"},
      {"splitting not an object", with_key("splitting", "true"), "/splitting",
       "found true, expected an object (empty for the defaults)"},
      {"splitting threshold of 1", with_key("splitting", R"({"threshold": 1.0})"),
       "/splitting/threshold", "found 1.0, expected a number in (1, 4]"},
      {"splitting threshold above 4", with_key("splitting", R"({"threshold": 5})"),
       "/splitting/threshold", "found 5, expected a number in (1, 4]"},
      {"zero alpha_s", with_key("splitting", R"({"alpha_s": 0})"), "/splitting/alpha_s",
       "found 0, expected a number in (0, 1]"},
      {"alpha_s above 1", with_key("splitting", R"({"alpha_s": 1.5})"), "/splitting/alpha_s",
       "found 1.5, expected a number in (0, 1]"},
      {"negative max_particles", with_key("splitting", R"({"max_particles": -1})"),
       "/splitting/max_particles", "found -1, expected a whole number from 0 (no cap) to 4e9"},
      {"fractional max_particles", with_key("splitting", R"({"max_particles": 2.5})"),
       "/splitting/max_particles", "found 2.5, expected a whole number from 0"},
      {"max_particles as a string", with_key("splitting", R"({"max_particles": "100"})"),
       "/splitting/max_particles", "found a string \"100\""},
      {"negative splitting min_depth", with_key("splitting", R"({"min_depth": -0.001})"),
       "/splitting/min_depth", "found -0.001, expected a number >= 0"},
      {"misspelt splitting key", with_key("splitting", R"({"treshold": 2})"), "/splitting/treshold",
       "one of the keys threshold, alpha_s, max_particles, axis, min_depth (did you mean "
       "\"threshold\"?)"},
      {"unknown split axis", with_key("splitting", R"({"axis": "minr"})"), "/splitting/axis",
       "expected one of \"minor\", \"major\" (did you mean \"minor\"?)"},
      {"merging not an object", with_key("merging", "0.5"), "/merging",
       "found 0.5, expected an object (empty for the defaults)"},
      {"merging threshold of 0", with_key("merging", R"({"threshold": 0})"), "/merging/threshold",
       "found 0, expected a number in (0, 1] (the area ratio A/A_0 below which particles merge)"},
      {"merging threshold above 1", with_key("merging", R"({"threshold": 1.2})"),
       "/merging/threshold", "found 1.2, expected a number in (0, 1]"},
      {"misspelt merging key", with_key("merging", R"({"threshhold": 0.4})"), "/merging/threshhold",
       "did you mean \"threshold\"?"},
  };
}

}  // namespace

TEST_CASE("broken scenes name the offending JSON path and say what was expected", "[scenario]") {
  check_broken(broken_scenes(), false);
}

TEST_CASE("broken bed, friction and splitting sections point at the exact key", "[scenario]") {
  check_broken(broken_effect_scenes(), true);
}

TEST_CASE("merging must stay below half the splitting threshold", "[scenario][merging]") {
  // Two particles merged just under the merging threshold have twice its area: at half the
  // splitting threshold or more they would be split again at once.
  json scene = json::parse(with_key("splitting", R"({"threshold": 1.2})"));
  scene["merging"] = json::parse(R"({"threshold": 0.6})");
  CHECK_THROWS_WITH(parse_text(scene.dump()),
                    Contains("/merging/threshold") &&
                        Contains("found 0.6, expected a number in (0, 0.6) (the area ratio "
                                 "A/A_0 below which particles merge, below half the splitting "
                                 "threshold"));
  scene["merging"] = json::parse(R"({"threshold": 0.59})");
  const auto s = parse_text(scene.dump());
  REQUIRE(s.merging.has_value());
  CHECK(s.merging->area_ratio_threshold == 0.59);
  // The default, with splitting's default.
  scene["splitting"] = json::object();
  scene["merging"] = json::object();
  CHECK(parse_text(scene.dump()).merging->area_ratio_threshold == 0.5);
  // Without the key, no merging.
  scene.erase("merging");
  CHECK_FALSE(parse_text(scene.dump()).merging.has_value());
}

TEST_CASE("a polygon of many vertices is checked edge against edge", "[scenario]") {
  // A circle of 20,000 vertices, then the same with vertices 5 and 15,000 swapped, which
  // makes chords that cross.
  constexpr int n = 20000;
  json circle = json::array();
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * 3.141592653589793 * k / n;
    circle.push_back({5.0 + 0.4 * std::cos(a), 0.5 + 0.4 * std::sin(a)});
  }
  const auto scene_with = [](const json& polygon) {
    return edited([&](json& s) {
      s["water"][0].erase("rectangle");
      s["water"][0]["polygon"] = polygon;
    });
  };
  CHECK_NOTHROW(parse_text(scene_with(circle)));
  std::swap(circle[5], circle[15000]);
  try {
    parse_text(scene_with(circle));
    FAIL("a crossed outline was accepted");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path() == "/water/0/polygon");
    // The first crossing pair in edge order, as a plain double loop would report it: edge 4
    // now runs from vertex 4 across the circle to the old vertex 15,000 and crosses edge
    // 15,000, which starts where vertex 5 was.
    CHECK_THAT(std::string(e.what()), Contains("edge 4 "));
    CHECK_THAT(std::string(e.what()), Contains(" and edge 15000 "));
    CHECK_THAT(std::string(e.what()), Contains("intersecting"));
  }
}

TEST_CASE("an error message holds path, found and expected in one line", "[scenario]") {
  const ScenarioError e("/water/0/depth", "-0.3", "a number > 0 (metres)");
  CHECK(std::string(e.what()) ==
        "scenario error at /water/0/depth: found -0.3, expected a number > 0 (metres)");
  CHECK(e.json_path() == "/water/0/depth");
  CHECK(e.found() == "-0.3");
  CHECK(e.expected() == "a number > 0 (metres)");
  CHECK_THAT(std::string(ScenarioError("", "x", "y").what()), Contains("at /: found x"));
}

TEST_CASE("a full scene arrives with every field as given", "[scenario]") {
  const std::string text = R"({
    "name": "dam",
    "description": "a test dam",
    "gravity": 9.8,
    "end_time": 2.0,
    "numerics": {"scheme": "seed", "cfl": 0.3, "alpha_e": 2.0, "gradient": "mps",
                 "min_time_step": 1e-6,
                 "max_area_ratio": 9, "eddy_viscosity": 0.02},
    "domain": {"x_min": -1, "x_max": 10, "y_min": -2, "y_max": 3},
    "water": [
      {"rectangle": {"x_min": 0, "x_max": 4, "y_min": 0, "y_max": 1},
       "depth": 0.5, "velocity": [1.5, -0.5], "spacing": 0.1},
      {"polygon": [[5, 0], [7, 0], [6, 2]], "depth": 0.2, "spacing": 0.05}
    ],
    "walls": [
      {"polyline": [[-1, -2], [10, -2]], "condition": "no_slip"},
      {"polyline": [[0, 3], [0, 2], [1, 2]]}
    ],
    "bed": {"plane": {"elevation": -0.2, "slope": [0.1, -0.05], "origin": [3.4, 1.0]}},
    "friction": {"manning_n": 0.025},
    "splitting": {"threshold": 2.0, "alpha_s": 0.5, "max_particles": 100000, "axis": "major",
                  "min_depth": 0.002},
    "output": {
      "path": "results/../out/dam.nc",
      "times": [1.0, 0.5, 2.0, 0.5],
      "grid": {"spacing": 0.2, "x_min": 0, "x_max": 8, "y_min": 0, "y_max": 2},
      "particles": false
    }
  })";
  const fs::path base = fs::temp_directory_path() / "swemps-scenario-base";
  const auto s = swemps::scenario::parse(text, base, "unused");

  CHECK(s.name == "dam");
  CHECK(s.description == "a test dam");
  CHECK(s.end_time_s == 2.0);
  CHECK(s.numerics.gravity_m_s2 == 9.8);
  CHECK(s.numerics.cfl == 0.3);
  CHECK(s.numerics.alpha_e == 2.0);
  CHECK(s.numerics.gradient == swemps::swe::GradientVariant::mps);
  CHECK(s.numerics.min_time_step_s == 1e-6);
  CHECK(s.domain.x_min == -1);
  CHECK(s.domain.x_max == 10);
  CHECK(s.domain.y_min == -2);
  CHECK(s.domain.y_max == 3);

  REQUIRE(s.water.size() == 2);
  const std::vector<swemps::scenario::Point> rectangle{{0, 0}, {4, 0}, {4, 1}, {0, 1}};
  CHECK(s.water[0].polygon == rectangle);
  CHECK(std::get<UniformDepth>(s.water[0].depth).depth_m == 0.5);
  CHECK(s.water[0].velocity_m_s == std::array<double, 2>{1.5, -0.5});
  CHECK(s.water[0].spacing_m == 0.1);
  const std::vector<swemps::scenario::Point> triangle{{5, 0}, {7, 0}, {6, 2}};
  CHECK(s.water[1].polygon == triangle);
  CHECK(std::get<UniformDepth>(s.water[1].depth).depth_m == 0.2);
  CHECK(s.water[1].velocity_m_s == std::array<double, 2>{0.0, 0.0});
  CHECK(s.water[1].spacing_m == 0.05);

  CHECK(s.numerics.max_area_ratio == 9.0);
  REQUIRE(s.eddy_viscosity_m2_s.has_value());
  CHECK(*s.eddy_viscosity_m2_s == 0.02);
  REQUIRE(s.walls.size() == 2);
  CHECK(s.walls[0].polyline.size() == 2);
  CHECK(s.walls[0].condition == swemps::scenario::WallCondition::no_slip);
  CHECK(s.walls[1].polyline.size() == 3);
  CHECK(s.walls[1].condition == swemps::scenario::WallCondition::slip);

  const auto* plane = std::get_if<PlaneBedSpec>(&s.bed);
  REQUIRE(plane != nullptr);
  CHECK(plane->elevation_m == -0.2);
  CHECK(plane->slope == std::array<double, 2>{0.1, -0.05});
  CHECK(plane->origin_m == swemps::scenario::Point{3.4, 1.0});
  REQUIRE(s.manning_n.has_value());
  CHECK(std::get<double>(*s.manning_n) == 0.025);
  REQUIRE(s.splitting.has_value());
  CHECK(s.splitting->area_ratio_threshold == 2.0);
  CHECK(s.splitting->alpha_s == 0.5);
  CHECK(s.splitting->max_particles == 100000);
  CHECK(s.splitting->axis == swemps::splitting::SplitAxis::major);
  CHECK(s.splitting->min_depth_m == 0.002);

  CHECK(s.output.path == (fs::absolute(base) / "out" / "dam.nc").lexically_normal());
  CHECK(s.output.times_s == std::vector<double>{0.5, 1.0, 2.0});
  CHECK(s.output.grid.spacing_m == 0.2);
  REQUIRE(s.output.grid.bounds.has_value());
  CHECK(s.output.grid.bounds->x_min == 0);
  CHECK(s.output.grid.bounds->x_max == 8);
  CHECK(s.output.grid.bounds->y_min == 0);
  CHECK(s.output.grid.bounds->y_max == 2);
  CHECK_FALSE(s.output.write_particles);
}

TEST_CASE("omitted keys take their defaults", "[scenario]") {
  json scene = minimal_scene();
  scene["water"].push_back(
      json::parse(R"({"polygon": [[5, 0], [6, 0], [6, 1]], "depth": 0.1, "spacing": 0.04})"));
  const fs::path base = fs::temp_directory_path() / "swemps-defaults";
  const auto s = swemps::scenario::parse(scene.dump(), base, "ritter");

  CHECK(s.name == "ritter");
  CHECK(s.description.empty());
  CHECK(s.numerics.gravity_m_s2 == 9.81);
  CHECK(s.numerics.cfl == 0.5);
  CHECK(s.numerics.scheme == swemps::swe::SchemeKind::conservative);
  CHECK(s.numerics.kappa == 1.3);
  CHECK(s.numerics.kernel == swemps::swe::KernelShape::cubic_spline);
  CHECK(s.numerics.dissipation == 1.0);
  CHECK(s.numerics.min_time_step_s == 1e-8);
  // Unset: each scheme's own cap, 8 under the default (conservative) scheme.
  CHECK_FALSE(s.numerics.max_area_ratio.has_value());
  CHECK(s.numerics.area_ratio_cap() == 8.0);
  CHECK_FALSE(s.eddy_viscosity_m2_s.has_value());  // no eddy viscosity
  CHECK(s.water[0].velocity_m_s == std::array<double, 2>{0.0, 0.0});
  CHECK(s.walls.empty());
  CHECK(std::holds_alternative<std::monostate>(s.bed));  // flat bed at z = 0
  CHECK_FALSE(s.manning_n.has_value());                  // no friction
  CHECK_FALSE(s.splitting.has_value());                  // no splitting
  CHECK(s.output.times_s == std::vector<double>{0.5});
  REQUIRE(s.output.grid.spacing_m.has_value());
  CHECK(*s.output.grid.spacing_m == Approx(0.02));  // half the finer of 0.1 and 0.04
  CHECK_FALSE(s.output.grid.bounds.has_value());    // the domain
  CHECK_FALSE(s.domain_from_bed);
  CHECK(s.water[0].volumes == VolumeRule::geometric);
  CHECK(s.inflows.empty());
  CHECK(s.outflows.empty());
  CHECK(s.output.gauges.empty());
  CHECK(s.output.series_interval_s == Approx(0.5 / 500));
  CHECK(s.output.wet_depth_m == 0.01);
  CHECK(s.output.depth_thresholds_m == std::vector<double>{0.1, 0.3, 0.5, 1.0});
  CHECK(s.output.land_use == swemps::maps::LandUse::urban);
  CHECK_FALSE(s.output.start_time.has_value());
  CHECK(s.output.rasters.empty());
  CHECK(s.output.raster_cog);
  CHECK(s.output.write_particles);
  CHECK(s.output.path.is_absolute());
  CHECK(s.output.path == (fs::absolute(base) / "ritter.nc").lexically_normal());
}

TEST_CASE("bed, friction and splitting arrive as given, with defaults for what is left out",
          "[scenario]") {
  SECTION("a plane with only a slope is level with the origin at z = 0") {
    const auto s = parse_text(with_key("bed", R"({"plane": {"slope": [0.1, 0]}})"));
    const auto* plane = std::get_if<PlaneBedSpec>(&s.bed);
    REQUIRE(plane != nullptr);
    CHECK(plane->elevation_m == 0.0);
    CHECK(plane->slope == std::array<double, 2>{0.1, 0.0});
    CHECK(plane->origin_m == swemps::scenario::Point{0.0, 0.0});
  }
  SECTION("an empty plane is the flat bed") {
    const auto s = parse_text(with_key("bed", R"({"plane": {}})"));
    const auto* plane = std::get_if<PlaneBedSpec>(&s.bed);
    REQUIRE(plane != nullptr);
    CHECK(plane->elevation_m == 0.0);
    CHECK(plane->slope == std::array<double, 2>{0.0, 0.0});
    CHECK(plane->origin_m == swemps::scenario::Point{0.0, 0.0});
  }
  SECTION("profile points are kept in the order and at the values given") {
    const auto s =
        parse_text(with_key("bed", R"({"profile_x": [[-1, 0.5], [3.4, 0], [10, 0.66]]})"));
    const auto* profile = std::get_if<ProfileBedSpec>(&s.bed);
    REQUIRE(profile != nullptr);
    const std::vector<swemps::scenario::Point> expected{{-1.0, 0.5}, {3.4, 0.0}, {10.0, 0.66}};
    CHECK(profile->points == expected);
  }
  SECTION("a profile of two points is enough") {
    const auto s = parse_text(with_key("bed", R"({"profile_x": [[0, 0], [1, 0]]})"));
    const auto* profile = std::get_if<ProfileBedSpec>(&s.bed);
    REQUIRE(profile != nullptr);
    CHECK(profile->points.size() == 2);
  }
  SECTION("friction stores Manning's n") {
    const auto s = parse_text(with_key("friction", R"({"manning_n": 0.001})"));
    REQUIRE(s.manning_n.has_value());
    CHECK(std::get<double>(*s.manning_n) == 0.001);
    CHECK(std::holds_alternative<std::monostate>(s.bed));
    CHECK_FALSE(s.splitting.has_value());
  }
  SECTION("an empty splitting object switches splitting on with the defaults") {
    const auto s = parse_text(with_key("splitting", "{}"));
    REQUIRE(s.splitting.has_value());
    CHECK(s.splitting->area_ratio_threshold == 1.5);
    CHECK(s.splitting->alpha_s == 0.7);
    CHECK(s.splitting->max_particles == 0);
    CHECK(s.splitting->min_depth_m == 1e-5);
    CHECK_FALSE(s.manning_n.has_value());
  }
  SECTION("splitting keys left out keep their defaults") {
    const auto s = parse_text(with_key("splitting", R"({"alpha_s": 0.4})"));
    REQUIRE(s.splitting.has_value());
    CHECK(s.splitting->area_ratio_threshold == 1.5);
    CHECK(s.splitting->alpha_s == 0.4);
    CHECK(s.splitting->max_particles == 0);
  }
  SECTION("splitting limits are inclusive at the top") {
    const auto s =
        parse_text(with_key("splitting", R"({"threshold": 4, "alpha_s": 1, "max_particles": 0})"));
    REQUIRE(s.splitting.has_value());
    CHECK(s.splitting->area_ratio_threshold == 4.0);
    CHECK(s.splitting->alpha_s == 1.0);
    CHECK(s.splitting->max_particles == 0);
  }
  SECTION("explicit splitting values are stored") {
    const auto s = parse_text(
        with_key("splitting", R"({"threshold": 1.8, "alpha_s": 0.6, "max_particles": 250000})"));
    REQUIRE(s.splitting.has_value());
    CHECK(s.splitting->area_ratio_threshold == 1.8);
    CHECK(s.splitting->alpha_s == 0.6);
    CHECK(s.splitting->max_particles == 250000);
  }
}

TEST_CASE("an output interval gives its multiples and end_time", "[scenario]") {
  SECTION("interval dividing end_time") {
    const auto s = parse_text(edited([](json& j) { j["output"] = {{"interval", 0.1}}; }));
    REQUIRE(s.output.times_s.size() == 5);
    for (std::size_t k = 0; k < 5; ++k) CHECK(s.output.times_s[k] == Approx(0.1 * (k + 1)));
    CHECK(s.output.times_s.back() == 0.5);
  }
  SECTION("interval not dividing end_time") {
    const auto s = parse_text(edited([](json& j) { j["output"] = {{"interval", 0.2}}; }));
    REQUIRE(s.output.times_s.size() == 3);
    CHECK(s.output.times_s[0] == Approx(0.2));
    CHECK(s.output.times_s[1] == Approx(0.4));
    CHECK(s.output.times_s[2] == 0.5);
  }
  SECTION("interval longer than the run") {
    const auto s = parse_text(edited([](json& j) { j["output"] = {{"interval", 3.0}}; }));
    CHECK(s.output.times_s == std::vector<double>{0.5});
  }
  SECTION("listed times always end with end_time") {
    const auto s = parse_text(edited([](json& j) { j["output"] = {{"times", {0.2}}}; }));
    CHECK(s.output.times_s == std::vector<double>{0.2, 0.5});
  }
}

TEST_CASE("load() names the scene after its file and resolves paths next to it", "[scenario]") {
  const fs::path folder = fs::temp_directory_path() / "swemps-load-test" / "mycase";
  fs::create_directories(folder);
  {
    std::ofstream(folder / "scenario.json") << minimal_scene().dump();
    std::ofstream(folder / "other.json") << minimal_scene().dump();
  }
  const auto named_by_folder = swemps::scenario::load(folder / "scenario.json");
  CHECK(named_by_folder.name == "mycase");
  CHECK(named_by_folder.output.path == (fs::absolute(folder) / "mycase.nc").lexically_normal());
  const auto named_by_file = swemps::scenario::load(folder / "other.json");
  CHECK(named_by_file.name == "other");
  fs::remove_all(folder.parent_path());
}

TEST_CASE("load() of a missing file says it cannot read it", "[scenario]") {
  const fs::path missing = fs::temp_directory_path() / "swemps-no-such-folder" / "scenario.json";
  try {
    swemps::scenario::load(missing);
    FAIL("no error for a missing file");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path().empty());
    CHECK_THAT(e.found(), Contains("cannot read file"));
    CHECK_THAT(e.found(), Contains("scenario.json"));
    CHECK_THAT(e.expected(), Contains("a readable scenario JSON file"));
  }
}

namespace {

// Loads cases/<name>/scenario.json, or returns nothing (with a warning) while it does not exist.
std::optional<swemps::scenario::Scenario> load_shipped(const std::string& name) {
  const fs::path file = fs::path(SWEMPS_SOURCE_DIR) / "cases" / name / "scenario.json";
  if (!fs::exists(file)) {
    WARN("skipped: " << file.string() << " does not exist yet");
    return std::nullopt;
  }
  return swemps::scenario::load(file);
}

}  // namespace

TEST_CASE("the shipped cases parse", "[scenario]") {
  SECTION("every case is a complete scene") {
    const std::vector<std::string> names{"ritter", "ritter-splitting", "runup"};
    for (const std::string& name : names) {
      INFO("case: " << name);
      const auto s = load_shipped(name);
      if (!s) continue;
      CHECK(s->name == name);
      CHECK(s->end_time_s > 0.0);
      CHECK_FALSE(s->water.empty());
      CHECK(s->output.path.is_absolute());
      CHECK(s->output.times_s.back() == s->end_time_s);
    }
  }

  SECTION("ritter: flat, frictionless, no splitting") {
    if (const auto s = load_shipped("ritter")) {
      CHECK(std::holds_alternative<std::monostate>(s->bed));
      CHECK_FALSE(s->manning_n.has_value());
      CHECK_FALSE(s->splitting.has_value());
    }
  }
  SECTION("ritter-splitting: the Ritter scene with splitting") {
    if (const auto s = load_shipped("ritter-splitting")) {
      CHECK(std::holds_alternative<std::monostate>(s->bed));
      CHECK_FALSE(s->manning_n.has_value());
      REQUIRE(s->splitting.has_value());
      CHECK(s->splitting->area_ratio_threshold == 1.5);
      CHECK(s->splitting->alpha_s == 0.7);
    }
  }
  SECTION("runup: a profile bed, friction and splitting") {
    if (const auto s = load_shipped("runup")) {
      const auto* profile = std::get_if<ProfileBedSpec>(&s->bed);
      REQUIRE(profile != nullptr);
      const std::vector<swemps::scenario::Point> expected{{3.4, 0.0}, {10.0, 0.66}};
      CHECK(profile->points == expected);
      REQUIRE(s->manning_n.has_value());
      CHECK(std::get<double>(*s->manning_n) == 0.001);
      REQUIRE(s->splitting.has_value());
      CHECK(s->splitting->area_ratio_threshold == 1.5);
      CHECK(s->splitting->alpha_s == 0.7);
      CHECK(s->splitting->max_particles == 0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Terrain, inflow, outflow and the flood-map output

namespace {

using swemps::scenario::DepthRaster;
using swemps::scenario::LevelSurface;
using swemps::scenario::RasterBedSpec;
using swemps::scenario::RasterSpec;

// A scene on a raster bed in map coordinates, without a domain (the raster's extent).
json raster_scene() {
  return json::parse(R"({
    "end_time": 10,
    "bed": {"raster": "dem.tif", "crs": "EPSG:32616"},
    "water": [{"fill": {"rectangle": {"x_min": 500100, "x_max": 500300,
                                      "y_min": 4000100, "y_max": 4000200}},
               "surface_elevation": 310, "spacing": 10}]
  })");
}

std::string raster_edited(const std::function<void(json&)>& edit) {
  json scene = raster_scene();
  edit(scene);
  return scene.dump(2);
}

const json kInflow = json::parse(R"({"line": [[1, 0], [1, 1]], "hydrograph": [[0, 0], [5, 1]]})");

// Broken terrain, inflow, outflow and output sections; `path` is the whole json_path().
std::vector<Broken> broken_terrain_scenes() {
  return {
      {"raster bed path empty", with_key("bed", R"({"raster": ""})"), "/bed/raster",
       "found a string \"\", expected a path to a raster of bed elevations"},
      {"raster bed path a number", with_key("bed", R"({"raster": 5})"), "/bed/raster",
       "found 5, expected a path"},
      {"raster and plane", with_key("bed", R"({"raster": "a.tif", "plane": {}})"), "/bed",
       "found both \"plane\" and \"raster\""},
      {"crs with a plane bed", with_key("bed", R"({"plane": {}, "crs": "EPSG:32616"})"), "/bed/crs",
       "no \"crs\" here (it goes with a \"raster\" bed)"},
      {"empty crs", with_key("bed", R"({"raster": "a.tif", "crs": ""})"), "/bed/crs",
       "expected a projected CRS in metres"},
      {"refinement with a plane bed", with_key("bed", R"({"plane": {}, "refinement": 2})"),
       "/bed/refinement", "no \"refinement\" here (it goes with a \"raster\" bed)"},
      {"refinement not whole", with_key("bed", R"({"raster": "a.tif", "refinement": 2.5})"),
       "/bed/refinement", "expected a whole number from 1 to 16"},
      {"refinement 0", with_key("bed", R"({"raster": "a.tif", "refinement": 0})"),
       "/bed/refinement", "expected a whole number from 1 to 16"},
      {"no domain without a raster bed", edited([](json& s) { s.erase("domain"); }), "/domain",
       "only a raster bed, whose extent it then is, lets it be left out"},
      {"both manning_n and a map",
       with_key("friction", R"({"manning_n": 0.03, "manning_n_raster": "n.tif"})"), "/friction",
       "found both \"manning_n\" and \"manning_n_raster\""},
      {"crs with a uniform n", with_key("friction", R"({"manning_n": 0.03, "crs": "EPSG:32616"})"),
       "/friction/crs", "it goes with \"manning_n_raster\""},
      {"roughness map not a string", with_key("friction", R"({"manning_n_raster": 3})"),
       "/friction/manning_n_raster", "expected a path to a raster of Manning's n"},
      {"roughness crs on a raster bed", raster_edited([](json& s) {
         s["friction"] = {{"manning_n_raster", "n.tif"}, {"crs", "EPSG:32616"}};
       }),
       "/friction/crs", "every raster is warped to the bed's CRS"},
      {"two rasters naming different CRSs", edited([](json& s) {
         s["friction"] = {{"manning_n_raster", "n.tif"}, {"crs", "EPSG:32616"}};
         s["water"][0] = {{"depth_raster", "h.tif"}, {"crs", "EPSG:32617"}, {"spacing", 0.1}};
       }),
       "/water/0/crs", "the same CRS for every raster"},
      {"fill without a bed", edited([](json& s) {
         s["water"][0] = {{"fill", {{"polygon", {{0, 0}, {1, 0}, {1, 1}}}}},
                          {"surface_elevation", 1},
                          {"spacing", 0.1}};
       }),
       "/water/0/fill", "a \"bed\" to fill"},
      {"fill and depth", raster_edited([](json& s) { s["water"][0]["depth"] = 1; }), "/water/0",
       "found both \"depth\" and \"fill\", expected exactly one of \"depth\", \"fill\" or "
       "\"depth_raster\""},
      {"fill with the shape outside it", raster_edited([](json& s) {
         s["water"][0]["polygon"] = {{500100, 4000100}, {500200, 4000100}, {500200, 4000200}};
       }),
       "/water/0/polygon", "with \"fill\" the shape goes inside it"},
      {"fill without a surface",
       raster_edited([](json& s) { s["water"][0].erase("surface_elevation"); }),
       "/water/0/surface_elevation", "found nothing (key missing), expected a number (metres"},
      {"fill from a point outside its shape", raster_edited([](json& s) {
         s["water"][0]["fill"]["from"] = {500050, 4000150};
       }),
       "/water/0/fill/from", "a point inside the shape, in the water the lake grows from"},
      {"fill from a word", raster_edited([](json& s) { s["water"][0]["fill"]["from"] = "here"; }),
       "/water/0/fill/from", "an [x, y] pair of numbers (m)"},
      {"fill without a shape",
       raster_edited([](json& s) { s["water"][0]["fill"] = json::object(); }), "/water/0/fill",
       "neither \"rectangle\" nor \"polygon\""},
      {"fill outside the domain", edited([](json& s) {
         s["bed"] = {{"plane", json::object()}};
         s["water"][0] = {{"fill", {{"polygon", {{0, 0}, {12, 0}, {1, 1}}}}},
                          {"surface_elevation", 1},
                          {"spacing", 0.1}};
       }),
       "/water/0/fill/polygon/1", "outside the domain [0, 10] x [0, 1]"},
      {"min_depth with a uniform depth", edited([](json& s) { s["water"][0]["min_depth"] = 0.1; }),
       "/water/0/min_depth", "it goes with \"fill\" or \"depth_raster\""},
      {"negative min_depth", raster_edited([](json& s) { s["water"][0]["min_depth"] = -0.1; }),
       "/water/0/min_depth", "found -0.1, expected a number >= 0 (metres)"},
      {"misspelt volume rule", raster_edited([](json& s) { s["water"][0]["volumes"] = "balance"; }),
       "/water/0/volumes", "one of \"geometric\", \"balanced\" (did you mean \"balanced\"?)"},
      {"balanced under the conservative scheme",
       raster_edited([](json& s) { s["water"][0]["volumes"] = "balanced"; }), "/water/0/volumes",
       "found \"balanced\" under the conservative scheme, expected \"geometric\""},
      {"geometric beside balanced", raster_edited([](json& s) {
         s["numerics"] = {{"scheme", "seed"}};
         s["water"].push_back(
             {{"rectangle",
               {{"x_min", 500000}, {"x_max", 500050}, {"y_min", 4000000}, {"y_max", 4000050}}},
              {"depth", 1},
              {"spacing", 10},
              {"volumes", "geometric"}});
       }),
       "/water/1/volumes", "found \"geometric\" while /water/0 is balanced"},
      {"depth raster with a surface", edited([](json& s) {
         s["water"][0] = {{"depth_raster", "h.tif"}, {"surface_elevation", 3}, {"spacing", 0.1}};
       }),
       "/water/0/surface_elevation", "it goes with \"fill\""},
      {"depth raster path empty", edited([](json& s) {
         s["water"][0] = {{"depth_raster", ""}, {"spacing", 0.1}};
       }),
       "/water/0/depth_raster", "expected a path to a raster of water depths"},
      {"inflow not an array", with_key("inflow", R"({"line": [[1, 0], [1, 1]]})"), "/inflow",
       "found an object, expected an array of inflow lines"},
      {"inflow line of three points", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["line"] = {{1, 0}, {1, 0.5}, {1, 1}};
       }),
       "/inflow/0/line", "found an array of 3 elements, expected an array of exactly 2"},
      {"inflow without a hydrograph", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0].erase("hydrograph");
       }),
       "/inflow/0", "neither \"hydrograph\" nor \"hydrograph_csv\""},
      {"inflow with two hydrographs", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["hydrograph_csv"] = "q.csv";
       }),
       "/inflow/0", "both \"hydrograph\" and \"hydrograph_csv\""},
      {"hydrograph going back in time", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["hydrograph"] = {{0, 1}, {5, 2}, {5, 3}};
       }),
       "/inflow/0/hydrograph/2/0", "found t = 5, expected a time greater than the previous"},
      {"negative discharge", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["hydrograph"] = {{0, -1}};
       }),
       "/inflow/0/hydrograph/0/1", "found -1, expected a discharge >= 0 (m^3/s)"},
      {"empty hydrograph", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["hydrograph"] = json::array();
       }),
       "/inflow/0/hydrograph", "found an empty array"},
      {"inflow direction along the line", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["direction"] = {1, 1};
       }),
       "/inflow/0/direction", "at 45 degrees to the line, expected a direction normal to the line"},
      {"zero inflow direction", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["direction"] = {0, 0};
       }),
       "/inflow/0/direction", "found a zero or unbounded vector"},
      {"inflow spacing needed without water", edited([](json& s) {
         s.erase("water");
         s["inflow"] = {kInflow};
       }),
       "/inflow/0/spacing", "required when the scene has no water"},
      {"two inflows of one name", edited([](json& s) {
         s["inflow"] = {kInflow, kInflow};
         s["inflow"][0]["name"] = "river";
         s["inflow"][1]["name"] = "river";
       }),
       "/inflow/1/name", "the name \"river\" again (inflow 0 has it)"},
      {"inflow line outside the domain", edited([](json& s) {
         s["inflow"] = {kInflow};
         s["inflow"][0]["line"] = {{1, 0}, {1, 2}};
       }),
       "/inflow/0/line/1", "expected an inflow line lying inside the domain"},
      {"no water and no inflow", edited([](json& s) { s["water"] = json::array(); }), "/water",
       "found an empty array, expected a non-empty array of water bodies, or an \"inflow\""},
      {"outflow line of one point", with_key("outflow", R"([{"line": [[10, 0]]}])"),
       "/outflow/0/line", "found an array of 1 element, expected an array of at least 2"},
      {"outflow without a line", with_key("outflow", R"([{}])"), "/outflow/0/line",
       "found nothing (key missing)"},
      {"misspelt outflow key", with_key("outflow", R"([{"lin": [[10, 0], [10, 1]]}])"),
       "/outflow/0/lin", "did you mean \"line\"?"},
      {"gauge outside the domain", edited([](json& s) {
         s["output"] = {{"gauges", {{{"name", "a"}, {"x", 20}, {"y", 0.5}}}}};
       }),
       "/output/gauges/0",
       "found the point (20, 0.5) outside the domain [0, 10] x [0, 1], "
       "expected a gauge inside the domain"},
      {"two gauges of one name", edited([](json& s) {
         s["output"] = {
             {"gauges",
              {{{"name", "a"}, {"x", 1}, {"y", 0.5}}, {{"name", "a"}, {"x", 2}, {"y", 0.5}}}}};
       }),
       "/output/gauges/1/name", "the name \"a\" again (gauge 0 has it)"},
      {"gauge without x", edited([](json& s) {
         s["output"] = {{"gauges", {{{"name", "a"}, {"y", 0.5}}}}};
       }),
       "/output/gauges/0/x", "found nothing (key missing), expected a number (metres)"},
      {"zero series interval", edited([](json& s) {
         s["output"] = {{"series_interval", 0}};
       }),
       "/output/series_interval", "found 0, expected a number > 0 (seconds)"},
      {"series interval far too short", edited([](json& s) {
         s["output"] = {{"series_interval", 1e-9}};
       }),
       "/output/series_interval", "expected an interval giving at most 1000000 samples"},
      {"negative wet depth", edited([](json& s) {
         s["output"] = {{"wet_depth", -0.01}};
       }),
       "/output/wet_depth", "found -0.01, expected a number >= 0 (metres)"},
      {"depth threshold at the wet depth", edited([](json& s) {
         s["output"] = {{"wet_depth", 0.1}, {"depth_thresholds", {0.3, 0.1}}};
       }),
       "/output/depth_thresholds/1", "found 0.1, expected a depth above wet_depth (0.1 m)"},
      {"depth thresholds not a list", edited([](json& s) {
         s["output"] = {{"depth_thresholds", 0.3}};
       }),
       "/output/depth_thresholds", "found 0.3, expected an array of depths (metres)"},
      {"misspelt land use", edited([](json& s) {
         s["output"] = {{"land_use", "urbane"}};
       }),
       "/output/land_use", "did you mean \"urban\"?"},
      {"start time without a date", edited([](json& s) {
         s["output"] = {{"start_time", "12:00"}};
       }),
       "/output/start_time", "found a string \"12:00\", expected an ISO 8601 date and time"},
      {"start time on the 30th of February", edited([](json& s) {
         s["output"] = {{"start_time", "2024-02-30T00:00:00Z"}};
       }),
       "/output/start_time", "expected an ISO 8601 date and time"},
      {"start time with a bad zone", edited([](json& s) {
         s["output"] = {{"start_time", "2024-06-01T12:00:00+2"}};
       }),
       "/output/start_time", "expected an ISO 8601 date and time"},
      {"unknown raster map", edited([](json& s) {
         s["output"] = {{"rasters", {"max_depth", "max_dpth"}}};
       }),
       "/output/rasters/1", "did you mean \"max_depth\"?"},
      {"rasters neither all nor a list", edited([](json& s) {
         s["output"] = {{"rasters", "some"}};
       }),
       "/output/rasters", "expected \"all\" or an array of map names"},
      {"a tsunami map without the tsunami products", edited([](json& s) {
         s["output"] = {{"rasters", {"max_depth", "tsunami_arrival_time"}}};
       }),
       "/output/rasters/1", "found a string \"tsunami_arrival_time\", expected one of"},
      {"tsunami products over water not filled to one level", edited([](json& s) {
         s["bed"] = {{"plane", {{"elevation", -1.0}, {"slope", {0.1, 0.0}}}}};
         s["output"] = {{"tsunami", json::object()}};
       }),
       "/output/tsunami/still_level", "expected the elevation of the sea at rest"},
      {"tsunami arrival rise of zero", edited([](json& s) {
         s["output"] = {{"tsunami", {{"arrival_rise", 0}}}};
       }),
       "/output/tsunami/arrival_rise", "found 0, expected a number > 0 (metres)"},
      {"unknown inundation line format", edited([](json& s) {
         s["output"] = {{"tsunami", {{"inundation_line", "shp"}}}};
       }),
       "/output/tsunami/inundation_line", "expected one of \"gpkg\", \"geojson\", \"none\""},
      {"unknown raster format", edited([](json& s) {
         s["output"] = {{"raster_format", "tiff"}};
       }),
       "/output/raster_format", "expected one of \"cog\", \"geotiff\""},
  };
}

}  // namespace

TEST_CASE("broken terrain, inflow, outflow and output sections point at the exact key",
          "[scenario]") {
  check_broken(broken_terrain_scenes(), true);
}

TEST_CASE("a raster scene arrives as given, with its domain left to the bed", "[scenario]") {
  json scene = raster_scene();
  // Balanced volumes are the seed scheme's (docs/scenario.md).
  scene["numerics"] = {{"scheme", "seed"}};
  scene["friction"] = {{"manning_n_raster", "landuse/n.tif"}};
  scene["water"].push_back(json::parse(R"({"depth_raster": "NETCDF:\"h.nc\":depth",
                                           "spacing": 20, "min_depth": 0.05, "volumes": "balanced",
                                           "velocity": [0.5, 0]})"));
  scene["water"].push_back(json::parse(R"({"rectangle": {"x_min": 500000, "x_max": 500050,
                                           "y_min": 4000000, "y_max": 4000050},
                                           "depth": 1, "spacing": 10})"));
  scene["inflow"] = json::parse(R"([
    {"line": [[500000, 4000100], [500000, 4000200]], "hydrograph_csv": "flood.csv"},
    {"name": "creek", "line": [[500100, 4000300], [500200, 4000300]],
     "hydrograph": [[0, 0], [60, 5], [120, 0]], "spacing": 5, "depth": 0.5, "direction": [0, -2]}
  ])");
  scene["outflow"] = json::parse(R"([{"line": [[500390, 4000000], [500390, 4000300]]}])");
  scene["output"] = json::parse(R"({"gauges": [{"name": "bridge", "x": 500200, "y": 4000150},
                                               {"x": 500300, "y": 4000100}],
                                    "series_interval": 2, "wet_depth": 0.05})");
  const fs::path base = fs::temp_directory_path() / "swemps-raster-scene";
  const auto s = swemps::scenario::parse(scene.dump(), base, "lake");
  const auto at_base = [&](const std::string& name) {
    return (fs::absolute(base) / name).lexically_normal();
  };

  CHECK(s.domain_from_bed);
  const auto* bed = std::get_if<RasterBedSpec>(&s.bed);
  REQUIRE(bed != nullptr);
  CHECK(bed->raster.path == at_base("dem.tif"));
  CHECK(bed->raster.crs == "EPSG:32616");
  REQUIRE(s.manning_n.has_value());
  const auto* roughness = std::get_if<RasterSpec>(&*s.manning_n);
  REQUIRE(roughness != nullptr);
  CHECK(roughness->path == at_base("landuse/n.tif"));
  CHECK(roughness->crs.empty());

  REQUIRE(s.water.size() == 3);
  const auto* level = std::get_if<LevelSurface>(&s.water[0].depth);
  REQUIRE(level != nullptr);
  CHECK(level->surface_elevation_m == 310.0);
  const std::vector<swemps::scenario::Point> fill_box{
      {500100, 4000100}, {500300, 4000100}, {500300, 4000200}, {500100, 4000200}};
  CHECK(s.water[0].polygon == fill_box);
  CHECK(s.water[0].min_depth_m == 0.01);
  CHECK(s.water[0].volumes == VolumeRule::balanced);
  const auto* raster = std::get_if<DepthRaster>(&s.water[1].depth);
  REQUIRE(raster != nullptr);
  // A GDAL dataset name keeps its driver and variable; only the file is resolved.
  CHECK(raster->raster.path.string() == "NETCDF:\"" + at_base("h.nc").string() + "\":depth");
  CHECK(s.water[1].polygon.empty());  // the whole domain
  CHECK(s.water[1].min_depth_m == 0.05);
  CHECK(s.water[1].velocity_m_s == std::array<double, 2>{0.5, 0.0});
  // One balanced body balances them all.
  CHECK(std::holds_alternative<UniformDepth>(s.water[2].depth));
  CHECK(s.water[2].volumes == VolumeRule::balanced);

  REQUIRE(s.inflows.size() == 2);
  CHECK(s.inflows[0].name == "inflow 0");
  CHECK(std::get<fs::path>(s.inflows[0].hydrograph) == at_base("flood.csv"));
  CHECK(s.inflows[0].spacing_m == 10.0);  // the finest water spacing
  CHECK_FALSE(s.inflows[0].depth_m.has_value());
  CHECK_FALSE(s.inflows[0].direction.has_value());
  CHECK(s.inflows[1].name == "creek");
  const std::vector<std::array<double, 2>> table{{0, 0}, {60, 5}, {120, 0}};
  CHECK(std::get<std::vector<std::array<double, 2>>>(s.inflows[1].hydrograph) == table);
  CHECK(s.inflows[1].spacing_m == 5.0);
  CHECK(s.inflows[1].depth_m == 0.5);
  CHECK(s.inflows[1].direction == std::array<double, 2>{0.0, -2.0});
  REQUIRE(s.outflows.size() == 1);
  CHECK(s.outflows[0].line.size() == 2);

  CHECK_FALSE(s.output.grid.spacing_m.has_value());  // the bed raster's own cells
  CHECK_FALSE(s.output.grid.bounds.has_value());
  REQUIRE(s.output.gauges.size() == 2);
  CHECK(s.output.gauges[0].name == "bridge");
  CHECK(s.output.gauges[0].position_m == swemps::scenario::Point{500200, 4000150});
  CHECK(s.output.gauges[1].name == "gauge 1");
  CHECK(s.output.series_interval_s == 2.0);
  CHECK(s.output.wet_depth_m == 0.05);
}

TEST_CASE("flood products arrive as given", "[scenario]") {
  SECTION("thresholds, land use, start time and rasters") {
    const auto s = parse_text(edited([](json& j) {
      j["output"] = {{"wet_depth", 0.05},
                     {"depth_thresholds", {1.0, 0.25}},
                     {"land_use", "pasture_arable"},
                     {"start_time", "2024-06-01T12:30+02:00"},
                     {"rasters", {"hazard_class_uk", "max_depth", "hazard_class_uk"}},
                     {"raster_format", "geotiff"}};
    }));
    CHECK(s.output.depth_thresholds_m == std::vector<double>{1.0, 0.25});
    CHECK(s.output.land_use == swemps::maps::LandUse::pasture_arable);
    CHECK(s.output.start_time == "2024-06-01T12:30+02:00");
    CHECK(s.output.start_time_units == "seconds since 2024-06-01 12:30:00 +02:00");
    CHECK(s.output.rasters == std::vector<std::string>{"hazard_class_uk", "max_depth"});
    CHECK_FALSE(s.output.raster_cog);
  }
  SECTION("the default thresholds above a deep wet depth, a date alone, every raster") {
    const auto s = parse_text(edited([](json& j) {
      j["output"] = {{"wet_depth", 0.3}, {"start_time", "2000-02-29"}, {"rasters", "all"}};
    }));
    CHECK(s.output.depth_thresholds_m == std::vector<double>{0.5, 1.0});
    CHECK(s.output.start_time_units == "seconds since 2000-02-29 00:00:00");
    // Every map but the tsunami maps, which only a scene with output.tsunami has.
    auto expected = swemps::maps::summary_map_names();
    std::erase_if(expected, swemps::maps::is_tsunami_map);
    CHECK(expected.size() + 2 == swemps::maps::summary_map_names().size());
    CHECK(s.output.rasters == expected);
    CHECK_FALSE(s.output.tsunami.has_value());
  }
  SECTION("tsunami products: the still level the water is filled to, the wet depth's rise") {
    const auto s = parse_text(edited([](json& j) {
      j["bed"] = {{"plane", {{"elevation", -1.0}, {"slope", {0.1, 0.0}}}}};
      j["water"][0] = {{"fill", {{"rectangle", j["water"][0]["rectangle"]}}},
                       {"surface_elevation", -0.3},
                       {"spacing", 0.1}};
      j["output"] = {{"wet_depth", 0.002}, {"tsunami", json::object()}, {"rasters", "all"}};
    }));
    REQUIRE(s.output.tsunami.has_value());
    CHECK(s.output.tsunami->levels.still_level_m == -0.3);
    CHECK(s.output.tsunami->levels.arrival_rise_m == 0.002);
    CHECK(s.output.tsunami->inundation_line == swemps::scenario::VectorFormat::gpkg);
    CHECK(s.output.rasters == swemps::maps::summary_map_names());
  }
  SECTION("tsunami products as given; a uniform depth over no bed is its own level") {
    const auto s = parse_text(edited([](json& j) {
      j["output"] = {
          {"tsunami",
           {{"still_level", 0.2}, {"arrival_rise", 0.03}, {"inundation_line", "geojson"}}},
          {"rasters", {"max_surface_rise"}}};
    }));
    CHECK(s.output.tsunami->levels.still_level_m == 0.2);
    CHECK(s.output.tsunami->levels.arrival_rise_m == 0.03);
    CHECK(s.output.tsunami->inundation_line == swemps::scenario::VectorFormat::geojson);
    CHECK(s.output.rasters == std::vector<std::string>{"max_surface_rise"});
    const auto d = parse_text(edited([](json& j) { j["output"] = {{"tsunami", json::object()}}; }));
    CHECK(d.output.tsunami->levels.still_level_m == 0.25);
    CHECK(d.output.tsunami->levels.arrival_rise_m == 0.01);
  }
  SECTION("UTC") {
    const auto s = parse_text(edited([](json& j) {
      j["output"] = {{"start_time", "2011-03-11 05:46:24Z"}};
    }));
    CHECK(s.output.start_time_units == "seconds since 2011-03-11 05:46:24 +00:00");
  }
}

TEST_CASE("the scene as read records the defaults it took", "[scenario]") {
  const auto s = parse_text(edited([](json& j) { j["output"] = {{"wet_depth", 0.05}}; }));
  const json as_read = json::parse(s.as_read_json);
  // Given: kept as written.
  CHECK(as_read["output"]["wet_depth"] == 0.05);
  // Left out: the value the scene ran with.
  CHECK(as_read["numerics"]["scheme"] == "conservative");
  CHECK(as_read["numerics"]["cfl"] == s.numerics.cfl);
  CHECK(as_read["output"]["series_interval"] == s.output.series_interval_s);
  CHECK(as_read["output"]["land_use"] == "urban");
  CHECK(as_read["output"]["depth_thresholds"] == json::array({0.1, 0.3, 0.5, 1.0}));
  CHECK(as_read["output"]["particles"] == true);
  CHECK(as_read["gravity"] == 9.81);
  // Read again, it is the same scene.
  const auto again = swemps::scenario::parse(s.as_read_json, fs::temp_directory_path(), "again");
  CHECK(again.numerics.cfl == s.numerics.cfl);
  CHECK(again.output.series_interval_s == s.output.series_interval_s);
  CHECK(again.output.depth_thresholds_m == s.output.depth_thresholds_m);
}

TEST_CASE("every shipped scene read again as recorded is the same scene", "[scenario]") {
  const fs::path cases = fs::path(SWEMPS_SOURCE_DIR) / "cases";
  std::size_t scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(cases)) {
    if (entry.path().extension() != ".json") continue;
    const std::string text = [&] {
      std::ifstream in(entry.path());
      return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }();
    if (json::parse(text).contains("sweep")) continue;  // a study file, not a scene
    INFO(entry.path().string());
    if (json::parse(text).contains("vary")) {
      // An ensemble file: every member's scene is a scene that reads.
      const auto ensemble = swemps::scenario::load_ensemble(entry.path());
      for (const auto& member : swemps::ensemble::members(ensemble)) {
        const fs::path folder = ensemble.folder / "member";
        CHECK_NOTHROW(swemps::scenario::parse(
            swemps::scenario::member_scene(ensemble, member, folder), folder, "member"));
      }
      continue;
    }
    const auto first = swemps::scenario::parse(text, entry.path().parent_path(), "scene");
    const auto again =
        swemps::scenario::parse(first.as_read_json, entry.path().parent_path(), "scene");
    CHECK(again.as_read_json == first.as_read_json);
    CHECK(again.output.path == first.output.path);
    CHECK(again.numerics.cfl == first.numerics.cfl);
    ++scenes;
  }
  CHECK(scenes >= 10);
}

TEST_CASE("a scene may start dry when an inflow brings the water", "[scenario]") {
  const auto s = parse_text(edited([](json& j) {
    j.erase("water");
    j["inflow"] = {kInflow};
    j["inflow"][0]["spacing"] = 0.05;
  }));
  CHECK(s.water.empty());
  REQUIRE(s.inflows.size() == 1);
  REQUIRE(s.output.grid.spacing_m.has_value());
  CHECK(*s.output.grid.spacing_m == Approx(0.025));  // half the inflow's spacing
}

TEST_CASE("a raster bed may keep a domain and choose a grid spacing", "[scenario]") {
  const auto s = parse_text(raster_edited([](json& j) {
    j["domain"] = {{"x_min", 500000}, {"x_max", 500400}, {"y_min", 4000000}, {"y_max", 4000300}};
    j["output"] = {{"grid", {{"spacing", 20}}}};
  }));
  CHECK_FALSE(s.domain_from_bed);
  CHECK(s.domain.x_max == 500400);
  CHECK(s.output.grid.spacing_m == 20.0);
}

// Buildings from vector files: footprints as walls (no water seeded and no rain under them, no
// particle ever inside) or raised into the bed; files in another CRS transformed only when
// asked; one-line errors naming the key for what cannot be read or placed.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/io/vector_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::scenario::ScenarioError;
namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// A GeoJSON feature collection of polygons given as rings of [x, y] (`crs`: a "crs" member
// naming it; empty: none, which GDAL reads as longitude/latitude).
std::string geojson(const std::vector<json>& rings, const std::string& crs = "") {
  json fc = {{"type", "FeatureCollection"}, {"features", json::array()}};
  if (!crs.empty()) fc["crs"] = {{"type", "name"}, {"properties", {{"name", crs}}}};
  for (const auto& ring : rings) {
    fc["features"].push_back({{"type", "Feature"},
                              {"properties", json::object()},
                              {"geometry", {{"type", "Polygon"}, {"coordinates", ring}}}});
  }
  return fc.dump();
}

// A square house from (x0, y0), `side` m, with a courtyard of `yard` m in its middle.
json house(double x0, double y0, double side, double yard = 0.0) {
  json rings = json::array();
  rings.push_back({{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}, {x0, y0}});
  if (yard > 0.0) {
    const double a = x0 + 0.5 * (side - yard), b = y0 + 0.5 * (side - yard);
    rings.push_back({{a, b}, {a + yard, b}, {a + yard, b + yard}, {a, b + yard}, {a, b}});
  }
  return rings;
}

// Water 0.5 m deep over a 40 m x 20 m flat box, moving east at 1 m/s, with walls round it.
json town_scene(const json& buildings) {
  json s = json::parse(R"({
    "name": "town", "end_time": 5,
    "domain": {"x_min": 0, "x_max": 40, "y_min": 0, "y_max": 20},
    "water": [{"rectangle": {"x_min": 0, "x_max": 40, "y_min": 0, "y_max": 20},
               "depth": 0.5, "spacing": 0.5, "velocity": [1.0, 0.0]}],
    "walls": [{"polyline": [[0, 0], [40, 0], [40, 20], [0, 20], [0, 0]]}],
    "output": {"path": "out.nc"}
  })");
  s["buildings"] = buildings;
  return s;
}

swemps::scenario::Scenario parse(const json& scene, const fs::path& dir) {
  return swemps::scenario::parse(scene.dump(), dir, "town");
}

std::string refusal(const json& scene, const fs::path& dir) {
  try {
    swemps::scenario::build(parse(scene, dir));
  } catch (const ScenarioError& e) {
    return e.json_path() + " | " + e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("buildings as walls: no water under them, and none gets in", "[scenario][buildings]") {
  swemps::testing::TempDir dir("buildings-walls");
  // A 6 m house with a 2 m courtyard, and a second house as a separate feature.
  write_text(dir.path() / "town.geojson",
             geojson({house(10.0, 7.0, 6.0, 2.0), house(25.0, 2.0, 4.0)}));
  auto built = swemps::scenario::build(
      parse(town_scene({{"file", "town.geojson"}, {"crs", "scene"}}), dir.path()));
  const auto& t = built.terrain;
  REQUIRE(t.building_footprints);
  CHECK(t.building_footprints->size() == 2);
  CHECK(t.building_walls.size() == 12);  // 4 + 4 (courtyard) + 4
  REQUIRE(t.buildings.size() == 1);
  CHECK(t.buildings[0].footprints == 2);
  auto& sim = built.simulation;
  const auto& p = sim.particles();
  // 80 x 40 lattice points; the houses hold 12 x 12 - 4 x 4 and 8 x 8 of them.
  CHECK(p.fluid_count() == 80 * 40 - (144 - 16) - 64);
  const auto inside = [&] {
    std::size_t n = 0;
    for (std::size_t i = 0; i < sim.particles().fluid_count(); ++i) {
      n += t.building_footprints->contains(sim.particles().x[i], sim.particles().y[i]) ? 1 : 0;
    }
    return n;
  };
  CHECK(inside() == 0);
  const double volume = sim.fluid_volume();
  for (int k = 0; k < 200 && sim.time() < 2.0; ++k) sim.advance(sim.stable_time_step());
  CHECK(sim.time() > 1.0);
  CHECK(inside() == 0);
  CHECK(sim.fluid_volume() == Approx(volume).epsilon(1e-12));
}

TEST_CASE("rain falls on no building that is a wall", "[scenario][buildings][rain]") {
  swemps::testing::TempDir dir("buildings-rain");
  write_text(dir.path() / "town.geojson", geojson({house(10.0, 7.0, 6.0, 2.0)}));
  json scene = town_scene({{"file", "town.geojson"}, {"crs", "scene"}});
  scene["rain"] = {{"rate_mm_h", 36}, {"spacing", 1.0}};
  auto built = swemps::scenario::build(parse(scene, dir.path()));
  const swemps::hydrology::Rain* rain = nullptr;
  for (const auto& e : built.simulation.effects()) {
    if (!rain) rain = dynamic_cast<const swemps::hydrology::Rain*>(e.get());
  }
  REQUIRE(rain);
  // 40 x 20 cells of 1 m; the roof holds 36 - 4 centres (the courtyard gets its rain).
  CHECK(rain->cell_count() == 800 - 32);
}

TEST_CASE("buildings raised into the bed", "[scenario][buildings]") {
  swemps::testing::TempDir dir("buildings-bed");
  swemps::io::write_geotiff(
      swemps::testing::sampled_field(40, 20, 1.0, [](double, double) { return 0.0; }),
      dir.path() / "flat.tif");
  write_text(dir.path() / "town.geojson", geojson({house(10.0, 7.0, 6.0)}));
  json scene =
      town_scene({{"file", "town.geojson"}, {"crs", "scene"}, {"as", "bed"}, {"height", 3.0}});
  scene["bed"] = {{"raster", "flat.tif"}};
  scene["water"][0].erase("depth");
  scene["water"][0]["fill"] = {{"rectangle", scene["water"][0]["rectangle"]}};
  scene["water"][0].erase("rectangle");
  scene["water"][0]["surface_elevation"] = 0.5;
  auto built = swemps::scenario::build(parse(scene, dir.path()));
  const auto& t = built.terrain;
  CHECK_FALSE(t.building_footprints);
  CHECK(t.building_walls.empty());
  REQUIRE(t.bed_raster);
  CHECK(t.bed->elevation(13.0, 10.0) == Approx(3.0));
  CHECK(t.bed->elevation(5.0, 10.0) == Approx(0.0));
  // Water filled to 0.5 m over the flat bed is none over a 3 m roof.
  CHECK(built.simulation.particles().fluid_count() > 2000);
  for (std::size_t i = 0; i < built.simulation.particles().fluid_count(); ++i) {
    const double x = built.simulation.particles().x[i], y = built.simulation.particles().y[i];
    CHECK_FALSE((x > 10.5 && x < 15.5 && y > 7.5 && y < 12.5));
  }
}

TEST_CASE("building files in another CRS move only when asked", "[scenario][buildings]") {
  swemps::testing::TempDir dir("buildings-crs");
  // UTM zone 16N, 1 m cells over 500000-500040 E, 4000000-4000020 N.
  swemps::io::write_geotiff(
      swemps::terrain::GriddedField(
          swemps::testing::grid_geometry(40, 20, 500000.0, 4000020.0, 1.0, 1.0),
          std::vector<double>(800, 0.0), swemps::testing::wkt_of("EPSG:32616")),
      dir.path() / "utm.tif");
  // The same house in longitude/latitude (no "crs" member) and in UTM with its "crs" member:
  // the central meridian of zone 16 is 87 W, where x = 500000 m.
  const double lat = 36.14480826;  // y = 4,000,010 m
  write_text(dir.path() / "lonlat.geojson",
             geojson({json::array({json::array(
                 {json::array({-87.0, lat}), json::array({-86.99994, lat}),
                  json::array({-86.99994, lat + 0.00005}), json::array({-87.0, lat + 0.00005}),
                  json::array({-87.0, lat})})})}));
  write_text(dir.path() / "utm.geojson",
             geojson({house(500010.0, 4000005.0, 5.0)}, "urn:ogc:def:crs:EPSG::32616"));
  json scene = town_scene({{"file", "utm.geojson"}});
  scene["domain"] = {{"x_min", 500000}, {"x_max", 500040}, {"y_min", 4000000}, {"y_max", 4000020}};
  scene["water"][0]["rectangle"] = scene["domain"];
  scene["walls"] = json::array();
  scene["bed"] = {{"raster", "utm.tif"}};
  {
    auto built = swemps::scenario::build(parse(scene, dir.path()));
    REQUIRE(built.terrain.building_footprints);
    CHECK(built.terrain.building_footprints->contains(500012.0, 4000007.0));
  }
  scene["buildings"] = {{"file", "lonlat.geojson"}};
  CHECK_THAT(refusal(scene, dir.path()),
             Contains("/buildings/file | ") && Contains("WGS 84") &&
                 Contains("set /buildings/reproject to true to transform it"));
  scene["buildings"]["reproject"] = true;
  {
    auto built = swemps::scenario::build(parse(scene, dir.path()));
    REQUIRE(built.terrain.building_footprints);
    const auto& ring = built.terrain.building_footprints->footprints()[0].outer;
    CHECK(ring[0][0] == Approx(500000.0).margin(0.01));
    CHECK(ring[0][1] == Approx(4000010.0).margin(0.01));
  }
}

TEST_CASE("buildings: one-line errors at the key", "[scenario][buildings]") {
  swemps::testing::TempDir dir("buildings-errors");
  write_text(dir.path() / "town.geojson", geojson({house(10.0, 7.0, 6.0)}));
  write_text(dir.path() / "points.geojson",
             R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
                 "geometry": {"type": "Point", "coordinates": [1, 2]}}]})");
  write_text(dir.path() / "not_vector.geojson", "walls, 3\n");
  const auto refused = [&](const json& buildings) {
    return refusal(town_scene(buildings), dir.path());
  };
  // GeoJSON without a "crs" member is longitude/latitude; the scene here has no CRS.
  CHECK_THAT(refused({{"file", "town.geojson"}}),
             Contains("/buildings/file | ") && Contains("set /buildings/crs to \"scene\""));
  CHECK_THAT(refused({{"file", "missing.geojson"}}), Contains("/buildings/file"));
  CHECK_THAT(refused({{"file", "points.geojson"}, {"crs", "scene"}}),
             Contains("holds no polygon (1 features)"));
  CHECK_THAT(refused({{"file", "not_vector.geojson"}, {"crs", "scene"}}),
             Contains("not a vector file GDAL can read"));
  CHECK_THAT(refused({{"file", "town.geojson"}, {"crs", "scene"}, {"layer", "roads"}}),
             Contains("has no layer 'roads'"));
  CHECK_THAT(refused({{"file", "town.geojson"}, {"crs", "scene"}, {"as", "bed"}}),
             Contains("/buildings/as | ") && Contains("without a bed raster"));
  const auto parse_refusal = [&](const json& buildings) {
    try {
      parse(town_scene(buildings), dir.path());
    } catch (const ScenarioError& e) {
      return e.json_path() + " | " + e.what();
    }
    return std::string("accepted");
  };
  CHECK_THAT(parse_refusal({{"file", "town.geojson"}, {"as", "bed"}, {"condition", "no_slip"}}),
             Contains("/buildings/condition"));
  CHECK_THAT(parse_refusal({{"file", "town.geojson"}, {"height", 3}}),
             Contains("/buildings/height"));
  CHECK_THAT(parse_refusal({{"file", "town.geojson"}, {"crs", "scene"}, {"reproject", true}}),
             Contains("/buildings/reproject"));
  CHECK_THAT(parse_refusal({{"file", "town.geojson"}, {"as", "roof"}}), Contains("/buildings/as"));
  CHECK_THAT(parse_refusal(json::array({{{"file", "town.geojson"}}, 3})), Contains("/buildings/1"));
}

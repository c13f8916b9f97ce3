// A scene with an earthquake's fault planes: the floor after the rupture is the bed the water
// sees, the water keeps its still depth over it (so its surface moves with the floor), planes
// placed by longitude and latitude land where a GIS puts them, and what cannot be meant is
// refused in one line.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "../support/broken_scenes.hpp"
#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/geographic.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/tsunami/okada.hpp"

using namespace swemps;
using Catch::Matchers::Contains;

namespace {

// A sea 2 km deep over a flat floor, 200 km x 100 km, 4 km lattice, and one thrust under it.
const char* kSea = R"({"end_time": 1,
  "domain": {"x_min": 0, "x_max": 200000, "y_min": 0, "y_max": 100000},
  "bed": {"plane": {"elevation": -2000}},
  "water": [{"fill": {"rectangle": {"x_min": 0, "x_max": 200000, "y_min": 0, "y_max": 100000}},
             "surface_elevation": 0, "spacing": 4000}],
  "fault_source": {"planes": [{"x": 100000, "y": 50000, "depth": 5000, "strike": 0, "dip": 20,
                                "rake": 90, "slip": 5, "length": 60000, "width": 40000}]}})";

}  // namespace

TEST_CASE("a fault source lifts the floor and the sea over it", "[scenario][tsunami]") {
  const auto scene = testing::parse_text(kSea);
  auto built = scenario::build(scene);
  const tsunami::FaultSource source(
      {{{100000.0, 50000.0}, 5000.0, 0.0, 20.0, 90.0, 5.0, 60000.0, 40000.0}});
  const auto& p = built.simulation.particles();
  REQUIRE(p.fluid_count() == 50u * 25u);
  double highest = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double uz = source.vertical_displacement(p.x[i], p.y[i]);
    // The floor under the particle is the floor after the rupture (read from the displacement
    // sampled at the 4 km spacing, whose cell centres the lattice's points are: exact there);
    // the water keeps its 2 km.
    CHECK(p.bed[i] == Approx(-2000.0 + uz).epsilon(1e-12));
    CHECK(p.volume[i] / (4000.0 * 4000.0) == Approx(2000.0).epsilon(1e-12));
    CHECK(built.terrain.bed->elevation(p.x[i], p.y[i]) == Approx(-2000.0 + uz).epsilon(1e-12));
    highest = std::max(highest, uz);
  }
  CHECK(highest > 0.5);  // the thrust's uplift reaches the lattice
  // A level floor that a rupture has deformed is not level: the bed term runs.
  bool bed_term = false;
  for (const auto& effect : built.simulation.effect_times())
    bed_term = bed_term || effect.name.find("bed slope") != std::string::npos;
  CHECK(bed_term);
}

TEST_CASE("a fault plane placed by longitude and latitude lands where a GIS puts it",
          "[scenario][tsunami]") {
  // UTM zone 16N: the zone's central meridian is 87 W, where true north is the grid's; 2 degrees
  // east of it, at 36 N, grid north lies about 1.2 degrees east of true north (the convergence,
  // sin(36) x 2 degrees), so true north is 1.2 degrees west of the map's +y.
  const std::string wkt = testing::wkt_of("EPSG:32616");
  const auto centre = io::project_geographic(-87.0, 36.0, wkt);
  CHECK(centre.x_m == Approx(500000.0).margin(1e-6));
  CHECK(centre.north_bearing_deg == Approx(0.0).margin(1e-6));
  const auto east = io::project_geographic(-85.0, 36.0, wkt);
  CHECK(east.north_bearing_deg == Approx(-2.0 * std::sin(36.0 * M_PI / 180.0)).margin(0.02));
  CHECK_THROWS_AS(io::project_geographic(-85.0, 36.0, ""), std::runtime_error);
}

TEST_CASE("a fault source that cannot be meant is refused at its key", "[scenario][tsunami]") {
  const std::string head = R"({"end_time": 1,
    "domain": {"x_min": 0, "x_max": 200000, "y_min": 0, "y_max": 100000},
    "water": [{"rectangle": {"x_min": 0, "x_max": 200000, "y_min": 0, "y_max": 100000},
               "depth": 2000, "spacing": 4000}],
    "fault_source": )";
  const auto with = [&](const std::string& source) { return head + source + "}"; };
  const std::string plane = R"("depth": 5000, "strike": 0, "dip": 20, "rake": 90, "slip": 5,
                               "length": 6e4, "width": 4e4)";
  testing::check_broken(
      {{"a plane outside the domain",
        with(R"({"planes": [{"x": 300000, "y": 5e4, )" + plane + "}]}"), "/fault_source/planes/0",
        "inside the domain"},
       {"no planes", with(R"({"planes": []})"), "/fault_source/planes", "non-empty array"},
       {"a dip of 0", with(R"({"planes": [{"x": 1e5, "y": 5e4, "depth": 5000, "strike": 0, "dip": 0,
                             "rake": 90, "slip": 5, "length": 6e4, "width": 4e4}]})"),
        "/fault_source/planes/0/dip", "a number in (0, 90]"},
       {"no slip", with(R"({"planes": [{"x": 1e5, "y": 5e4, "depth": 5000, "strike": 0, "dip": 20,
                             "rake": 90, "length": 6e4, "width": 4e4}]})"),
        "/fault_source/planes/0/slip", "the slip"},
       {"both kinds of position",
        with(R"({"planes": [{"x": 1e5, "y": 5e4, "longitude": 140, "latitude": 38, )" + plane +
             "}]}"),
        "/fault_source/planes/0", "or as \"longitude\""},
       {"a Poisson's ratio of 0.5",
        with(R"({"poisson_ratio": 0.5, "planes": [{"x": 1e5, "y": 5e4, )" + plane + "}]}"),
        "/fault_source/poisson_ratio", "(0, 0.5)"},
       {"a fault under the Navier-Stokes tank",
        R"({"end_time": 1, "model": "ns", "dimension": 2,
            "domain": {"x_min": 0, "x_max": 4, "y_min": 0, "y_max": 1}, "ns": {"spacing": 0.1},
            "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
                       "depth": 0.5}],
            "fault_source": {"planes": [{"x": 1, "y": 0.5, "depth": 1, "strike": 0, "dip": 20,
                                         "rake": 90, "slip": 0.1, "length": 1, "width": 1}]}})",
        "/fault_source", "a fault source"}},
      true);
  SECTION("longitude and latitude in a scene without a CRS") {
    const auto scene = testing::parse_text(
        with(R"({"planes": [{"longitude": 140, "latitude": 38, )" + plane + "}]}"));
    try {
      scenario::build(scene);
      FAIL("no error");
    } catch (const scenario::ScenarioError& e) {
      CHECK(e.json_path() == "/fault_source/planes/0");
      CHECK_THAT(std::string(e.what()), Contains("without a CRS"));
    }
  }
}

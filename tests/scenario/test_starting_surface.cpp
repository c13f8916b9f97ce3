// A scene's water starting displaced and moving, as tsunami scenes start: a solitary wave
// (NTHMP benchmark problem 1's profile and velocity), a displacement raster added to the
// still water, velocity rasters; and the one-line errors for what cannot be meant.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "../support/broken_scenes.hpp"
#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/tsunami/solitary_wave.hpp"

using namespace swemps;
using Catch::Matchers::Contains;

namespace {

// A channel 60 m x 2 m of still water 1 m deep on a flat bed, lattice 0.25 m; `extra` adds
// keys to the water body.
std::string channel(const std::string& extra, const std::string& depth = R"("depth": 1.0)") {
  return R"({"end_time": 1, "domain": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2},
    "water": [{"rectangle": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2}, )" +
         depth + R"(, "spacing": 0.25)" + extra + "}]}";
}

scenario::Scenario parse_in(const testing::TempDir& dir, const std::string& text) {
  return scenario::parse(text, dir.path(), "start");
}

// A raster in local metres over [0, 60] x [0, 2] in 0.5 m cells, f at each cell centre.
template <class F>
void write_raster(const testing::TempDir& dir, const std::string& name, const F& f,
                  std::size_t columns = 120, std::size_t rows = 4) {
  io::write_geotiff(testing::sampled_field(columns, rows, 0.5, f), dir.path() / name);
}

std::string build_error(const scenario::Scenario& scene, std::string* path) {
  try {
    scenario::build(scene);
  } catch (const scenario::ScenarioError& e) {
    *path = e.json_path();
    return e.what();
  }
  FAIL("build did not throw");
  return {};
}

}  // namespace

TEST_CASE("a solitary wave starts on the still water with its profile and velocity",
          "[scenario][tsunami]") {
  const auto scene = testing::parse_text(
      channel(R"(, "solitary_wave": {"height": 0.05, "crest": [30, 1], "direction": [1, 0]})"));
  auto built = scenario::build(scene);
  const auto& p = built.simulation.particles();
  // The still depth under the crest is the body's, 1 m.
  const tsunami::SolitaryWave wave({0.05, 1.0, {30.0, 1.0}, {1.0, 0.0}}, 9.81);
  REQUIRE(p.fluid_count() == 240u * 8u);
  double rise = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    // Geometric volumes: each particle carries its lattice cell's depth, 1 m + eta.
    const double eta = wave.elevation(p.x[i], p.y[i]);
    CHECK(p.volume[i] / 0.0625 == Approx(1.0 + eta).epsilon(1e-14));
    CHECK(p.u[i] == Approx(std::sqrt(9.81) * eta).epsilon(1e-14));
    CHECK(p.v[i] == 0.0);
    rise += p.volume[i] - 0.0625;
  }
  // The wave's volume: H d / gamma * 2 per metre of crest, on a 2 m wide channel.
  const double gamma = std::sqrt(3.0 * 0.05 / 4.0);
  CHECK(rise == Approx(2.0 * 0.05 * 2.0 / gamma).epsilon(1e-3));
  CHECK(built.volumes.geometric_m3 == Approx(120.0 + rise).epsilon(1e-12));
}

TEST_CASE("a solitary wave over a sea filled to a level takes the depth under its crest",
          "[scenario][tsunami]") {
  // The bed falls 10 % towards +x from 1 m at x = 0: the shore at x = 10, still water 2 m deep
  // under x = 30.
  const auto scene = testing::parse_text(
      R"({"end_time": 1, "domain": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2},
    "bed": {"plane": {"elevation": 1.0, "slope": [-0.1, 0]}},
    "water": [{"fill": {"rectangle": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2}},
               "surface_elevation": 0, "spacing": 0.25,
               "solitary_wave": {"height": 0.1, "crest": [30, 0], "direction": [-1, 0]}}]})");
  auto built = scenario::build(scene);
  const auto& p = built.simulation.particles();
  const tsunami::SolitaryWave wave({0.1, 2.0, {30.0, 0.0}, {-1.0, 0.0}}, 9.81);
  REQUIRE(p.fluid_count() > 0);
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double still = -(1.0 - 0.1 * p.x[i]);
    CHECK(p.volume[i] / 0.0625 == Approx(still + wave.elevation(p.x[i], p.y[i])).epsilon(1e-12));
    CHECK(p.u[i] == Approx(-std::sqrt(9.81 / 2.0) * wave.elevation(p.x[i], p.y[i])).epsilon(1e-12));
  }
  SECTION("a crest over ground the level leaves dry is an error at the wave") {
    auto dry = scene;
    std::get<scenario::SolitaryWaveStart>(dry.water[0].displacement).crest_m = {5.0, 1.0};
    std::string path;
    CHECK_THAT(build_error(dry, &path), Contains("under the crest point"));
    CHECK(path == "/water/0/solitary_wave");
  }
}

TEST_CASE("a displacement raster raises the still water where it holds water, not the land",
          "[scenario][tsunami]") {
  testing::TempDir dir("displacement");
  // The bed rises 5 % towards +x from -1 m at x = 0: dry beyond x = 20 m (level 0).
  // The raster lifts the surface by 0.2 m for x < 30, nodata for y > 1.5, nothing beyond.
  write_raster(dir, "eta.tif", [](double x, double y) {
    if (y > 1.5) return std::numeric_limits<double>::quiet_NaN();
    return x < 30.0 ? 0.2 : 0.0;
  });
  const std::string text =
      R"({"end_time": 1, "domain": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2},
    "bed": {"plane": {"elevation": -1, "slope": [0.05, 0]}},
    "water": [{"fill": {"rectangle": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2}},
               "surface_elevation": 0, "spacing": 0.25, "min_depth": 0.01,
               "surface_displacement": "eta.tif"}]})";
  auto built = scenario::build(parse_in(dir, text));
  const auto& p = built.simulation.particles();
  REQUIRE(p.fluid_count() > 0);
  std::size_t raised = 0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double still = -(-1.0 + 0.05 * p.x[i]);
    // No water where the still level leaves the land dry, however much the raster lifts it.
    CHECK(still > 0.01);
    // Cells astride x = 30 or y = 1.5 interpolate; away from them the rise is 0.2 or 0.
    const bool lifted = p.x[i] < 29.75 && p.y[i] < 1.25;
    const bool still_water = p.x[i] > 30.25 || p.y[i] > 1.75;
    if (lifted) ++raised;
    if (lifted) CHECK(p.volume[i] / 0.0625 == Approx(still + 0.2).epsilon(1e-12));
    if (still_water) CHECK(p.volume[i] / 0.0625 == Approx(still).epsilon(1e-12));
  }
  CHECK(raised > 100u);

  SECTION("a raster that misses the domain is an error at its key") {
    io::write_geotiff(terrain::GriddedField(testing::grid_geometry(4, 4, 100.0, 104.0, 1.0, 1.0),
                                            std::vector<double>(16, 0.1)),
                      dir.path() / "far.tif");
    auto scene = parse_in(dir, text);
    std::get<scenario::DisplacementRaster>(scene.water[0].displacement).raster.path =
        dir.path() / "far.tif";
    std::string path;
    CHECK_THAT(build_error(scene, &path), Contains("which misses the domain"));
    CHECK(path == "/water/0/surface_displacement");
  }
  SECTION("a raster that is nodata over the whole domain is an error at its key") {
    write_raster(dir, "void.tif",
                 [](double, double) { return std::numeric_limits<double>::quiet_NaN(); });
    auto scene = parse_in(dir, text);
    std::get<scenario::DisplacementRaster>(scene.water[0].displacement).raster.path =
        dir.path() / "void.tif";
    std::string path;
    CHECK_THAT(build_error(scene, &path), Contains("nodata over the whole domain"));
    CHECK(path == "/water/0/surface_displacement");
  }
}

TEST_CASE("velocity rasters set each particle's starting velocity", "[scenario][tsunami]") {
  testing::TempDir dir("velocity");
  write_raster(dir, "u.tif", [](double x, double) { return x < 30.0 ? 0.3 : 0.0; });
  // Nodata in the north: still water there.
  write_raster(dir, "v.tif", [](double, double y) {
    return y > 1.5 ? std::numeric_limits<double>::quiet_NaN() : -0.2;
  });
  auto built =
      scenario::build(parse_in(dir, channel(R"(, "velocity": {"u": "u.tif", "v": "v.tif"})")));
  const auto& p = built.simulation.particles();
  REQUIRE(p.fluid_count() == 240u * 8u);
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    if (p.x[i] < 29.75) CHECK(p.u[i] == Approx(0.3).epsilon(1e-12));
    if (p.x[i] > 30.25) CHECK(p.u[i] == 0.0);
    if (p.y[i] < 1.25) CHECK(p.v[i] == Approx(-0.2).epsilon(1e-12));
    if (p.y[i] > 1.75) CHECK(p.v[i] == 0.0);
    CHECK(p.volume[i] == Approx(0.0625).epsilon(1e-14));
  }
}

TEST_CASE("a starting wave or velocity that cannot be meant is refused at its key",
          "[scenario][tsunami]") {
  const std::string wave =
      R"(, "solitary_wave": {"height": 0.05, "crest": [30, 1], "direction": [1, 0]})";
  testing::check_broken(
      {{"both a raster and a wave", channel(wave + R"(, "surface_displacement": "eta.tif")"),
        "/water/0", "at most one of them"},
       {"a still depth no deeper than the height",
        channel(R"(, "solitary_wave": {"height": 0.5, "depth": 0.5, "crest": [30, 1],
                                         "direction": [1, 0]})"),
        "/water/0/solitary_wave/depth", "greater than its height"},
       {"no direction",
        channel(R"(, "solitary_wave": {"height": 0.05, "crest": [30, 1], "direction": [0, 0]})"),
        "/water/0/solitary_wave/direction", "non-zero"},
       {"a crest outside the domain",
        channel(R"(, "solitary_wave": {"height": 0.05, "crest": [70, 1], "direction": [1, 0]})"),
        "/water/0/solitary_wave/crest", "a wave's crest point inside the domain"},
       {"no crest", channel(R"(, "solitary_wave": {"height": 0.05, "direction": [1, 0]})"),
        "/water/0/solitary_wave/crest", "on the crest line"},
       {"a wave on a depth raster",
        R"({"end_time": 1, "domain": {"x_min": 0, "x_max": 60, "y_min": 0, "y_max": 2},
            "water": [{"depth_raster": "h.tif", "spacing": 0.25)" +
            wave + "}]}",
        "/water/0/solitary_wave", "a depth raster gives the displaced depth itself"},
       {"a velocity object with a third key",
        channel(R"(, "velocity": {"u": "u.tif", "v": "v.tif", "w": "w.tif"})"),
        "/water/0/velocity/w", "one of the keys"},
       {"a velocity object without v", channel(R"(, "velocity": {"u": "u.tif"})"),
        "/water/0/velocity/v", "north velocity"},
       {"a wave in the Navier-Stokes tank",
        R"({"end_time": 1, "model": "ns", "dimension": 2,
            "domain": {"x_min": 0, "x_max": 4, "y_min": 0, "y_max": 1}, "ns": {"spacing": 0.1},
            "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
                       "depth": 0.5, "solitary_wave": {"height": 0.05, "crest": [0.5, 0.5],
                                                       "direction": [1, 0]}}]})",
        "/water/0/solitary_wave", "a starting wave"}},
      true);
}

// Tests of the sea boundary's parts: the level series, the settings it refuses, its buffer and
// ghosts beside a sea at rest, the water it takes out and lets in, and the scene keys that
// make one.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/broken_scenes.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/boundaries/sea_boundary.hpp"
#include "swemps/io/hydrograph_csv.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/swe/simulation.hpp"

using namespace swemps;
using boundaries::LevelSeries;
using boundaries::SeaBoundary;
using boundaries::SeaBoundarySettings;
using Catch::Contains;

namespace {

// The east end of a channel 1 m wide, at x = 10.
SeaBoundarySettings east_end() {
  SeaBoundarySettings s;
  s.from = {10.0, 0.0};
  s.to = {10.0, 1.0};
  s.outward = {1.0, 0.0};
  s.spacing_m = 0.1;
  s.still_level_m = 0.5;
  return s;
}

// A channel 10 m long and 1 m wide, open or held at a level at its east end.
std::string channel(const std::string& boundary, double end_time = 2.0) {
  return R"({"end_time": )" + std::to_string(end_time) + R"(,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
               "depth": 0.5, "spacing": 0.1}],
    "walls": [{"polyline": [[10, 0], [0, 0], [0, 1], [10, 1]]}],
    "sea_boundaries": [)" +
         boundary + R"(],
    "output": {"path": "sea.nc"}})";
}

const SeaBoundary& sea_boundary_of(const swe::Simulation& sim) {
  for (const auto& effect : sim.effects()) {
    if (const auto* sea = dynamic_cast<const SeaBoundary*>(effect.get())) return *sea;
  }
  throw std::logic_error("no sea boundary");
}

}  // namespace

TEST_CASE("level series: linear between points, held beyond the ends", "[sea_boundary]") {
  const LevelSeries series({{10.0, 1.0}, {20.0, 2.0}, {30.0, -1.0}});
  CHECK(series.level(0.0) == 1.0);
  CHECK(series.level(15.0) == Approx(1.5));
  CHECK(series.level(25.0) == Approx(0.5));
  CHECK(series.level(40.0) == -1.0);
  CHECK(series.end_time() == 30.0);
  CHECK(series.last_level() == -1.0);
  CHECK_THROWS_WITH(LevelSeries({}), Contains("no points"));
  CHECK_THROWS_WITH(LevelSeries({{0.0, 1.0}, {0.0, 2.0}}),
                    Contains("point 2") && Contains("not after the previous point's 0 s"));
  CHECK_THROWS_WITH(LevelSeries({{0.0, NAN}}), Contains("level is not a finite number"));
}

TEST_CASE("a level series file: time and level columns, negative levels allowed",
          "[sea_boundary][io]") {
  testing::TempDir dir("level-series");
  const auto write = [&](const std::string& text) {
    const auto path = dir.path() / "level.csv";
    std::ofstream(path) << text;
    return path;
  };
  const auto points = io::read_level_csv(write("# tide\ntime_s,level_m\n0,-0.5\n60,0.25\n"));
  REQUIRE(points.size() == 2);
  CHECK(points[0][1] == -0.5);
  CHECK(points[1][0] == 60.0);
  CHECK_THROWS_WITH(io::read_level_csv(write("time,level\n0,1\n0,2\n")),
                    Contains(".csv:3: time 0 s is not after the previous time 0 s"));
  CHECK_THROWS_WITH(io::read_level_csv(write("time,level [ft]\n0,1\n")),
                    Contains("levels must be in m, not 'ft'"));
  CHECK_THROWS_WITH(io::read_level_csv(write("time,discharge\n0,1\n")),
                    Contains("neither time (time, t) nor level"));
}

TEST_CASE("sea boundary: settings are validated", "[sea_boundary]") {
  auto s = east_end();
  s.to = s.from;
  CHECK_THROWS_WITH(SeaBoundary(s), Contains("zero or non-finite length"));
  s = east_end();
  s.outward = {1.0, 1.0};
  CHECK_THROWS_WITH(SeaBoundary(s), Contains("not normal to the line"));
  s = east_end();
  s.spacing_m = 0.0;
  CHECK_THROWS_WITH(SeaBoundary(s), Contains("spacing"));
  s = east_end();
  s.still_level_m = INFINITY;
  CHECK_THROWS_WITH(SeaBoundary(s), Contains("still level"));
  const SeaBoundary open(east_end());
  CHECK(open.stretch_count() == 10);
  CHECK(open.boundary_level(1e6) == 0.5);
  s = east_end();
  s.level = LevelSeries({{0.0, 0.5}, {10.0, 0.7}});
  const SeaBoundary level(s);
  CHECK(level.boundary_level(5.0) == Approx(0.6));
  CHECK(level.boundary_level(20.0) == 0.7);  // then open about the last level
}

TEST_CASE("a sea at rest stays at rest beside an open boundary", "[sea_boundary]") {
  auto sim = scenario::make_simulation(
      testing::parse_text(channel(R"({"line": [[10, 0], [10, 1]], "type": "open"})")));
  sim.refresh();
  // The depth the lattice sums to, a few 1e-5 under 0.5 (the kernel's sum over a lattice).
  const double summed = sim.particles().depth.front();
  sim.advance_to(2.0, [] {});
  sim.refresh();
  const auto& p = sim.particles();
  double fastest = 0.0, furthest = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    fastest = std::max(fastest, std::hypot(p.u[i], p.v[i]));
    furthest = std::max(furthest, std::abs(p.depth[i] - summed));
  }
  // The buffer holds water the lattice sums as the sea's own: nothing moves, nothing crosses.
  // Without it (a bare edge) the channel drains at once; with the buffer carrying the still
  // depth times its cell, not the lattice's summed area, the end row moved at 6e-5 m/s.
  CHECK(fastest < 1e-8);
  CHECK(furthest < 1e-9);
  const auto& sea = sea_boundary_of(sim);
  CHECK(sea.particles_added() == 0);
  CHECK(sea.particles_removed() == 0);
  // Three rows of ten beyond the line, at least the particles' reach deep.
  CHECK(sea.buffer_count() >= 30);
}

TEST_CASE("a level boundary lets water in as its level rises and out as it falls, booking both",
          "[sea_boundary]") {
  auto sim = scenario::make_simulation(
      testing::parse_text(channel(R"({"line": [[10, 0], [10, 1]], "type": "level",
                  "series": [[0, 0.5], [1, 0.55], [2, 0.45]]})",
                                  3.0)));
  double rose = 0.0;
  sim.advance_to(1.0, [] {});
  rose = sim.fluid_volume() - 5.0;
  sim.advance_to(3.0, [] {});
  const auto& sea = sea_boundary_of(sim);
  CHECK(sea.particles_added() > 0);
  CHECK(sea.particles_removed() > 0);
  // A rise of 5 cm a second over 1 s fills the channel's near end: water came in.
  CHECK(rose > 0.02);
  CHECK(sim.ledger().added_m3 == sea.volume_added());
  CHECK(sim.ledger().removed_m3 == sea.volume_removed());
  CHECK(std::abs(sim.relative_volume_change()) < 1e-12);
}

TEST_CASE("sea boundaries that cannot be meant are refused at their key", "[sea_boundary]") {
  const auto with = [](const std::string& b) { return channel(b); };
  testing::check_broken(
      {{"no type", with(R"({"line": [[10, 0], [10, 1]]})"), "/sea_boundaries/0/type",
        "\"open\" (waves leave) or \"level\""},
       {"a type of its own", with(R"({"line": [[10, 0], [10, 1]], "type": "tide"})"),
        "/sea_boundaries/0/type", "open"},
       {"a level boundary without a series", with(R"({"line": [[10, 0], [10, 1]],
                                                      "type": "level"})"),
        "/sea_boundaries/0", "exactly one of \"series\" or \"series_csv\""},
       {"a series out of order", with(R"({"line": [[10, 0], [10, 1]], "type": "level",
                                          "series": [[0, 0.5], [5, 0.6], [5, 0.7]]})"),
        "/sea_boundaries/0/series/2/0", "a time greater than the previous point's 5"},
       {"a series on an open boundary", with(R"({"line": [[10, 0], [10, 1]], "type": "open",
                                                 "series": [[0, 0.5]]})"),
        "/sea_boundaries/0/series", "\"type\": \"level\""},
       {"a still level on a level boundary", with(R"({"line": [[10, 0], [10, 1]],
          "type": "level", "level": 0.5, "series": [[0, 0.5]]})"),
        "/sea_boundaries/0/level", "no \"level\""},
       {"a line of three points", with(R"({"line": [[10, 0], [10, 0.5], [10, 1]],
                                           "type": "open"})"),
        "/sea_boundaries/0/line", "exactly 2"},
       {"a slanted line", with(R"({"line": [[10, 0], [9.5, 1]], "type": "open"})"),
        "/sea_boundaries/0/line", "a line along x or along y"},
       {"a line outside the domain", with(R"({"line": [[12, 0], [12, 1]], "type": "open"})"),
        "/sea_boundaries/0/line/0", "inside the domain"},
       {"two of one name", with(R"({"name": "sea", "line": [[10, 0], [10, 1]], "type": "open"},
                                   {"name": "sea", "line": [[0, 0], [0, 1]], "type": "open"})"),
        "/sea_boundaries/1/name", "a name no other sea boundary has"},
       {"a sea boundary under the seed scheme",
        R"({"end_time": 1, "numerics": {"scheme": "seed"},
            "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
            "water": [{"rectangle": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
                       "depth": 0.5, "spacing": 0.1}],
            "sea_boundaries": [{"line": [[10, 0], [10, 1]], "type": "open"}]})",
        "/sea_boundaries", "the conservative scheme"},
       {"a sea boundary in the Navier-Stokes tank",
        R"({"end_time": 1, "model": "ns", "dimension": 2,
            "domain": {"x_min": 0, "x_max": 4, "y_min": 0, "y_max": 1}, "ns": {"spacing": 0.1},
            "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
                       "depth": 0.5}],
            "sea_boundaries": [{"line": [[4, 0], [4, 1]], "type": "open"}]})",
        "/sea_boundaries", "sea boundaries"}},
      true);
  const auto build_error = [](const std::string& text, std::string& path) {
    try {
      scenario::build(testing::parse_text(text));
    } catch (const scenario::ScenarioError& e) {
      path = e.json_path();
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string path;
  SECTION("an open boundary with no water beside it and no level") {
    CHECK_THAT(build_error(R"({"end_time": 1,
        "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
        "water": [{"rectangle": {"x_min": 0, "x_max": 5, "y_min": 0, "y_max": 1},
                   "depth": 0.5, "spacing": 0.1}],
        "sea_boundaries": [{"line": [[10, 0], [10, 1]], "type": "open"}],
        "output": {"path": "sea.nc"}})",
                           path),
               Contains("the level of the sea at rest"));
    CHECK(path == "/sea_boundaries/0/level");
  }
  SECTION("a series file that cannot be read") {
    CHECK_THAT(build_error(channel(R"({"line": [[10, 0], [10, 1]], "type": "level",
                                       "series_csv": "no-such-tide.csv"})"),
                           path),
               Contains("no-such-tide.csv"));
    CHECK(path == "/sea_boundaries/0/series_csv");
  }
  SECTION("a line across the domain's centre") {
    CHECK_THAT(build_error(channel(R"({"line": [[5, 0], [5, 1]], "type": "open"})"), path),
               Contains("runs through the domain's centre"));
    CHECK(path == "/sea_boundaries/0/line");
  }
}

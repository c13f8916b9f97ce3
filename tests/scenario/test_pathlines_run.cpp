// Pathlines in a run (docs/provenance.md, "Pathlines"): a particle in uniform flow is followed
// exactly, a line ends where its particle leaves through an outflow line, lines chosen by
// source stay on their side of a wall through splits and merges, a restarted run writes the
// same lines, and a scene that asks for what cannot be followed is refused.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "../support/two_lanes.hpp"
#include "swemps/scenario/scenario.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Water 1 m deep moving at 1 m/s along a channel between two slip walls, 200 m of it from
// x = 0; an outflow line at x = 150. The pathlines follow every particle between x = 90 and
// 150. Until a wave from the water's ends or the outflow line reaches them, the middle moves
// as one: each particle by exactly (t, 0).
json uniform_channel() {
  return json::parse(R"({
    "name": "uniform channel",
    "end_time": 3,
    "domain": {"x_min": -50, "x_max": 250, "y_min": 0, "y_max": 20},
    "walls": [{"polyline": [[-50, 0], [250, 0]]}, {"polyline": [[-50, 20], [250, 20]]}],
    "water": [{"depth": 1.0, "spacing": 1.0, "velocity": [1.0, 0.0],
               "rectangle": {"x_min": 0, "x_max": 200, "y_min": 0, "y_max": 20}}],
    "outflow": [{"line": [[150, 0], [150, 20]]}],
    "output": {"path": "channel.nc", "interval": 1, "grid": {"spacing": 2},
               "particles": false,
               "pathlines": {"polygon": [[90, 0], [150, 0], [150, 20], [90, 20]],
                             "count": 5000, "interval": 0.25, "path": "channel.geojson"}}
  })");
}

// The two-lane channel (tests/support/two_lanes.hpp: a wall between two lanes, each with a
// lake and a river, rain, an outflow, splitting and merging), following 60 particles of the
// north lake a vertex every quarter second.
json two_lanes() {
  json scene = swemps::testing::two_lane_channel();
  scene["output"]["interval"] = 2;
  scene["output"]["particles"] = false;
  scene["output"]["pathlines"] = {
      {"source", "north lake"}, {"count", 60}, {"interval", 0.25}, {"path", "lanes.geojson"}};
  return scene;
}

fs::path write_scene(const fs::path& dir, const std::string& name, const json& scene) {
  const fs::path file = dir / name;
  std::ofstream(file) << scene.dump(2);
  return file;
}

json read_json(const fs::path& file) {
  std::ifstream in(file);
  REQUIRE(in.good());
  return json::parse(in);
}

std::string cli() { return std::string(SWEMPS_CLI); }

}  // namespace

TEST_CASE("a pathline in uniform flow follows it exactly, and ends where it leaves",
          "[pathlines][cli]") {
  swemps::testing::TempDir dir("pathlines");
  const auto scene = write_scene(dir.path(), "channel.json", uniform_channel());
  const auto run = swemps::testing::run_command(cli() + " run -q " + scene.string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  const json lines = read_json(dir.path() / "channel.geojson");
  const auto& features = lines.at("features");
  // Every particle in the polygon: 60 columns of 20 at 1 m.
  REQUIRE(features.size() == 1200);
  std::size_t uniform = 0, left = 0;
  for (const auto& f : features) {
    const auto& points = f.at("geometry").at("coordinates");
    const auto& times = f.at("properties").at("time_s");
    REQUIRE(points.size() == times.size());
    const double x0 = points[0][0], y0 = points[0][1];
    if (x0 < 110.0) {
      // Far from every wave: the particle moves by (t, 0), to round-off, and is followed to
      // the end at every quarter second.
      ++uniform;
      REQUIRE(times.size() == 13);
      CHECK(f.at("properties").at("fate") == "in the domain");
      for (std::size_t k = 0; k < times.size(); ++k) {
        const double t = times[k];
        CHECK(t == Approx(0.25 * static_cast<double>(k)).margin(0.2));
        CHECK(std::abs(static_cast<double>(points[k][0]) - (x0 + t)) < 1e-9);
        CHECK(std::abs(static_cast<double>(points[k][1]) - y0) < 1e-9);
      }
      CHECK(times.back() == 3.0);
    }
    if (x0 > 147.6) {
      // Within 3 m of the outflow line (less a step): removed there, the line ending just past
      // it.
      ++left;
      CHECK(f.at("properties").at("fate") == "left the domain");
      const double end_x = points.back()[0];
      CHECK(end_x >= 150.0);
      CHECK(end_x < 150.5);
      CHECK(static_cast<double>(times.back()) < 3.0);
    }
  }
  CHECK(uniform == 400);
  CHECK(left == 40);

  // check says what a run would follow; a polygon from a file chooses as one given inline.
  std::ofstream(dir.path() / "area.geojson") << R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon",
       "coordinates": [[[90, 0], [110, 0], [110, 20], [90, 20], [90, 0]]]}}]})";
  json from_file = uniform_channel();
  from_file["output"]["pathlines"]["polygon"] = {{"file", "area.geojson"}, {"crs", "scene"}};
  const auto file_scene = write_scene(dir.path(), "from_file.json", from_file);
  const auto checked = swemps::testing::run_command(cli() + " check " + file_scene.string());
  INFO(checked.output);
  CHECK(checked.status == 0);
  CHECK_THAT(checked.output, Contains("400 particles, chosen at the start, a vertex every 0.25 s"));
}

TEST_CASE("pathlines chosen by source stay with their water through splits and merges",
          "[pathlines][cli]") {
  swemps::testing::TempDir dir("pathlines");
  const auto scene = write_scene(dir.path(), "lanes.json", two_lanes());
  const auto run = swemps::testing::run_command(cli() + " run -q " + scene.string());
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK_THAT(run.output, !Contains("no particle"));
  const json lines = read_json(dir.path() / "lanes.geojson");
  const auto& features = lines.at("features");
  REQUIRE(features.size() == 60);
  double longest_jump = 0.0;
  for (const auto& f : features) {
    CHECK(f.at("properties").at("source") == "north lake");
    const auto& points = f.at("geometry").at("coordinates");
    REQUIRE(points.size() >= 2);
    for (std::size_t k = 0; k < points.size(); ++k) {
      // The north lane's water never crosses the wall at y = 5.
      CHECK(static_cast<double>(points[k][1]) > 5.0);
      if (k > 0) {
        const double dx = static_cast<double>(points[k][0]) - points[k - 1][0].get<double>();
        const double dy = static_cast<double>(points[k][1]) - points[k - 1][1].get<double>();
        longest_jump = std::max(longest_jump, std::hypot(dx, dy));
      }
    }
  }
  // A quarter second at the lane's few m/s, and a split's daughter or a merge's centre half a
  // spacing aside: no line jumps across the lane.
  CHECK(longest_jump < 2.0);
}

TEST_CASE("a restarted run writes the same pathlines as one straight through", "[pathlines][cli]") {
  swemps::testing::TempDir dir("pathlines");
  json j = two_lanes();
  j["end_time"] = 4;
  const auto scene = write_scene(dir.path(), "lanes.json", j).string();
  const auto straight =
      swemps::testing::run_command(cli() + " run -q " + scene + " --checkpoint-every 1");
  INFO(straight.output);
  REQUIRE(straight.status == 0);
  const auto checkpoint = dir.path() / "lanes.checkpoint";
  REQUIRE(fs::exists(checkpoint));  // at t = 2 s, the first output time after the start

  // The scene names one path for both runs' lines: keep the first run's.
  fs::rename(dir.path() / "lanes.geojson", dir.path() / "straight.geojson");

  // A run killed after that checkpoint left its file as .partial: the restart goes on from
  // t = 2 s and writes every line whole.
  fs::copy_file(dir.path() / "lanes.nc", dir.path() / "killed.nc.partial");
  fs::copy_file(checkpoint, dir.path() / "killed.checkpoint");
  const auto restarted = swemps::testing::run_command(
      cli() + " run -q " + scene + " -o " + (dir.path() / "killed.nc").string() + " --restart " +
      (dir.path() / "killed.checkpoint").string());
  INFO(restarted.output);
  REQUIRE(restarted.status == 0);
  const json a = read_json(dir.path() / "straight.geojson");
  const json b = read_json(dir.path() / "lanes.geojson");
  REQUIRE(a.at("features").size() == 60);
  CHECK(a.at("features") == b.at("features"));
}

TEST_CASE("pathlines are refused where they cannot be followed", "[pathlines]") {
  const auto error_at = [](const json& j) {
    try {
      swemps::scenario::parse(j.dump(), fs::temp_directory_path(), "pathlines");
    } catch (const swemps::scenario::ScenarioError& e) {
      return e.json_path() + ": " + e.what();
    }
    return std::string("no error");
  };
  json no_sources = two_lanes();
  no_sources["output"].erase("provenance");
  CHECK_THAT(error_at(no_sources),
             Contains("/output/pathlines/source") && Contains("output.provenance.sources"));
  json unknown = two_lanes();
  unknown["output"]["pathlines"]["source"] = "north lak";
  CHECK_THAT(error_at(unknown), Contains("/output/pathlines/source") && Contains("north lake"));
  json shapefile = two_lanes();
  shapefile["output"]["pathlines"]["path"] = "lanes.shp";
  CHECK_THAT(error_at(shapefile), Contains("/output/pathlines/path"));
  json late = two_lanes();
  late["output"]["pathlines"]["start"] = 8;
  CHECK_THAT(error_at(late), Contains("/output/pathlines/start"));
  json few = two_lanes();
  few["output"]["pathlines"]["count"] = 0;
  CHECK_THAT(error_at(few), Contains("/output/pathlines/count"));
  json triangle = two_lanes();
  triangle["output"]["pathlines"]["polygon"] = json::parse("[[0, 0], [1, 1]]");
  CHECK_THAT(error_at(triangle), Contains("/output/pathlines/polygon"));
  json fine = two_lanes();
  CHECK(error_at(fine) == "no error");
}

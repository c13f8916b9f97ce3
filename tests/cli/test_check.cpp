// `swe-mps check` through the real executable: the report's numbers are those of the scene as
// run builds it, a scene run refuses is refused with run's message and exit status, and a check
// leaves no file behind.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "../support/terrain_fixtures.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace fs = std::filesystem;

namespace {

using swemps::testing::CommandResult;
using swemps::testing::run_command;

const std::string cli = SWEMPS_CLI;

// The names in a folder, to tell what a command left there.
std::set<std::string> files_in(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
  return names;
}

// The value printed after a report row's label ("  fluid at the start   4,650 (...)"), up to
// the next space, with the digit groups' commas dropped.
std::string row_value(const std::string& report, const std::string& label) {
  const std::regex row("\n  " + label + " +([^ \n]+)");
  std::smatch m;
  if (!std::regex_search(report, m, row)) return "";
  std::string value = m[1];
  value.erase(std::remove(value.begin(), value.end(), ','), value.end());
  return value;
}

// The one line main() prints for a refused scene.
std::string failure_line(const std::string& output) {
  std::istringstream lines(output);
  std::string line, found;
  while (std::getline(lines, line)) {
    if (line.rfind("swe-mps: ", 0) == 0) found = line;
  }
  return found;
}

// The same scene through run and through check: both refuse it alike.
void refused_alike(const std::string& scene_and_options, int status) {
  const CommandResult by_run = run_command(cli + " run " + scene_and_options + " -q");
  const CommandResult by_check = run_command(cli + " check " + scene_and_options + " -q");
  INFO("run:\n" << by_run.output << "\ncheck:\n" << by_check.output);
  CHECK(by_run.status == status);
  CHECK(by_check.status == status);
  CHECK_FALSE(failure_line(by_check.output).empty());
  CHECK(failure_line(by_check.output) == failure_line(by_run.output));
  CHECK_THAT(by_check.output, !Catch::Contains("check: OK"));
}

// A bed raster of 20 x 10 cells of 10 m in UTM zone 16N, z = 100 + col + 10 row (row 0 the
// northern one), whose two eastern columns are nodata: outside the domain the scenes give.
void write_bed(const fs::path& path) {
  const auto g = swemps::testing::grid_geometry(20, 10, 500000.0, 4001000.0, 10.0, 10.0);
  std::vector<double> z;
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      z.push_back(col >= 18 ? std::numeric_limits<double>::quiet_NaN()
                            : 100.0 + static_cast<double>(col) + 10.0 * static_cast<double>(row));
    }
  }
  swemps::io::write_geotiff(
      swemps::terrain::GriddedField(g, z, swemps::testing::wkt_of("EPSG:32616"), "bed"), path);
}

// Water 1 m deep over the western 150 m of the bed above; `domain_x_max` may reach past it.
std::string raster_scene(double domain_x_max) {
  std::ostringstream s;
  s << R"({"end_time": 2,
    "bed": {"raster": "bed.tif"},
    "domain": {"x_min": 500000, "x_max": )"
    << domain_x_max << R"(, "y_min": 4000900, "y_max": 4001000},
    "water": [{"rectangle": {"x_min": 500000, "x_max": 500150, "y_min": 4000900, "y_max": 4001000},
               "depth": 1, "spacing": 10}],
    "output": {"path": "out.nc"}})";
  return s.str();
}

}  // namespace

TEST_CASE("check reports the Ritter case as run builds it, and writes nothing", "[cli][check]") {
  const swemps::testing::TempDir scratch("check-ritter");
  const fs::path& dir = scratch.path();
  fs::copy_file(fs::path(SWEMPS_SOURCE_DIR) / "cases/ritter/scenario.json", dir / "scenario.json");
  const auto r = run_command(cli + " check " + (dir / "scenario.json").string() + " --threads 2");
  INFO(r.output);
  REQUIRE(r.status == 0);
  for (const char* section : {"\nScene\n", "\nDomain and CRS\n", "\nRasters", "\nParticles\n",
                              "\nMemory\n", "\nTime step\n", "\nWall-time estimate\n"}) {
    CHECK_THAT(r.output, Catch::Contains(section));
  }
  CHECK_THAT(r.output, Catch::Contains("500 x 50 cells of 0.02 x 0.02 m over [0, 10] x [0, 1] m"));
  CHECK_THAT(r.output, Catch::Contains("none (local metres)"));
  CHECK_THAT(r.output, Catch::Contains("on 2 threads: between"));
  CHECK_THAT(r.output, Catch::Contains("The band is where the runs of the shipped scenes fell"));
  CHECK_THAT(r.output, Catch::EndsWith("check: OK — the scene can run\n"));

  // The scene as run builds it, before any step.
  auto built = swemps::scenario::build(swemps::scenario::load(dir / "scenario.json"));
  CHECK(row_value(r.output, "fluid at the start") ==
        std::to_string(built.simulation.particles().fluid_count()));
  const double dt_s = built.simulation.stable_time_step();
  const std::string printed = row_value(r.output, "first stable step");
  REQUIRE_FALSE(printed.empty());
  CHECK(std::stod(printed) == Approx(dt_s).epsilon(1e-8));
  // At the first dt, and one more for each of the 4 output times before the end.
  CHECK(row_value(r.output, "steps to the end") == std::to_string(int(std::ceil(0.5 / dt_s)) + 4));

  CHECK(files_in(dir) == std::set<std::string>{"scenario.json"});
}

TEST_CASE("check reports a bed raster's extent, cells, values and nodata", "[cli][check]") {
  const swemps::testing::TempDir scratch("check-raster");
  const fs::path& dir = scratch.path();
  write_bed(dir / "bed.tif");
  std::ofstream(dir / "scenario.json") << raster_scene(500150);
  const auto r = run_command(cli + " check " + (dir / "scenario.json").string() + " -q");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("WGS 84 / UTM zone 16N (EPSG:32616)"));
  CHECK_THAT(r.output, Catch::Contains("[500000, 500150] x [4000900, 4001000] m"));
  CHECK_THAT(r.output, Catch::Contains("150 x 100 m (15,000 m2)"));
  CHECK_THAT(r.output, Catch::Contains((dir / "bed.tif").string()));
  CHECK_THAT(r.output, Catch::Contains("[500000, 500200] x [4000900, 4001000] m"));
  CHECK_THAT(r.output, Catch::Contains("20 x 10 of 10 x 10 m"));
  // The cells over the domain: columns 0-14 of every row, 100 (north-west) to 100 + 14 + 90.
  CHECK_THAT(r.output, Catch::Contains("100 to 204 (150 cells)"));
  CHECK_THAT(r.output, Catch::Contains("0 in the domain, 20 of 200 cells in all"));
  CHECK(row_value(r.output, "fluid at the start") == "150");
  CHECK(files_in(dir) == std::set<std::string>{"bed.tif", "scenario.json"});
}

TEST_CASE("check refuses what run refuses, with run's message and exit status", "[cli][check]") {
  const swemps::testing::TempDir scratch("check-refused");
  const fs::path& dir = scratch.path();

  SECTION("a bed raster that is no raster") {
    std::ofstream(dir / "bed.tif") << "not a raster\n";
    std::ofstream(dir / "scenario.json") << raster_scene(500150);
    refused_alike((dir / "scenario.json").string(), 2);
  }
  SECTION("a domain reaching onto the raster's nodata") {
    write_bed(dir / "bed.tif");
    std::ofstream(dir / "scenario.json") << raster_scene(500200);
    refused_alike((dir / "scenario.json").string(), 2);
  }
  SECTION("a domain beyond the raster") {
    write_bed(dir / "bed.tif");
    std::ofstream(dir / "scenario.json") << raster_scene(500300);
    refused_alike((dir / "scenario.json").string(), 2);
  }
  SECTION("an output folder that does not exist") {
    fs::copy_file(fs::path(SWEMPS_SOURCE_DIR) / "cases/ritter/scenario.json",
                  dir / "scenario.json");
    refused_alike((dir / "scenario.json").string() + " -o " + (dir / "missing/out.nc").string(), 4);
    CHECK_FALSE(fs::exists(dir / "missing"));
  }
  SECTION("an output path that is a folder") {
    fs::copy_file(fs::path(SWEMPS_SOURCE_DIR) / "cases/ritter/scenario.json",
                  dir / "scenario.json");
    fs::create_directory(dir / "out.nc");
    refused_alike((dir / "scenario.json").string() + " -o " + (dir / "out.nc").string(), 4);
  }
}

TEST_CASE("check of a scene that starts dry times the steps once an inflow has let water in",
          "[cli][check]") {
  const swemps::testing::TempDir scratch("check-inflow");
  const fs::path& dir = scratch.path();
  // 100 m3/s for 99 s, then down to 0 in 2 s, over a 20 m line: 1e4 m3, 100 particles of
  // 10 m x 10 m x 1 m.
  std::ofstream(dir / "q.csv") << "time_s,discharge_m3_s\n0,100\n99,100\n101,0\n";
  std::ofstream(dir / "scenario.json") << R"({"end_time": 200,
    "domain": {"x_min": 0, "x_max": 400, "y_min": 0, "y_max": 40},
    "inflow": [{"name": "west", "line": [[0, 10], [0, 30]], "hydrograph_csv": "q.csv",
                "spacing": 10, "depth": 1}],
    "output": {"path": "out.nc"}})";
  const auto r = run_command(cli + " check " + (dir / "scenario.json").string() + " -q");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(row_value(r.output, "fluid at the start") == "0");
  CHECK_THAT(r.output,
             Catch::Contains("10,000 m3 by the end time, about 100 particles (depth 1 m)"));
  // A scene this small is stepped in memory to its end time, inflow and all: no pilot.
  CHECK_THAT(r.output, Catch::Contains("the scene itself, stepped in memory"));
  CHECK_THAT(r.output, Catch::Contains("    to its end time: "));
  CHECK_THAT(r.output, !Catch::Contains("a pilot run"));
  CHECK_THAT(r.output,
             Catch::Contains("on 1 thread: between") || Catch::Contains("threads: between"));
  CHECK(files_in(dir) == std::set<std::string>{"q.csv", "scenario.json"});
}

TEST_CASE("check of a model ns scene reports its tank and particles", "[cli][check]") {
  const swemps::testing::TempDir scratch("check-ns");
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "scenario.json") << R"({
    "end_time": 0.1, "model": "ns", "dimension": 2, "ns": {"spacing": 0.01},
    "domain": {"x_min": 0, "x_max": 0.4, "y_min": 0, "y_max": 0.1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 0.1, "y_min": 0, "y_max": 0.1}, "depth": 0.1}],
    "output": {"path": "tank.nc"}})";
  const auto r = run_command(cli + " check " + (dir / "scenario.json").string() + " -q");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("Navier-Stokes, 2D x-z section"));
  CHECK(row_value(r.output, "fluid particles") == "100");
  CHECK_THAT(r.output, Catch::Contains("\nTank and particles\n"));
  CHECK_FALSE(row_value(r.output, "first stable step").empty());
  CHECK_THAT(r.output, Catch::EndsWith("check: OK — the scene can run\n"));
  CHECK(files_in(dir) == std::set<std::string>{"scenario.json"});
}

TEST_CASE("check reports the rain a scene lets fall", "[cli][check][rain]") {
  const swemps::testing::TempDir scratch("check-rain");
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "scenario.json") << R"({
    "name": "rain-check", "end_time": 60,
    "domain": {"x_min": 0, "x_max": 20, "y_min": 0, "y_max": 10},
    "rain": {"name": "storm", "rate_mm_h": 36, "spacing": 1},
    "output": {"path": "out.nc"}})";
  const auto r = run_command(cli + " check " + (dir / "scenario.json").string() + " -q");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(row_value(r.output, "rain") == "1");
  // 36 mm/h for 60 s on 200 m2: 0.12 m3.
  CHECK_THAT(r.output, Catch::Contains("storm") &&
                           Catch::Contains("200 cells of 1 m2 (200 m2); 0.12 m3 falls by the end "
                                           "time, before losses"));
  CHECK(files_in(dir) == std::set<std::string>{"scenario.json"});
}

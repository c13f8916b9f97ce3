// Ensemble files read strictly (each mistake refused at its JSON path), and the member scenes
// made from a base scene: knob values put at their pointers, files the scene names still found
// from the member's folder.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../support/temp_dir.hpp"
#include "swemps/scenario/ensemble_file.hpp"
#include "swemps/scenario/scenario.hpp"

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using nlohmann::json;
using swemps::scenario::ScenarioError;

// A base scene naming a file under every key that can name one.
const char* kBaseScene = R"({
  "end_time": 1,
  "bed": {"raster": "terrain/dem.tif"},
  "friction": {"manning_n_raster": "NETCDF:\"terrain/n.nc\":manning"},
  "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
             "depth_raster": "/absolute/depth.tif", "spacing": 0.1}],
  "inflow": [{"line": [[0, 0], [0, 1]], "hydrograph_csv": "q.csv", "depth": 0.5},
             {"line": [[1, 0], [1, 1]], "hydrograph": [[0, 0], [10, 5], [20, 0]], "depth": 0.5}],
  "rain": {"rate_csv": "rain/storm.csv"},
  "output": {"path": "base.nc", "interval": 0.5}
})";

struct Fixture {
  swemps::testing::TempDir dir{"ensemble-file"};
  fs::path scene_dir = dir.path() / "case";
  fs::path file = dir.path() / "runs" / "ens.json";
  Fixture() {
    fs::create_directories(scene_dir);
    fs::create_directories(file.parent_path());
    std::ofstream(scene_dir / "scenario.json") << kBaseScene;
  }
  swemps::ensemble::Ensemble parse(const std::string& rest) const {
    return swemps::scenario::parse_ensemble(R"({"scene": "../case/scenario.json", )" + rest + "}",
                                            file);
  }
};

}  // namespace

TEST_CASE("an ensemble file is read with its defaults", "[ensemble][scenario]") {
  const Fixture f;
  const auto e = f.parse(R"("vary": [
      {"pointer": "/inflow/1/hydrograph/1/1", "name": "peak", "values": [5, 10, 20]},
      {"pointer": "/friction/manning_n", "range": [0.02, 0.08], "distribution": "log_uniform"}],
      "samples": 4, "seed": 11)");
  CHECK(e.base_scene == f.scene_dir / "scenario.json");
  CHECK(e.folder == f.file.parent_path() / "ens");
  REQUIRE(e.knobs.size() == 2);
  CHECK(e.knobs[0].name == "peak");
  CHECK(e.knobs[0].values == std::vector<std::string>{"5", "10", "20"});
  CHECK(e.knobs[1].name == "/friction/manning_n");
  CHECK(e.knobs[1].sampled());
  CHECK(e.knobs[1].distribution == swemps::ensemble::Distribution::log_uniform);
  CHECK(e.samples == 4);
  CHECK(e.seed == 11);
  CHECK(e.sampling == swemps::ensemble::Sampling::latin_hypercube);
  CHECK(e.thresholds_m == std::vector<double>{0.1, 0.3, 0.5, 1.0});
  CHECK(e.threads_per_member == 1);
  CHECK_FALSE(e.jobs);
  CHECK_FALSE(e.run_time_limit_s);
  CHECK_FALSE(e.checkpoint_every);
  CHECK(*f.parse(R"("vary": [{"pointer": "/end_time", "values": [1]}], "checkpoint_every": 3)")
             .checkpoint_every == 3);
  CHECK(swemps::ensemble::member_count(e) == 12);
}

TEST_CASE("mistakes in an ensemble file are refused at their JSON path", "[ensemble][scenario]") {
  const Fixture f;
  struct Refusal {
    std::string label, rest, path, says;
  };
  const std::string knob = R"("vary": [{"pointer": "/end_time", "values": [1, 2]}])";
  const std::vector<Refusal> cases{
      {"unknown key", knob + R"(, "sead": 1)", "/sead", "did you mean \"seed\""},
      {"no knobs", R"("vary": [])", "/vary", "non-empty array"},
      {"not a pointer", R"("vary": [{"pointer": "end_time", "values": [1]}])", "/vary/0/pointer",
       "not a JSON pointer"},
      {"array element not there", R"("vary": [{"pointer": "/water/3/depth", "values": [1]}])",
       "/vary/0/pointer", "does not add them"},
      {"an empty part under an array", R"("vary": [{"pointer": "/water/", "values": [1]}])",
       "/vary/0/pointer", "does not add them"},
      {"an index too large for any array",
       R"("vary": [{"pointer": "/water/99999999999999999999999", "values": [1]}])",
       "/vary/0/pointer", "does not add them"},
      {"below a number", R"("vary": [{"pointer": "/end_time/x", "values": [1]}])",
       "/vary/0/pointer", "below 1 at \"/end_time\""},
      {"the output path", R"("vary": [{"pointer": "/output/path", "values": ["a.nc"]}])",
       "/vary/0/pointer", "anything but the output path"},
      {"values and range", R"("vary": [{"pointer": "/end_time", "values": [1], "range": [1, 2]}])",
       "/vary/0", "either"},
      {"repeated value", R"("vary": [{"pointer": "/end_time", "values": [1, 2, 1]}])",
       "/vary/0/values/2", "each value once"},
      {"empty range",
       R"("vary": [{"pointer": "/end_time", "range": [2, 2]}], "samples": 2, "seed": 1)",
       "/vary/0/range", "low < high"},
      {"log of zero",
       R"("vary": [{"pointer": "/end_time", "range": [0, 2], "distribution": "log_uniform"}], "samples": 2, "seed": 1)",
       "/vary/0/range", "positive"},
      {"sampled without a seed",
       R"("vary": [{"pointer": "/end_time", "range": [1, 2]}], "samples": 3)", "/seed", "seed"},
      {"seed without a sampled knob", knob + R"(, "seed": 3)", "/seed", "only with a knob"},
      {"a pointer twice",
       R"("vary": [{"pointer": "/end_time", "values": [1]}, {"pointer": "/end_time", "values": [2]}])",
       "/vary/1/pointer", "each pointer once"},
      {"thresholds not ascending", knob + R"(, "thresholds": [0.5, 0.1])", "/thresholds/1",
       "ascending"},
      {"a partition with a blank", knob + R"(, "slurm": {"partition": "a b"})", "/slurm/partition",
       "without blanks"},
      {"an sbatch option that is not one", knob + R"(, "slurm": {"options": ["exclusive"]})",
       "/slurm/options/0", "starting with '-'"},
      {"fractional threads", knob + R"(, "threads_per_member": 1.5)", "/threads_per_member",
       "whole number"},
      {"checkpoints never", knob + R"(, "checkpoint_every": 0)", "/checkpoint_every",
       "from 1 to 1000000"},
  };
  for (const Refusal& c : cases) {
    INFO(c.label << ": " << c.rest);
    try {
      f.parse(c.rest);
      FAIL("accepted");
    } catch (const ScenarioError& e) {
      CHECK(e.json_path() == c.path);
      CHECK_THAT(std::string(e.what()), Contains("ensemble error at " + c.path));
      CHECK_THAT(std::string(e.what()), Contains(c.says));
    }
  }
  // A base scene that cannot be read is named as such.
  try {
    swemps::scenario::parse_ensemble(R"({"scene": "nowhere.json", )" + knob + "}", f.file);
    FAIL("accepted");
  } catch (const ScenarioError& e) {
    CHECK(e.json_path() == "/scene");
  }
}

TEST_CASE("a member's scene has its values, its own output and the base scene's files",
          "[ensemble][scenario]") {
  const Fixture f;
  const auto e = f.parse(R"("vary": [
      {"pointer": "/inflow/1/hydrograph/1/1", "values": [5, 10]},
      {"pointer": "/friction/manning_n", "values": [0.03]},
      {"pointer": "/water/0", "values": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
                                           "depth_raster": "other/depth.tif", "spacing": 0.2}]}])");
  const auto members = swemps::ensemble::members(e);
  REQUIRE(members.size() == 2);
  const fs::path member_dir = e.folder / "member-1";
  const json scene = json::parse(swemps::scenario::member_scene(e, members[1], member_dir));
  CHECK(scene["inflow"][1]["hydrograph"][1][1] == 10);
  CHECK(scene["friction"]["manning_n"] == 0.03);
  CHECK(scene["output"]["path"] == "result.nc");
  CHECK(scene["output"]["interval"] == 0.5);
  // Every file, read from the member's folder, is the base scene's file (a knob's file name is
  // taken as the base scene's are, from its folder); absolute names are kept.
  const auto from_member = [&](const std::string& name) {
    return (member_dir / name).lexically_normal();
  };
  CHECK(from_member(scene["bed"]["raster"]) == f.scene_dir / "terrain" / "dem.tif");
  CHECK(from_member(scene["inflow"][0]["hydrograph_csv"]) == f.scene_dir / "q.csv");
  CHECK(from_member(scene["rain"]["rate_csv"]) == f.scene_dir / "rain" / "storm.csv");
  CHECK(from_member(scene["water"][0]["depth_raster"]) == f.scene_dir / "other" / "depth.tif");
  const std::string wrapped = scene["friction"]["manning_n_raster"];
  CHECK(wrapped == "NETCDF:\"" +
                       (f.scene_dir / "terrain" / "n.nc").lexically_relative(member_dir).string() +
                       "\":manning");
  CHECK(json::parse(swemps::scenario::member_scene(
            e, members[0], member_dir))["inflow"][1]["hydrograph"][1][1] == 5);

  // A scene without an output section gets one.
  std::ofstream(f.scene_dir / "scenario.json") << R"({"end_time": 1})";
  const auto bare = f.parse(R"("vary": [{"pointer": "/end_time", "values": [2]}])");
  const json made = json::parse(
      swemps::scenario::member_scene(bare, swemps::ensemble::members(bare)[0], member_dir));
  CHECK(made["end_time"] == 2);
  CHECK(made["output"]["path"] == "result.nc");
}

// The fuzzing entry point: every input is read as a scene, as a study file and as an ensemble
// file, since the readers take JSON text and each input then exercises all three; an ensemble
// that reads makes its first and last members' scenes, which are read as scenes. A ScenarioError is
// the readers' answer to bad input; any other exception, a crash, a sanitizer report or an input
// that takes seconds is a bug.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "swemps/scenario/ensemble_file.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/scenario/study_file.hpp"

namespace {

// The base scene an ensemble input may name ("scene": "scene.json"), written once.
std::filesystem::path ensemble_file() {
  static const std::filesystem::path file = [] {
    const auto dir = std::filesystem::temp_directory_path() / "swemps-fuzz-ensemble";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "scene.json") << R"({"end_time": 1,
      "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
      "water": [{"rectangle": {"x_min": 0, "x_max": 4, "y_min": 0, "y_max": 1},
                 "depth": 0.25, "spacing": 0.1}],
      "inflow": [{"line": [[10, 0], [10, 1]], "hydrograph": [[0, 0], [1, 2]], "depth": 0.1}],
      "output": {"path": "r.nc"}})";
    return dir / "e.json";
  }();
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Only joined to relative paths in the text; the readers open no file.
  const std::filesystem::path base_dir = "/fuzz";
  try {
    swemps::scenario::parse(text, base_dir, "fuzz");
  } catch (const swemps::scenario::ScenarioError&) {
  }
  try {
    swemps::scenario::parse_study(text, base_dir, base_dir / "study.csv");
  } catch (const swemps::scenario::ScenarioError&) {
  }
  try {
    const auto ensemble = swemps::scenario::parse_ensemble(text, ensemble_file());
    if (swemps::ensemble::member_count(ensemble) <= 64) {
      const auto members = swemps::ensemble::members(ensemble);
      for (const auto* m : {&members.front(), &members.back()}) {
        const auto folder = ensemble.folder / "member";
        swemps::scenario::parse(swemps::scenario::member_scene(ensemble, *m, folder), folder);
      }
    }
  } catch (const swemps::scenario::ScenarioError&) {
  }
  return 0;
}

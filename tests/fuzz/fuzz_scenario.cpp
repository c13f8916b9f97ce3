// The fuzzing entry point: every input is read both as a scene and as a study file, since
// both readers take JSON text and each input then exercises both. A ScenarioError is the
// readers' answer to bad input; any other exception, a crash, a sanitizer report or an input
// that takes seconds is a bug.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "swemps/scenario/scenario.hpp"
#include "swemps/scenario/study_file.hpp"

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
  return 0;
}

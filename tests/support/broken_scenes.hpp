#pragma once
// Shared by the scene tests: parsing a scene from text, and checking that each of a list of
// broken scenes is refused at the right JSON path with a message that says what was expected.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "swemps/scenario/scenario.hpp"

namespace swemps::testing {

inline scenario::Scenario parse_text(const std::string& text) {
  return scenario::parse(text, std::filesystem::temp_directory_path(), "test");
}

struct Broken {
  std::string label;
  std::string text;
  std::string path;     // the expected json_path(): a substring of it, or all of it
  std::string message;  // expected substring of what()
};

// Each broken scene must throw a ScenarioError at its path (a substring match, or the exact
// path) whose message names what was expected.
inline void check_broken(const std::vector<Broken>& cases, bool exact_path) {
  using Catch::Matchers::Contains;
  for (const Broken& c : cases) {
    INFO("case: " << c.label << "\ntext:\n" << c.text);
    bool threw = false;
    try {
      parse_text(c.text);
    } catch (const scenario::ScenarioError& e) {
      threw = true;
      if (exact_path) {
        CHECK(e.json_path() == c.path);
      } else {
        CHECK_THAT(e.json_path(), Contains(c.path));
        CHECK_THAT(std::string(e.what()), Contains("scenario error at "));
      }
      CHECK_THAT(std::string(e.what()), Contains(c.message));
    }
    CHECK(threw);
  }
}

}  // namespace swemps::testing

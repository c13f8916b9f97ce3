// The "friction" section of a scene file: one Manning's n, a roughness map, or a land-use map
// of classes and the table of each class's n (docs/scenario.md, "friction"). The rest of the
// scene is load.cpp's.

#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

std::optional<ManningSpec> read_friction(const json* v, const std::filesystem::path& base_dir) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, "/friction",
                 {"manning_n", "manning_n_raster", "land_use_raster", "land_use_manning_n", "crs"},
                 "an object with \"manning_n\", \"manning_n_raster\" or \"land_use_raster\"");
  std::vector<std::string_view> given;
  for (const std::string_view key : {"manning_n", "manning_n_raster", "land_use_raster"}) {
    if (o.find(key) != nullptr) given.push_back(key);
  }
  const std::string one_of =
      "exactly one of \"manning_n\", \"manning_n_raster\" or \"land_use_raster\"";
  if (given.size() > 1) throw ScenarioError(o.path(), several(given), one_of);
  // None given: the uniform n is what is missing.
  const bool land_use = !given.empty() && given.front() == "land_use_raster";
  if (!land_use && o.find("land_use_manning_n") != nullptr) {
    throw ScenarioError(o.path("land_use_manning_n"), "a land-use table without a land-use map",
                        "\"land_use_manning_n\" only beside \"land_use_raster\"");
  }
  if (!given.empty() && given.front() == "manning_n_raster") {
    return RasterSpec{
        file_path(o, "manning_n_raster", "a raster of Manning's n (s m^-1/3)", base_dir),
        crs_text(o)};
  }
  if (land_use) {
    LandUseSpec spec;
    spec.raster = RasterSpec{
        file_path(o, "land_use_raster", "a raster of whole-number land-use classes", base_dir),
        crs_text(o)};
    const std::string table_expected =
        "an object from each land-use class (a whole number, as a string) to its Manning's n "
        "(> 0, s m^-1/3), such as {\"1\": 0.035, \"2\": 0.1}";
    const json* table = o.find("land_use_manning_n");
    if (table == nullptr)
      throw ScenarioError(o.path("land_use_manning_n"), kMissing, table_expected);
    if (!table->is_object() || table->empty()) {
      throw ScenarioError(o.path("land_use_manning_n"), describe(*table), table_expected);
    }
    for (const auto& [key, value] : table->items()) {
      const std::string at = member_path(o.path("land_use_manning_n"), key);
      std::size_t used = 0;
      long long code = 0;
      try {
        code = std::stoll(key, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != key.size()) {
        throw ScenarioError(at, "the class " + literal(key), "a whole number such as \"3\"");
      }
      const double n = finite_number(value, at, "Manning's n > 0 (s m^-1/3)");
      if (!(n > 0.0)) throw ScenarioError(at, fmt(n), "Manning's n > 0 (s m^-1/3)");
      if (!spec.manning_n.emplace(code, n).second) {
        throw ScenarioError(at, "the class " + std::to_string(code) + " again", "each class once");
      }
    }
    return spec;
  }
  if (o.find("crs") != nullptr) {
    throw ScenarioError(o.path("crs"), "a \"crs\" with \"manning_n\"",
                        "no \"crs\" here (it goes with \"manning_n_raster\" or "
                        "\"land_use_raster\")");
  }
  return positive(o, "manning_n", "s m^-1/3");
}

}  // namespace swemps::scenario

// The "buildings" section of a scene file: footprints from a vector file, as walls or raised
// into the bed (docs/scenario.md, "buildings"). Reading the file is build's; this checks the
// words.

#include <nlohmann/json.hpp>
#include <string>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

BuildingsSpec read_one(const json& v, const std::string& path,
                       const std::filesystem::path& base_dir) {
  const Object o(v, path, {"file", "layer", "as", "condition", "height", "crs", "reproject"},
                 "an object with a \"file\" of building polygons");
  BuildingsSpec b;
  b.key_path = path;
  const PolygonFileSpec file = read_polygon_file_keys(o, path, base_dir);
  b.file = file.file;
  b.layer = file.layer;
  b.crs = file.crs;
  b.reproject = file.reproject;
  const std::string_view as = choice(o, "as", {"walls", "bed"}, "walls");
  b.as = as == "bed" ? BuildingsSpec::As::bed : BuildingsSpec::As::walls;
  if (b.as == BuildingsSpec::As::bed && o.find("condition") != nullptr) {
    throw ScenarioError(o.path("condition"), describe(*o.find("condition")),
                        "no \"condition\" with \"as\": \"bed\" (it is the walls' slip or no-slip)");
  }
  if (b.as == BuildingsSpec::As::walls && o.find("height") != nullptr) {
    throw ScenarioError(o.path("height"), describe(*o.find("height")),
                        "no \"height\" with \"as\": \"walls\" (walls are never overtopped; "
                        "\"as\": \"bed\" raises the footprints by a height)");
  }
  // Each reads only its own key, so that the record of the scene's defaults holds no other.
  if (b.as == BuildingsSpec::As::walls) {
    const std::string_view condition = choice(o, "condition", {"slip", "no_slip"}, "slip");
    b.condition = condition == "no_slip" ? WallCondition::no_slip : WallCondition::slip;
  } else {
    b.height_m = positive(o, "height", kMetres, BuildingsSpec::kDefaultHeightM);
  }
  return b;
}

}  // namespace

PolygonFileSpec read_polygon_file_keys(const Object& o, const std::string& path,
                                       const std::filesystem::path& base_dir) {
  PolygonFileSpec spec;
  spec.key_path = path;
  spec.file =
      file_path(o, "file", "a vector file of polygons (GeoJSON, Shapefile, GeoPackage)", base_dir);
  spec.layer = optional_string(o, "layer", "a layer name").value_or("");
  spec.crs = optional_string(o, "crs", "a CRS (\"EPSG:27700\", WKT or a PROJ string), or \"scene\"")
                 .value_or("");
  spec.reproject = optional_bool(o, "reproject", false);
  if (spec.reproject && spec.crs == "scene") {
    throw ScenarioError(o.path("reproject"), "true with \"crs\": \"scene\"",
                        "one of them: \"scene\" takes the coordinates as they are, "
                        "\"reproject\" transforms them");
  }
  return spec;
}

std::vector<BuildingsSpec> read_buildings(const json* v, const std::filesystem::path& base_dir) {
  if (v == nullptr) return {};
  const std::string path = "/buildings";
  if (v->is_object()) return {read_one(*v, path, base_dir)};
  if (!v->is_array()) {
    throw ScenarioError(path, describe(*v), "a buildings object, or an array of them");
  }
  std::vector<BuildingsSpec> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    out.push_back(read_one((*v)[i], element_path(path, i), base_dir));
  }
  return out;
}

}  // namespace swemps::scenario

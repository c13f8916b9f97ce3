// The tsunami sections of a scene file: "fault_source", an earthquake's rectangular fault
// planes (tsunami/okada.hpp), placed on the map or by longitude and latitude; and
// "sea_boundaries", lines where the sea goes on beyond the domain
// (boundaries/sea_boundary.hpp). The rest of the scene is load.cpp's; the strict JSON reading
// is json_reading.hpp's.

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// A key every plane must give.
const json& required(const Object& o, std::string_view key, const std::string& expected) {
  const json* v = o.find(key);
  if (v == nullptr) throw ScenarioError(o.path(key), kMissing, expected);
  return *v;
}

FaultPlaneSpec read_plane(const json& v, const std::string& path) {
  const Object o(v, path,
                 {"x", "y", "longitude", "latitude", "depth", "strike", "dip", "rake", "slip",
                  "length", "width"},
                 "an object describing one fault plane");
  FaultPlaneSpec spec;
  tsunami::FaultPlane& f = spec.plane;
  const bool on_map = o.find("x") || o.find("y");
  const bool geographic = o.find("longitude") || o.find("latitude");
  if (on_map && geographic) {
    throw ScenarioError(path, "both map coordinates and longitude/latitude",
                        "the top edge's midpoint as \"x\" and \"y\" (m, the scene's CRS) or as "
                        "\"longitude\" and \"latitude\" (degrees)");
  }
  if (geographic) {
    required(o, "longitude", "the top edge's midpoint's longitude (degrees east)");
    required(o, "latitude", "the top edge's midpoint's latitude (degrees north)");
    spec.longitude_latitude =
        Point{in_range(o, "longitude", -180.0, false, 180.0, false, "degrees east", 0.0),
              in_range(o, "latitude", -90.0, false, 90.0, false, "degrees north", 0.0)};
  } else {
    const std::string where = "the top edge's midpoint on the map (m, the scene's CRS)";
    required(o, "x", where);
    required(o, "y", where);
    f.top_centre_m = {number(o, "x", "a number (" + where + ")"),
                      number(o, "y", "a number (" + where + ")")};
  }
  required(o, "depth", "the top edge's depth below the sea floor (m)");
  f.top_depth_m = non_negative(o, "depth", kMetres, 0.0);
  required(o, "strike", "the strike (degrees clockwise from north)");
  f.strike_deg = number(o, "strike", "a number (degrees clockwise from north)");
  required(o, "dip", "the dip (degrees)");
  f.dip_deg = bounded(o, "dip", 0.0, true, 90.0, "degrees below the horizontal", 45.0);
  required(o, "rake", "the rake (degrees; 90 for a thrust)");
  f.rake_deg = number(o, "rake", "a number (degrees; 90 for a thrust)");
  required(o, "slip", "the slip (m)");
  f.slip_m = non_negative(o, "slip", kMetres, 0.0);
  f.length_m = positive(o, "length", kMetres);
  f.width_m = positive(o, "width", kMetres);
  return spec;
}

SeaBoundarySpec read_sea_boundary(const json& v, const std::string& path, std::size_t index,
                                  const std::vector<WaterBody>& water,
                                  const std::filesystem::path& base_dir) {
  const Object o(v, path, {"name", "line", "type", "level", "series", "series_csv", "spacing"},
                 "an object with a \"line\" and a \"type\" (\"open\" or \"level\")");
  SeaBoundarySpec b;
  b.name = optional_string(o, "name", "a non-empty string")
               .value_or("sea boundary " + std::to_string(index));
  if (b.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }
  const std::string line_expected = "an array of exactly 2 [x, y] points (metres)";
  const json& line = required(o, "line", line_expected);
  if (!line.is_array() || line.size() != 2) {
    throw ScenarioError(o.path("line"), describe(line), line_expected);
  }
  const std::vector<Point> ends = points(line, o.path("line"), 2);
  check_distinct_neighbours(ends, o.path("line"), false);
  b.line = {ends[0], ends[1]};
  // The boundary's own particles continue the water's lattice, whose rows run along x and y:
  // a slanted line meets the lattice askew, and the seam stirs a sea at rest (measured: 1.2 mm
  // in 1 m of water within 4 s at 30 degrees; docs/tsunami.md, "Sea boundaries").
  if (ends[0][0] != ends[1][0] && ends[0][1] != ends[1][1]) {
    throw ScenarioError(o.path("line"), "a line slanted to the x and y axes",
                        "a line along x or along y (the particle lattice's rows), such as a "
                        "stretch of the domain's edge");
  }

  required(o, "type", "\"open\" (waves leave) or \"level\" (the level follows a series)");
  const bool level = choice(o, "type", {"open", "level"}, "open") == "level";
  const json* series = o.find("series");
  const json* csv = o.find("series_csv");
  if (level) {
    if (o.find("level") != nullptr) {
      throw ScenarioError(o.path("level"), "a still level on a level boundary",
                          "no \"level\" (a level boundary follows its series, then is open "
                          "about the series' last level)");
    }
    const std::string one_source = "exactly one of \"series\" or \"series_csv\"";
    if (series && csv) throw ScenarioError(path, "both \"series\" and \"series_csv\"", one_source);
    if (!series && !csv) {
      throw ScenarioError(path, "neither \"series\" nor \"series_csv\"", one_source);
    }
    if (series) {
      b.level = read_time_series(*series, o.path("series"), {"level", "m"});
    } else {
      b.level = file_path(o, "series_csv", "a CSV file of times and levels", base_dir);
    }
  } else {
    for (const char* key : {"series", "series_csv"}) {
      if (o.find(key) != nullptr) {
        throw ScenarioError(o.path(key), "a level series on an open boundary",
                            "\"type\": \"level\" for a boundary that follows a series");
      }
    }
    if (o.find("level") != nullptr) {
      b.still_level_m = number(o, "level", "a number (the still sea's level, m)");
    }
  }
  double finest = 0.0;
  for (const WaterBody& w : water)
    finest = finest == 0.0 ? w.spacing_m : std::min(finest, w.spacing_m);
  if (finest > 0.0) {
    b.spacing_m = positive(o, "spacing", kMetres, finest);
  } else {
    b.spacing_m = positive(o, "spacing", "metres; required when the scene has no water");
  }
  return b;
}

}  // namespace

std::vector<SeaBoundarySpec> read_sea_boundaries(const json* v, const std::vector<WaterBody>& water,
                                                 const std::filesystem::path& base_dir) {
  if (v == nullptr) return {};
  const std::string path = "/sea_boundaries";
  if (!v->is_array()) throw ScenarioError(path, describe(*v), "an array of sea boundaries");
  std::vector<SeaBoundarySpec> out;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < v->size(); ++i) {
    SeaBoundarySpec b = read_sea_boundary((*v)[i], element_path(path, i), i, water, base_dir);
    check_new_name(names, b.name, path, i, "sea boundary");
    names.push_back(b.name);
    out.push_back(std::move(b));
  }
  return out;
}

std::optional<FaultSourceSpec> read_fault_source(const json* v) {
  if (v == nullptr) return std::nullopt;
  const std::string path = "/fault_source";
  const Object o(*v, path, {"planes", "poisson_ratio"},
                 "an object with \"planes\" and optionally \"poisson_ratio\"");
  FaultSourceSpec spec;
  spec.poisson_ratio = in_range(o, "poisson_ratio", 0.0, true, 0.5, true,
                                "Poisson's ratio of the crust", spec.poisson_ratio);
  const json& planes = required(o, "planes", "an array of fault planes");
  if (!planes.is_array() || planes.empty()) {
    throw ScenarioError(o.path("planes"), describe(planes), "a non-empty array of fault planes");
  }
  for (std::size_t i = 0; i < planes.size(); ++i) {
    spec.planes.push_back(read_plane(planes[i], element_path(o.path("planes"), i)));
  }
  return spec;
}

}  // namespace swemps::scenario

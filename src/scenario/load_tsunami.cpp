// The "fault_source" section of a scene file: an earthquake's rectangular fault planes
// (tsunami/okada.hpp), placed on the map or by longitude and latitude. The rest of the scene
// is load.cpp's; the strict JSON reading is json_reading.hpp's.

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

}  // namespace

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

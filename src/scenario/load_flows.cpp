// The "inflow" and "outflow" sections of a scene file: inflow lines with their hydrographs
// (given in the file or as a CSV file), and outflow lines. The rest of the scene is
// load.cpp's; the strict JSON reading is json_reading.hpp's.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// ---------------------------------------------------------------------------------------------
// Inflow and outflow

double smallest_spacing(const std::vector<WaterBody>& water) {
  double s = water.front().spacing_m;
  for (const WaterBody& w : water) s = std::min(s, w.spacing_m);
  return s;
}

Inflow read_inflow(const json& v, const std::string& path, std::size_t index,
                   const std::vector<WaterBody>& water, const std::filesystem::path& base_dir) {
  const Object o(v, path,
                 {"name", "line", "hydrograph", "hydrograph_csv", "spacing", "depth", "direction"},
                 "an object with a \"line\" and a \"hydrograph\" or \"hydrograph_csv\"");
  Inflow in;
  in.name =
      optional_string(o, "name", "a non-empty string").value_or("inflow " + std::to_string(index));
  if (in.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }

  const std::string line_expected = "an array of exactly 2 [x, y] points (metres)";
  const json* line = o.find("line");
  if (line == nullptr) throw ScenarioError(o.path("line"), kMissing, line_expected);
  if (!line->is_array() || line->size() != 2) {
    throw ScenarioError(o.path("line"), describe(*line), line_expected);
  }
  const std::vector<Point> ends = points(*line, o.path("line"), 2);
  check_distinct_neighbours(ends, o.path("line"), false);
  in.line = {ends[0], ends[1]};

  const std::string one_source = "exactly one of \"hydrograph\" or \"hydrograph_csv\"";
  const json* table = o.find("hydrograph");
  const json* csv = o.find("hydrograph_csv");
  if (table && csv)
    throw ScenarioError(path, "both \"hydrograph\" and \"hydrograph_csv\"", one_source);
  if (!table && !csv) {
    throw ScenarioError(path, "neither \"hydrograph\" nor \"hydrograph_csv\"", one_source);
  }
  if (table) {
    in.hydrograph = read_time_series(*table, o.path("hydrograph"), {"discharge", "m^3/s", true});
  } else {
    in.hydrograph = file_path(o, "hydrograph_csv", "a CSV file of times and discharges", base_dir);
  }

  // Inflow particles as fine as the finest water keep the particle sizes alike.
  if (water.empty()) {
    in.spacing_m = positive(o, "spacing", "metres; required when the scene has no water");
  } else {
    in.spacing_m = positive(o, "spacing", kMetres, smallest_spacing(water));
  }
  if (o.find("depth") != nullptr) in.depth_m = positive(o, "depth", kMetres);

  if (const json* direction = o.find("direction")) {
    const auto d = pair(*direction, o.path("direction"), "a [dx, dy] pair of numbers");
    const double along_x = in.line[1][0] - in.line[0][0];
    const double along_y = in.line[1][1] - in.line[0][1];
    const double norm = std::hypot(d[0], d[1]);
    const double length = std::hypot(along_x, along_y);
    // Appended piece by piece: "[" + a temporary trips a false -Wrestrict in GCC 12's string.
    std::string normal = "[";
    normal += fmt(-along_y / length);
    normal += ", ";
    normal += fmt(along_x / length);
    normal += "]";
    const std::string expected =
        "a direction normal to the line, such as " + normal + " or its opposite";
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      throw ScenarioError(o.path("direction"), "a zero or unbounded vector", expected);
    }
    const double cosine = (d[0] * along_x + d[1] * along_y) / (norm * length);
    if (std::abs(cosine) > 1e-9) {
      const double degrees = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
      throw ScenarioError(
          o.path("direction"),
          "[" + fmt(d[0]) + ", " + fmt(d[1]) + "], at " + fmt(degrees) + " degrees to the line",
          expected);
    }
    in.direction = d;
  }
  return in;
}

}  // namespace

std::vector<std::array<double, 2>> read_time_series(const json& v, const std::string& path,
                                                    const SeriesValue& value,
                                                    const std::string& expected) {
  const std::string name(value.name), unit(value.unit);
  if (!v.is_array() || v.empty()) {
    throw ScenarioError(path, describe(v),
                        expected.empty()
                            ? "an array of at least 1 [time, " + name + "] point (s, " + unit + ")"
                            : expected);
  }
  std::vector<std::array<double, 2>> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string at = element_path(path, i);
    const auto point = pair(v[i], at, "a [time, " + name + "] pair of numbers (s, " + unit + ")");
    if (!out.empty() && !(point[0] > out.back()[0])) {
      throw ScenarioError(element_path(at, 0), "t = " + fmt(point[0]),
                          "a time greater than the previous point's " + fmt(out.back()[0]) +
                              " (times strictly increasing, seconds)");
    }
    if (value.non_negative && point[1] < 0.0) {
      throw ScenarioError(element_path(at, 1), fmt(point[1]), "a " + name + " >= 0 (" + unit + ")");
    }
    out.push_back(point);
  }
  return out;
}

std::vector<Inflow> read_inflows(const json* v, const std::vector<WaterBody>& water,
                                 const std::filesystem::path& base_dir) {
  if (v == nullptr) return {};
  const std::string path = "/inflow";
  if (!v->is_array()) throw ScenarioError(path, describe(*v), "an array of inflow lines");
  std::vector<Inflow> out;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < v->size(); ++i) {
    Inflow in = read_inflow((*v)[i], element_path(path, i), i, water, base_dir);
    check_new_name(names, in.name, path, i, "inflow");
    names.push_back(in.name);
    out.push_back(std::move(in));
  }
  return out;
}

void check_new_name(const std::vector<std::string>& names, const std::string& name,
                    const std::string& array_path, std::size_t index, const std::string& what) {
  const auto earlier = std::find(names.begin(), names.end(), name);
  if (earlier == names.end()) return;
  throw ScenarioError(member_path(element_path(array_path, index), "name"),
                      "the name " + literal(name) + " again (" + what + " " +
                          std::to_string(earlier - names.begin()) + " has it)",
                      "a name no other " + what + " has");
}

std::vector<Outflow> read_outflows(const json* v) {
  if (v == nullptr) return {};
  const std::string path = "/outflow";
  if (!v->is_array()) throw ScenarioError(path, describe(*v), "an array of outflow lines");
  std::vector<Outflow> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const Object o((*v)[i], element_path(path, i), {"line"}, "an object with a \"line\"");
    const json* line = o.find("line");
    if (line == nullptr) {
      throw ScenarioError(o.path("line"), kMissing,
                          "an array of at least 2 [x, y] points (metres)");
    }
    Outflow outflow{points(*line, o.path("line"), 2)};
    check_distinct_neighbours(outflow.line, o.path("line"), false);
    out.push_back(std::move(outflow));
  }
  return out;
}

// With a raster bed the scene's CRS is the bed's and every other raster is warped to it;

}  // namespace swemps::scenario

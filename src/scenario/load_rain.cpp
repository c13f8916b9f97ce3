// The "rain" section of a scene file: rain over the domain or a polygon, its rate constant,
// a series in the file or a CSV file of one, and the losses that take part of it
// (docs/scenario.md, "rain"). The rest of the scene is load.cpp's.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

const std::string kRateExpected =
    "a rate in mm/h >= 0, or an array of at least 1 [time, rate] point (s, mm/h)";

std::vector<std::array<double, 2>> read_rate(const json& v, const std::string& path) {
  if (!v.is_number()) return read_time_series(v, path, {"rain rate", "mm/h", true}, kRateExpected);
  const double rate = finite_number(v, path, kRateExpected);
  if (rate < 0.0) throw ScenarioError(path, fmt(rate) + " mm/h", "a rain rate >= 0 (mm/h)");
  return {{0.0, rate}};
}

double finest_creating_spacing(const std::vector<WaterBody>& water,
                               const std::vector<Inflow>& inflows) {
  double s = std::numeric_limits<double>::infinity();
  for (const WaterBody& w : water) s = std::min(s, w.spacing_m);
  for (const Inflow& in : inflows) s = std::min(s, in.spacing_m);
  return s;
}

RainSpec read_one_rain(const json& v, const std::string& path, const std::string& default_name,
                       const std::vector<WaterBody>& water, const std::vector<Inflow>& inflows,
                       const std::filesystem::path& base_dir) {
  const Object o(v, path,
                 {"name", "rate_mm_h", "rate_csv", "polygon", "spacing", "creation_depth",
                  "initial_loss_mm", "continuing_loss_mm_h"},
                 "an object with a \"rate_mm_h\" or a \"rate_csv\"");
  RainSpec rain;
  rain.key_path = path;
  rain.name = optional_string(o, "name", "a non-empty string").value_or(default_name);
  if (rain.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }
  const std::string one_source = "exactly one of \"rate_mm_h\" or \"rate_csv\"";
  const json* table = o.find("rate_mm_h");
  const json* csv = o.find("rate_csv");
  if (table && csv) throw ScenarioError(path, "both \"rate_mm_h\" and \"rate_csv\"", one_source);
  if (!table && !csv)
    throw ScenarioError(path, "neither \"rate_mm_h\" nor \"rate_csv\"", one_source);
  if (table) {
    rain.rate_mm_h = read_rate(*table, o.path("rate_mm_h"));
  } else {
    rain.rate_mm_h = file_path(o, "rate_csv", "a CSV file of times and rain rates", base_dir);
  }
  if (const json* polygon = o.find("polygon")) {
    rain.polygon = read_polygon(*polygon, o.path("polygon"));
  }
  // Rain particles as fine as the finest water keep the particle sizes alike.
  const double finest = finest_creating_spacing(water, inflows);
  if (std::isfinite(finest)) {
    rain.spacing_m = positive(o, "spacing", kMetres, finest);
  } else {
    rain.spacing_m =
        positive(o, "spacing", "metres; required when the scene has no water or inflow");
  }
  rain.creation_depth_m = positive(o, "creation_depth", kMetres, rain.creation_depth_m);
  rain.initial_loss_mm = non_negative(o, "initial_loss_mm", "mm", 0.0);
  rain.continuing_loss_mm_h = non_negative(o, "continuing_loss_mm_h", "mm/h", 0.0);
  return rain;
}

}  // namespace

std::vector<RainSpec> read_rain(const json* v, const std::vector<WaterBody>& water,
                                const std::vector<Inflow>& inflows,
                                const std::filesystem::path& base_dir) {
  if (v == nullptr) return {};
  const std::string path = "/rain";
  // One rain as an object; several (each over its own polygon, with its own gauge's series)
  // as an array.
  if (v->is_object()) return {read_one_rain(*v, path, "rain", water, inflows, base_dir)};
  if (!v->is_array()) {
    throw ScenarioError(path, describe(*v), "a rain object, or an array of them");
  }
  std::vector<RainSpec> out;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < v->size(); ++i) {
    RainSpec rain = read_one_rain((*v)[i], element_path(path, i), "rain " + std::to_string(i),
                                  water, inflows, base_dir);
    check_new_name(names, rain.name, path, i, "rain");
    names.push_back(rain.name);
    out.push_back(std::move(rain));
  }
  return out;
}

}  // namespace swemps::scenario

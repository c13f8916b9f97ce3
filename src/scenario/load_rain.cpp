// The "rain" section of a scene file: rain over the domain or a polygon, its rate constant,
// a series in the file or a CSV file of one, a map or a netCDF series of maps, and the losses
// that take part of it, each a number or a map (docs/scenario.md, "rain"). The rest of the
// scene is load.cpp's.

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

// o[key]: a number >= 0 in `unit`, or a raster file of such numbers (resolved against the
// scene's folder, warped to the rain's "crs"); `fallback` when absent.
ValueOrRaster value_or_raster(const Object& o, std::string_view key, const std::string& unit,
                              std::optional<double> fallback, const std::filesystem::path& base_dir,
                              const std::string& crs) {
  const json* v = o.find(key);
  if (v != nullptr && v->is_string()) {
    return RasterSpec{
        file_path(o, key, "a raster of " + std::string(key) + " (" + unit + ")", base_dir), crs};
  }
  const std::string expected = "a number >= 0 (" + unit + "), or a raster file of them";
  if (v == nullptr && fallback) return *fallback;
  if (v == nullptr) throw ScenarioError(o.path(key), kMissing, expected);
  const double value = finite_number(*v, o.path(key), expected);
  if (value < 0.0) throw ScenarioError(o.path(key), describe(*v), expected);
  return value;
}

GreenAmptSpec read_green_ampt(const json& v, const std::string& path,
                              const std::filesystem::path& base_dir, const std::string& crs) {
  const Object o(v, path, {"conductivity_mm_h", "suction_mm", "moisture_deficit"},
                 "an object with \"conductivity_mm_h\", \"suction_mm\" and \"moisture_deficit\"");
  GreenAmptSpec soil;
  soil.conductivity_mm_h =
      value_or_raster(o, "conductivity_mm_h", "mm/h", std::nullopt, base_dir, crs);
  soil.suction_mm = value_or_raster(o, "suction_mm", "mm", std::nullopt, base_dir, crs);
  soil.moisture_deficit = value_or_raster(o, "moisture_deficit", "a fraction of the soil's volume",
                                          std::nullopt, base_dir, crs);
  if (const double* deficit = std::get_if<double>(&soil.moisture_deficit);
      deficit && *deficit > 1) {
    throw ScenarioError(o.path("moisture_deficit"), fmt(*deficit),
                        "a fraction of the soil's volume, 0 to 1");
  }
  return soil;
}

RainSpec read_one_rain(const json& v, const std::string& path, const std::string& default_name,
                       const std::vector<WaterBody>& water, const std::vector<Inflow>& inflows,
                       const std::filesystem::path& base_dir) {
  const Object o(
      v, path,
      {"name", "rate_mm_h", "rate_csv", "rate_raster", "rate_netcdf", "polygon", "spacing",
       "creation_depth", "initial_loss_mm", "continuing_loss_mm_h", "green_ampt", "crs"},
      "an object with a \"rate_mm_h\", \"rate_csv\", \"rate_raster\" or \"rate_netcdf\"");
  RainSpec rain;
  rain.key_path = path;
  rain.name = optional_string(o, "name", "a non-empty string").value_or(default_name);
  if (rain.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }
  const std::string crs = crs_text(o);
  std::vector<std::string_view> given;
  for (const std::string_view key : {"rate_mm_h", "rate_csv", "rate_raster", "rate_netcdf"}) {
    if (o.find(key) != nullptr) given.push_back(key);
  }
  const std::string one_source =
      "exactly one of \"rate_mm_h\", \"rate_csv\", \"rate_raster\" or \"rate_netcdf\"";
  if (given.size() > 1) throw ScenarioError(path, several(given), one_source);
  if (given.empty()) throw ScenarioError(path, "no rate", one_source);
  if (given.front() == "rate_mm_h") {
    rain.rate_mm_h = read_rate(*o.find("rate_mm_h"), o.path("rate_mm_h"));
  } else if (given.front() == "rate_csv") {
    rain.rate_mm_h = file_path(o, "rate_csv", "a CSV file of times and rain rates", base_dir);
  } else if (given.front() == "rate_raster") {
    rain.rate_mm_h = RainSpec::RateRaster{RasterSpec{
        file_path(o, "rate_raster", "a raster of the rain's rate (mm/h)", base_dir), crs}};
  } else {
    rain.rate_mm_h = RainSpec::RateNetcdf{RasterSpec{
        file_path(o, "rate_netcdf",
                  "a netCDF file of the rain's rate (mm/h) over (time, y, x), or a variable "
                  "of one as NETCDF:\"file.nc\":variable",
                  base_dir),
        crs}};
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
  rain.initial_loss_mm = value_or_raster(o, "initial_loss_mm", "mm", 0.0, base_dir, crs);
  if (const json* soil = o.find("green_ampt")) {
    if (o.find("continuing_loss_mm_h") != nullptr) {
      throw ScenarioError(path, "both \"continuing_loss_mm_h\" and \"green_ampt\"",
                          "at most one of the continuing loss and Green-Ampt infiltration");
    }
    rain.green_ampt = read_green_ampt(*soil, o.path("green_ampt"), base_dir, crs);
  } else {
    rain.continuing_loss_mm_h =
        value_or_raster(o, "continuing_loss_mm_h", "mm/h", 0.0, base_dir, crs);
  }
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

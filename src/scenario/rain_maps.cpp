#include "rain_maps.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "json_reading.hpp"
#include "swemps/io/cf_time.hpp"

namespace swemps::scenario {

namespace {

using json_reading::fmt;
using Field = terrain::GriddedField;
constexpr auto kNearest = io::RasterRequest::Resampling::nearest;

// How a series' values become mm/h: a factor for rates, or depths per interval (mm).
struct ValueUnits {
  double to_mm_h = 1.0;
  bool depth_per_interval = false;
};

std::optional<ValueUnits> rain_units(std::string units) {
  std::string squeezed;
  for (const char c : units) {
    if (c != ' ') squeezed += c;
  }
  for (const char* rate : {"", "mm/h", "mmh-1", "mm/hr", "mmhr-1", "mmh**-1", "mm/hour"}) {
    if (squeezed == rate) return ValueUnits{};
  }
  for (const char* rate : {"mm/s", "mms-1", "kgm-2s-1", "kg/m2/s", "kgm**-2s**-1"}) {
    if (squeezed == rate) return ValueUnits{3600.0, false};
  }
  if (squeezed == "m/s" || squeezed == "ms-1") return ValueUnits{3.6e6, false};
  if (squeezed == "mm" || squeezed == "kgm-2") return ValueUnits{1.0, true};
  return std::nullopt;
}

// The start of each map in seconds of the run.
std::vector<double> run_seconds(const io::RasterSeries& series,
                                const std::optional<std::string>& start_time,
                                const std::string& json_path) {
  double shift_s = 0.0;
  if (series.time_units.since && start_time) {
    const auto start = io::parse_calendar_time(*start_time);
    if (start) {
      shift_s = io::seconds_since_1970(*series.time_units.since) - io::seconds_since_1970(*start);
    }
  }
  std::vector<double> out;
  for (std::size_t k = 0; k < series.times.size(); ++k) {
    out.push_back(series.times[k] * series.time_units.seconds_per_unit + shift_s);
    if (k > 0 && !(out[k] > out[k - 1])) {
      throw ScenarioError(json_path,
                          "map " + std::to_string(k + 1) + " of the series starts at " +
                              fmt(out[k]) + " s, not after map " + std::to_string(k) + " (" +
                              fmt(out[k - 1]) + " s)",
                          "a series of maps whose times increase");
    }
  }
  return out;
}

void read_rate_series(const RasterSpec& raster, const RainSpec& spec, const Scenario& scene,
                      SceneCrs& crs, Terrain::RainMaps& maps) {
  const std::string path = spec.key_path + "/rate_netcdf";
  io::RasterSeries series =
      crs.read_series(raster, "rain rate series", spec.key_path + "/crs", path);
  const auto units = rain_units(series.value_units);
  if (!units) {
    throw ScenarioError(path, "rain in '" + series.value_units + "'",
                        "rates in mm/h (also mm/s, m/s, kg m-2 s-1) or depths in mm over each "
                        "map's interval; a variable without units is read as mm/h");
  }
  maps.rate_starts_s = run_seconds(series, scene.output.start_time, path);
  const auto& starts = maps.rate_starts_s;
  const std::size_t n = starts.size();
  // Each map holds until the next; the last for as long as the one before it, or for ever when
  // it is the only one (a static map).
  maps.rate_end_s = n > 1 ? starts[n - 1] + (starts[n - 1] - starts[n - 2])
                          : std::numeric_limits<double>::infinity();
  if (units->depth_per_interval && n < 2) {
    throw ScenarioError(path, "a single map of rain depths (mm)",
                        "rates (mm/h), or depths over the intervals of two maps or more");
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double end = k + 1 < n ? starts[k + 1] : maps.rate_end_s;
    const double factor = units->depth_per_interval ? 3600.0 / (end - starts[k]) : units->to_mm_h;
    maps.rate_mm_h.push_back(std::make_shared<const Field>(
        factor == 1.0 ? std::move(series.frames[k]) : series.frames[k].scaled(factor)));
  }
}

void read_parameter(const ValueOrRaster& value, const std::string& key, const std::string& what,
                    const RainSpec& spec, SceneCrs& crs, Terrain::RainMaps& maps) {
  const auto* raster = std::get_if<RasterSpec>(&value);
  if (!raster) return;
  maps.parameters[key] = std::make_shared<const Field>(
      crs.read(*raster, what, spec.key_path + "/crs", spec.key_path + "/" + key, kNearest));
}

}  // namespace

void read_rain_maps(const Scenario& scene, SceneCrs& crs, Terrain& terrain) {
  terrain.rain.assign(scene.rain.size(), {});
  for (std::size_t i = 0; i < scene.rain.size(); ++i) {
    const RainSpec& spec = scene.rain[i];
    Terrain::RainMaps& maps = terrain.rain[i];
    if (const auto* map = std::get_if<RainSpec::RateRaster>(&spec.rate_mm_h)) {
      maps.rate_starts_s = {0.0};
      maps.rate_end_s = std::numeric_limits<double>::infinity();
      maps.rate_mm_h.push_back(std::make_shared<const Field>(
          crs.read(map->raster, "rain rate raster", spec.key_path + "/crs",
                   spec.key_path + "/rate_raster", kNearest)));
    } else if (const auto* series = std::get_if<RainSpec::RateNetcdf>(&spec.rate_mm_h)) {
      read_rate_series(series->raster, spec, scene, crs, maps);
    }
    read_parameter(spec.initial_loss_mm, "initial_loss_mm", "initial loss raster", spec, crs, maps);
    read_parameter(spec.continuing_loss_mm_h, "continuing_loss_mm_h", "continuing loss raster",
                   spec, crs, maps);
    if (spec.green_ampt) {
      const GreenAmptSpec& soil = *spec.green_ampt;
      read_parameter(soil.conductivity_mm_h, "green_ampt/conductivity_mm_h",
                     "hydraulic conductivity raster", spec, crs, maps);
      read_parameter(soil.suction_mm, "green_ampt/suction_mm", "suction head raster", spec, crs,
                     maps);
      read_parameter(soil.moisture_deficit, "green_ampt/moisture_deficit",
                     "moisture deficit raster", spec, crs, maps);
    }
  }
}

}  // namespace swemps::scenario

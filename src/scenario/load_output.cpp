// The "output" section of a scene file: the map times, the grid, the gauges and what else
// to write. The rest of the scene is load.cpp's; the strict JSON reading is json_reading.hpp's.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/io/cf_time.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/maps/provenance_maxima.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// An interval-generated output list (or series) longer than this is surely a typo.
constexpr double kMaxOutputTimes = 1e6;
// Each written grid field of this many cells takes gigabytes; a finer grid is surely a typo,
// better reported here than by the allocator.
constexpr double kMaxGridCells = 1e9;

// ---------------------------------------------------------------------------------------------
// Output

std::vector<double> listed_times(const json& v, const std::string& path, double end_time) {
  if (!v.is_array()) throw ScenarioError(path, describe(v), "an array of times (seconds)");
  const std::string expected = "a time in (0, end_time = " + fmt(end_time) + "] (seconds)";
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double t = finite_number(v[i], element_path(path, i), expected);
    if (!(t > 0.0) || t > end_time) {
      throw ScenarioError(element_path(path, i), describe(v[i]), expected);
    }
    out.push_back(t);
  }
  return out;
}

// interval, 2 interval, ... up to end_time; end_time itself is added by the caller. A multiple
// within rounding of end_time is dropped so the run does not write two records a hair apart.
std::vector<double> regular_times(const Object& o, double end_time) {
  const double interval = positive(o, "interval", kSeconds);
  if (end_time / interval > kMaxOutputTimes) {
    throw ScenarioError(
        o.path("interval"),
        describe(*o.find("interval")) + ", giving " + fmt(end_time / interval) + " output times",
        "an interval giving at most " + fmt(kMaxOutputTimes) + " output times (seconds)");
  }
  const double slack = 1e-9 * end_time;
  std::vector<double> out;
  for (std::size_t k = 1;; ++k) {
    const double t = static_cast<double>(k) * interval;
    if (t >= end_time - slack) break;
    out.push_back(t);
  }
  return out;
}

std::vector<double> read_times(const Object& o, double end_time) {
  const json* times = o.find("times");
  const json* interval = o.find("interval");
  if (times && interval) {
    throw ScenarioError(o.path(), "both \"times\" and \"interval\"",
                        "at most one of \"times\" or \"interval\"");
  }
  std::vector<double> out;
  if (times) {
    out = listed_times(*times, o.path("times"), end_time);
  } else if (interval) {
    out = regular_times(o, end_time);
  }
  out.push_back(end_time);  // the final state is always worth having
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

void check_grid_cells(double spacing_m, const Rectangle& bounds, const std::string& path) {
  const double cells =
      ((bounds.x_max - bounds.x_min) / spacing_m) * ((bounds.y_max - bounds.y_min) / spacing_m);
  if (cells > kMaxGridCells) {
    throw ScenarioError(path, fmt(spacing_m) + ", giving about " + fmt(std::ceil(cells)) + " cells",
                        "a spacing giving at most " + fmt(kMaxGridCells) + " grid cells (metres)");
  }
}

namespace {

// The finest particle spacing of the scene's water, inflows and rain.
double finest_spacing(const Scenario& scene) {
  double s = std::numeric_limits<double>::infinity();
  for (const WaterBody& w : scene.water) s = std::min(s, w.spacing_m);
  for (const Inflow& in : scene.inflows) s = std::min(s, in.spacing_m);
  for (const RainSpec& rain : scene.rain) s = std::min(s, rain.spacing_m);
  return s;
}

GridSpec read_grid(const json* v, const std::string& path, const Scenario& scene) {
  const Object o(v ? *v : empty_object(), path, {"spacing", "x_min", "x_max", "y_min", "y_max"},
                 "an object");
  GridSpec grid;
  // A raster bed brings its own cells; elsewhere half the particle spacing resolves the
  // particle field without empty cells between them. Model ns counts the particles standing
  // in each cell instead: a cell must hold whole columns of them, or the depth map stripes.
  if (o.find("spacing") != nullptr || !std::holds_alternative<RasterBedSpec>(scene.bed)) {
    const double fallback =
        scene.model == Model::ns ? 2.0 * scene.ns->settings.spacing_m : 0.5 * finest_spacing(scene);
    grid.spacing_m = positive(o, "spacing", kMetres, fallback);
  }

  std::vector<std::string_view> present;
  for (std::string_view key : kBoxKeys) {
    if (o.find(key) != nullptr) present.push_back(key);
  }
  if (present.size() == kBoxKeys.size()) {
    grid.bounds = box(o);
    if (grid.spacing_m) check_grid_cells(*grid.spacing_m, *grid.bounds, o.path("spacing"));
  } else if (!present.empty()) {
    throw ScenarioError(path, "only " + join(present, false),
                        "all four of x_min, x_max, y_min, y_max, or none (the domain)");
  }
  return grid;
}

std::filesystem::path read_output_path(const Object& o, const std::string& name,
                                       const std::filesystem::path& base_dir) {
  const std::string expected = "a file name or path (relative to the scenario's folder)";
  const std::string text = optional_string(o, "path", expected).value_or(name + ".nc");
  std::filesystem::path p(text);
  if (text.empty() || !p.has_filename()) {
    const std::string found = "a string " + literal(text);
    throw ScenarioError(o.path("path"), text.empty() ? found : found + ", which names a folder",
                        expected);
  }
  if (p.is_relative()) p = base_dir / p;
  return std::filesystem::absolute(p).lexically_normal();
}

std::vector<Gauge> read_gauges(const json* v, const std::string& path) {
  if (v == nullptr) return {};
  if (!v->is_array()) throw ScenarioError(path, describe(*v), "an array of gauges");
  std::vector<Gauge> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const Object o((*v)[i], element_path(path, i), {"name", "x", "y"},
                   "an object with x, y and optionally a name");
    Gauge g;
    g.name =
        optional_string(o, "name", "a non-empty string").value_or("gauge " + std::to_string(i));
    if (g.name.empty()) {
      throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
    }
    // The name is the gauge's id in the output file.
    for (std::size_t k = 0; k < out.size(); ++k) {
      if (out[k].name != g.name) continue;
      throw ScenarioError(
          o.path("name"),
          "the name " + literal(g.name) + " again (gauge " + std::to_string(k) + " has it)",
          "a name no other gauge has");
    }
    g.position_m = {number(o, "x", "a number (metres)"), number(o, "y", "a number (metres)")};
    out.push_back(std::move(g));
  }
  return out;
}

// The default further depth thresholds: 0.1 m wets a floor, 0.3 m is where a flood starts to
// take people off their feet and stops cars, 0.5 m and 1 m bound the hazard classes
// (docs/outputs.md). Those not above the wet depth are left out.
constexpr double kDefaultThresholds[] = {0.1, 0.3, 0.5, 1.0};

std::vector<double> read_thresholds(const Object& o, double wet_depth_m) {
  const json* v = o.find("depth_thresholds");
  std::vector<double> out;
  if (v == nullptr) {
    for (const double t : kDefaultThresholds) {
      if (t > wet_depth_m) out.push_back(t);
    }
    DefaultsRecord::note(o.path("depth_thresholds"), out);
    return out;
  }
  const std::string path = o.path("depth_thresholds");
  const std::string expected =
      "an array of depths (metres), each above wet_depth (" + fmt(wet_depth_m) + " m)";
  if (!v->is_array()) throw ScenarioError(path, describe(*v), expected);
  for (std::size_t i = 0; i < v->size(); ++i) {
    const double t = finite_number((*v)[i], element_path(path, i),
                                   "a depth above wet_depth (" + fmt(wet_depth_m) + " m)");
    if (!(t > wet_depth_m)) {
      throw ScenarioError(element_path(path, i), describe((*v)[i]),
                          "a depth above wet_depth (" + fmt(wet_depth_m) + " m)");
    }
    out.push_back(t);
  }
  return out;
}

maps::LandUse read_land_use(const Object& o) {
  const std::string_view word =
      choice(o, "land_use", {"urban", "woodland", "pasture_arable"}, "urban");
  if (word == "woodland") return maps::LandUse::woodland;
  if (word == "pasture_arable") return maps::LandUse::pasture_arable;
  return maps::LandUse::urban;
}

// An ISO 8601 date and time (io::parse_calendar_time) as the CF units of a time axis, or
// empty when the text is not one.
std::string cf_time_units(std::string_view text) {
  const auto t = io::parse_calendar_time(text);
  if (!t) return {};
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "seconds since %04d-%02d-%02d %02d:%02d:%02d", t->year,
                t->month, t->day, t->hour, t->minute, static_cast<int>(t->second));
  std::string units = buffer;
  // A zone given in the text is kept, as an offset ("Z" as +00:00).
  if (t->zoned) {
    const int m = std::abs(t->offset_minutes);
    std::snprintf(buffer, sizeof buffer, " %c%02d:%02d", t->offset_minutes < 0 ? '-' : '+', m / 60,
                  m % 60);
    units += buffer;
  }
  return units;
}

// The level every body of the scene's starting water is filled to, when they share one: a
// level body's surface, or a uniform depth over no bed (the plane z = 0). None when a body's
// surface is not level or two bodies differ.
std::optional<double> common_still_level(const Scenario& scene) {
  std::optional<double> level;
  for (const WaterBody& body : scene.water) {
    std::optional<double> surface;
    if (const auto* filled = std::get_if<LevelSurface>(&body.depth)) {
      surface = filled->surface_elevation_m;
    } else if (const auto* uniform = std::get_if<UniformDepth>(&body.depth);
               uniform && std::holds_alternative<std::monostate>(scene.bed)) {
      surface = uniform->depth_m;
    }
    if (!surface || (level && *level != *surface)) return std::nullopt;
    level = surface;
  }
  return level;
}

std::optional<TsunamiOutput> read_tsunami(const json* v, const std::string& path,
                                          const Scenario& scene, double wet_depth_m) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, path, {"still_level", "arrival_rise", "inundation_line"}, "an object");
  TsunamiOutput out;
  const std::string level_expected =
      "the elevation of the sea at rest (metres), which the scene's water does not give: its "
      "bodies are not all filled to one level";
  const std::optional<double> filled = common_still_level(scene);
  out.levels.still_level_m = number(o, "still_level", level_expected, filled);
  // The wet depth is the scene's own measure of water that counts; a film's rise is none.
  out.levels.arrival_rise_m =
      positive(o, "arrival_rise", kMetres, wet_depth_m > 0.0 ? wet_depth_m : 0.01);
  const std::string_view format = choice(o, "inundation_line", {"gpkg", "geojson", "none"}, "gpkg");
  out.inundation_line = format == "gpkg"      ? VectorFormat::gpkg
                        : format == "geojson" ? VectorFormat::geojson
                                              : VectorFormat::none;
  return out;
}

// "all", or a list of the maps to write as GeoTIFF; the tsunami maps only with `tsunami`, the
// provenance maps only with the provenance they map.
std::vector<std::string> read_rasters(const Object& o, bool tsunami,
                                      const ProvenanceOutput& provenance) {
  const json* v = o.find("rasters");
  if (v == nullptr) return {};
  std::vector<std::string> known = maps::summary_map_names();
  if (!tsunami) std::erase_if(known, maps::is_tsunami_map);
  if (provenance.sources) known.insert(known.end(), {"max_source_depth", "max_source_share"});
  if (provenance.age) known.push_back("max_mean_age");
  const Names choices(known.begin(), known.end());
  const std::string path = o.path("rasters");
  if (v->is_string() && v->get_ref<const std::string&>() == "all") return known;
  if (!v->is_array()) {
    throw ScenarioError(path, describe(*v), "\"all\" or an array of map names");
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string name(word((*v)[i], element_path(path, i), choices));
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  }
  return out;
}

ProvenanceOutput read_provenance(const json* v, const std::string& path) {
  if (v == nullptr) return {};
  const Object o(*v, path, {"sources", "age"}, "an object");
  ProvenanceOutput out;
  out.sources = optional_bool(o, "sources", false);
  out.age = optional_bool(o, "age", false);
  return out;
}

}  // namespace

Output read_output(const json* v, const Scenario& scene, const std::filesystem::path& base_dir) {
  const std::string path = "/output";
  const Object o(v ? *v : empty_object(), path,
                 {"path", "times", "interval", "grid", "particles", "gauges", "series_interval",
                  "wet_depth", "depth_thresholds", "land_use", "start_time", "rasters",
                  "raster_format", "tsunami", "provenance", "pathlines"},
                 "an object");
  Output out;
  out.path = read_output_path(o, scene.name, base_dir);
  out.times_s = read_times(o, scene.end_time_s);
  out.grid = read_grid(o.find("grid"), o.path("grid"), scene);
  out.write_particles = optional_bool(o, "particles", true);
  out.gauges = read_gauges(o.find("gauges"), o.path("gauges"));
  // 500 samples draw smooth gauge curves and time the flood to a fifth of a percent of the run.
  out.series_interval_s = positive(o, "series_interval", kSeconds, scene.end_time_s / 500.0);
  if (scene.end_time_s / out.series_interval_s > kMaxOutputTimes) {
    throw ScenarioError(
        o.path("series_interval"),
        describe(*o.find("series_interval")) + ", giving " +
            fmt(scene.end_time_s / out.series_interval_s) + " samples",
        "an interval giving at most " + fmt(kMaxOutputTimes) + " samples (seconds)");
  }
  out.wet_depth_m = non_negative(o, "wet_depth", kMetres, out.wet_depth_m);
  out.depth_thresholds_m = read_thresholds(o, out.wet_depth_m);
  out.land_use = read_land_use(o);
  const std::string date_expected =
      "an ISO 8601 date and time of t = 0, such as \"2024-06-01T12:00:00Z\" or "
      "\"2024-06-01T12:00:00+02:00\"";
  if (const auto start = optional_string(o, "start_time", date_expected)) {
    const std::string units = cf_time_units(*start);
    if (units.empty()) {
      throw ScenarioError(o.path("start_time"), describe(*o.find("start_time")), date_expected);
    }
    out.start_time = *start;
    out.start_time_units = units;
  }
  out.tsunami = read_tsunami(o.find("tsunami"), o.path("tsunami"), scene, out.wet_depth_m);
  out.provenance = read_provenance(o.find("provenance"), o.path("provenance"));
  out.rasters = read_rasters(o, out.tsunami.has_value(), out.provenance);
  out.pathlines = read_pathlines(o.find("pathlines"), o.path("pathlines"), scene, out, base_dir);
  out.raster_cog = choice(o, "raster_format", {"cog", "geotiff"}, "cog") == "cog";
  return out;
}

}  // namespace swemps::scenario

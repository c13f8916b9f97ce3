// The "pathlines" block of a scene's output (docs/provenance.md, "Pathlines"): which particles
// to follow, from when, how often a vertex is kept, and the vector file they go to. Reading
// the polygon file is build's; this checks the words.

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// At most this many lines: each keeps a vertex per interval, and a GIS draws them one by one.
constexpr int kMaxPathlines = 100000;
// At most this many vertices a line, as the output's other intervals are held to.
constexpr double kMaxVertices = 1e6;

// The path given (relative to the scenario's folder), whose extension says the format; none:
// beside the output wherever the run writes it (PathlineOutput::path).
void read_path(const Object& o, const Output& output, const std::filesystem::path& base_dir,
               PathlineOutput& out) {
  const std::string expected =
      "a file name or path ending in .gpkg or .geojson (relative to the scenario's folder)";
  const auto text = optional_string(o, "path", expected);
  if (!text) return;
  std::filesystem::path p(*text);
  if (p.is_relative()) p = base_dir / p;
  p = std::filesystem::absolute(p).lexically_normal();
  const std::string extension = p.extension().string();
  if (extension == ".gpkg") {
    out.format = VectorFormat::gpkg;
  } else if (extension == ".geojson" || extension == ".json") {
    out.format = VectorFormat::geojson;
  } else {
    throw ScenarioError(o.path("path"), describe(*o.find("path")), expected);
  }
  if (p == output.path) {
    throw ScenarioError(o.path("path"), describe(*o.find("path")) + ", the netCDF output's path",
                        expected + " other than the output's");
  }
  out.path = p;
}

}  // namespace

std::optional<PathlineOutput> read_pathlines(const json* v, const std::string& path,
                                             const Scenario& scene, const Output& output,
                                             const std::filesystem::path& base_dir) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, path, {"path", "count", "source", "polygon", "start", "interval"},
                 "an object");
  PathlineOutput out;
  read_path(o, output, base_dir, out);
  out.count = static_cast<std::size_t>(
      whole_number(o, "count", 1, kMaxPathlines, "the most particles to follow", 100));
  if (const auto source = optional_string(o, "source", "the name of a source of the scene")) {
    const auto labels = provenance_labels(scene);
    if (std::find(labels.begin(), labels.end(), *source) == labels.end()) {
      std::vector<std::string_view> names(labels.begin(), labels.end());
      throw ScenarioError(o.path("source"), describe(*o.find("source")),
                          "the name of a source of the scene: one of " + join(names, true) +
                              did_you_mean(*source, names));
    }
    // The particles tell their sources apart only when they carry them.
    if (!output.provenance.sources) {
      throw ScenarioError(o.path("source"), describe(*o.find("source")),
                          "no \"source\" unless output.provenance.sources is true (the "
                          "particles carry their sources only then)");
    }
    out.source = *source;
  }
  if (const json* polygon = o.find("polygon")) {
    if (polygon->is_array()) {
      out.polygon = read_polygon(*polygon, o.path("polygon"));
    } else {
      const Object file(*polygon, o.path("polygon"), {"file", "layer", "crs", "reproject"},
                        "an object with a \"file\" of polygons, or an array of [x, y] vertices");
      out.polygon_file = read_polygon_file_keys(file, o.path("polygon"), base_dir);
    }
  }
  out.start_s = in_range(o, "start", 0.0, false, scene.end_time_s, true,
                         "the time the particles are chosen, before the end (seconds)", 0.0);
  out.interval_s = positive(o, "interval", kSeconds, output.series_interval_s);
  if ((scene.end_time_s - out.start_s) / out.interval_s > kMaxVertices) {
    throw ScenarioError(
        o.path("interval"), describe(*o.find("interval")),
        "an interval giving at most " + fmt(kMaxVertices) + " vertices a line (seconds)");
  }
  return out;
}

}  // namespace swemps::scenario

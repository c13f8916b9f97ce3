#pragma once
// The sections of a scene file that load.cpp leaves to other files of the scenario module.
// Internal to it: not part of the public headers.

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "json_reading.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

// Reading points and files (load.cpp): an [x, y] pair; an array of at least `min_count`
// points (`coordinates` names the pair: "x, z" for a bed profile); consecutive points that
// differ (a polygon's last one from its first too); a required file name resolved against
// the scene's folder (`what` says what the file holds).
std::array<double, 2> pair(const json_reading::json& v, const std::string& path,
                           const std::string& expected);
std::vector<Point> points(const json_reading::json& v, const std::string& path,
                          std::size_t min_count, const std::string& coordinates = "x, y");
void check_distinct_neighbours(const std::vector<Point>& pts, const std::string& path,
                               bool closed);
std::filesystem::path file_path(const json_reading::Object& o, std::string_view key,
                                const std::string& what, const std::filesystem::path& base_dir);

// Names tell the entries of an array (inflows, sea boundaries) apart in the run's report:
// entry `index` of `array_path`, named `name`, must not repeat the name of one before it
// (`names`). `what` is the entry's kind, as "inflow".
void check_new_name(const std::vector<std::string>& names, const std::string& name,
                    const std::string& array_path, std::size_t index, const std::string& what);

// Shapes and places (load.cpp): a box object; a simple polygon of at least 3 points; a box's
// four corners; points that must lie inside the domain (`vertex_paths` points an error at the
// vertex, `what` names the thing).
Rectangle read_box(const json_reading::json& v, const std::string& path);
std::vector<Point> read_polygon(const json_reading::json& v, const std::string& path);
std::vector<Point> corners(const Rectangle& r);
void check_inside(const std::vector<Point>& poly, const Rectangle& domain, const std::string& path,
                  bool vertex_paths, const std::string& what = "water lying");
// o["crs"], empty when not given; "both "a" and "b"" or "all of ..." for keys that exclude
// each other (load.cpp).
std::string crs_text(const json_reading::Object& o);
std::string several(const std::vector<std::string_view>& keys);

// "[x_min, x_max] x [y_min, y_max]", for messages (load.cpp).
std::string describe_box(const Rectangle& r);

// The four box keys of `o`, all required, min < max on both axes (load.cpp).
Rectangle box(const json_reading::Object& o);
extern const json_reading::Names kBoxKeys;  // x_min, x_max, y_min, y_max

// The smallest axis-aligned box around at least one point (load.cpp).
Rectangle bounding_box(const std::vector<Point>& pts);

// The "water" section (load_water.cpp). `default_spacing_m`: the particle spacing of water
// that gives none (model ns, whose lattice spacing is the "ns" block's); 0: each body must
// give one. The scheme decides the default volume rule.
std::vector<WaterBody> read_waters(const json_reading::json* v,
                                   const std::optional<Rectangle>& domain, bool has_bed,
                                   const std::filesystem::path& base_dir, double default_spacing_m,
                                   swe::SchemeKind scheme);

// A series of [time, value] points (load_flows.cpp): a non-empty array, times strictly
// increasing, values >= 0 where `value` says so. `expected` replaces the message for a value
// that is not such an array (empty: "an array of at least 1 [time, <name>] point").
struct SeriesValue {
  std::string_view name;  // "discharge", in messages
  std::string_view unit;  // "m^3/s"
  bool non_negative = false;
};
std::vector<std::array<double, 2>> read_time_series(const json_reading::json& v,
                                                    const std::string& path,
                                                    const SeriesValue& value,
                                                    const std::string& expected = {});

// The "inflow" and "outflow" sections (load_flows.cpp); an inflow's spacing defaults to the
// finest of the water's.
std::vector<Inflow> read_inflows(const json_reading::json* v, const std::vector<WaterBody>& water,
                                 const std::filesystem::path& base_dir);
std::vector<Outflow> read_outflows(const json_reading::json* v);
// The "rain" section (load_rain.cpp): one rain object or an array of them; a rain's spacing
// defaults to the finest of the water's and the inflows'.
std::vector<RainSpec> read_rain(const json_reading::json* v, const std::vector<WaterBody>& water,
                                const std::vector<Inflow>& inflows,
                                const std::filesystem::path& base_dir);

// The "buildings" section (load_buildings.cpp): one object or an array of them.
std::vector<BuildingsSpec> read_buildings(const json_reading::json* v,
                                          const std::filesystem::path& base_dir);

// The "fault_source" section (load_tsunami.cpp); absent: none.
std::optional<FaultSourceSpec> read_fault_source(const json_reading::json* v);
// The "sea_boundaries" section (load_tsunami.cpp); a boundary's spacing defaults to the finest
// of the water's.
std::vector<SeaBoundarySpec> read_sea_boundaries(const json_reading::json* v,
                                                 const std::vector<WaterBody>& water,
                                                 const std::filesystem::path& base_dir);

// The "friction" section (load_friction.cpp); absent: no friction.
std::optional<ManningSpec> read_friction(const json_reading::json* v,
                                         const std::filesystem::path& base_dir);

// The "output" section, read after everything it refers to (load_output.cpp).
Output read_output(const json_reading::json* v, const Scenario& scene,
                   const std::filesystem::path& base_dir);
// A grid spacing over `bounds` must give at most a billion cells (load_output.cpp).
void check_grid_cells(double spacing_m, const Rectangle& bounds, const std::string& path);

// "model", "dimension" and the "ns" block (load_ns.cpp).
void read_model(const json_reading::Object& o, double gravity, Scenario& s);
// Model ns: the tank's height when the "ns" block gives none, twice the deepest water on the
// lattice (load_ns.cpp).
void default_tank_height(Scenario& s);

// The keys "file", "layer", "crs" and "reproject" of a vector file of polygons, as buildings
// and the pathlines' polygon take them (load_buildings.cpp); `path` is where `o` stands.
PolygonFileSpec read_polygon_file_keys(const json_reading::Object& o, const std::string& path,
                                       const std::filesystem::path& base_dir);

// The output's "pathlines" block (load_pathlines.cpp), read after the rest of `output`: its
// default path is beside output.path, its default interval the series interval, and a
// source to follow needs output.provenance.sources.
std::optional<PathlineOutput> read_pathlines(const json_reading::json* v, const std::string& path,
                                             const Scenario& scene, const Output& output,
                                             const std::filesystem::path& base_dir);

}  // namespace swemps::scenario

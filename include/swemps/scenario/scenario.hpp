#pragma once
// A validated scene: plain structs, filled from scenario.json by load() and checked there.
// Nothing below this module knows JSON exists.

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "swemps/splitting/particle_splitting.hpp"
#include "swemps/swe/settings.hpp"

namespace swemps::scenario {

using Point = std::array<double, 2>;  // (x, y) in m

struct Rectangle {
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;  // m
};

// A body of still or moving water: a polygon (a rectangle is stored as its 4 corners),
// filled with particles on a square lattice of the given spacing.
struct WaterBody {
  std::vector<Point> polygon;  // counter-clockwise or clockwise, not closed, >= 3 vertices
  double depth_m = 0.0;
  std::array<double, 2> velocity_m_s{0.0, 0.0};
  double spacing_m = 0.0;
};

enum class WallCondition { slip, no_slip };

// A wall is a polyline of straight segments; particles are kept on the side they start on.
struct Wall {
  std::vector<Point> polyline;  // >= 2 vertices
  WallCondition condition = WallCondition::slip;
};

// Analytic beds. No bed at all (the default) is a flat bed at z = 0 and costs nothing.
struct PlaneBedSpec {
  double elevation_m = 0.0;            // z_b at the origin
  std::array<double, 2> slope{0.0, 0.0};  // dz_b/dx, dz_b/dy (m/m)
  Point origin_m{0.0, 0.0};
};
struct ProfileBedSpec {
  std::vector<Point> points;  // (x, z_b) in m, x strictly increasing; level beyond the ends
};
using BedSpec = std::variant<std::monostate, PlaneBedSpec, ProfileBedSpec>;

struct GridSpec {
  double spacing_m = 0.0;
  Rectangle bounds;  // cell centres at bounds.x_min + (i + 0.5) spacing_m, ...
};

struct Output {
  std::filesystem::path path;   // absolute once loaded
  std::vector<double> times_s;  // sorted, unique, in (0, end_time]; t = 0 is always written too
  GridSpec grid;
  bool write_particles = true;
};

struct Scenario {
  std::string name;
  std::string description;
  double end_time_s = 0.0;
  swe::Settings numerics;
  Rectangle domain;  // particles leaving it are removed and their volume booked
  std::vector<WaterBody> water;
  std::vector<Wall> walls;
  BedSpec bed;
  std::optional<double> manning_n;  // s m^-1/3; absent: no friction
  std::optional<splitting::SplittingSettings> splitting;  // absent: no splitting
  Output output;
};

// A problem in a scenario file: where (JSON path such as /water/0/depth), what was found,
// what was expected. what() gives all three in one line.
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(std::string json_path, std::string found, std::string expected);
  const std::string& json_path() const { return json_path_; }
  const std::string& found() const { return found_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string json_path_, found_, expected_;
};

// Reads and validates a scenario file. Relative paths inside it are taken relative to the
// file's folder. Throws ScenarioError (file unreadable, syntax, unknown key, bad value).
Scenario load(const std::filesystem::path& file);

// The same from text; `base_dir` resolves relative paths, `default_name` names an unnamed scene.
Scenario parse(const std::string& text, const std::filesystem::path& base_dir,
               const std::string& default_name = "scenario");

}  // namespace swemps::scenario

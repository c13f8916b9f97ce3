#include "boundary_effects.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "json_reading.hpp"
#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/boundaries/inflow_line.hpp"
#include "swemps/boundaries/outflow_line.hpp"
#include "swemps/boundaries/sea_boundary.hpp"
#include "swemps/io/hydrograph_csv.hpp"

namespace swemps::scenario {

namespace {

// The unit normal of the line on the side of the domain's centre; `remedy` says what to give
// when the line's extension runs through the centre.
std::array<double, 2> towards_centre(const std::array<Point, 2>& line, const Rectangle& domain,
                                     const std::string& path, const std::string& remedy) {
  const auto& [a, b] = line;
  const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
  std::array<double, 2> normal{-(b[1] - a[1]) / length, (b[0] - a[0]) / length};
  const double to_x = 0.5 * (domain.x_min + domain.x_max) - 0.5 * (a[0] + b[0]);
  const double to_y = 0.5 * (domain.y_min + domain.y_max) - 0.5 * (a[1] + b[1]);
  const double side = normal[0] * to_x + normal[1] * to_y;
  if (std::abs(side) <= slack_for(domain)) {
    throw ScenarioError(path, "a line whose extension runs through the domain's centre", remedy);
  }
  if (side < 0.0) normal = {-normal[0], -normal[1]};
  return normal;
}

}  // namespace

SeriesPoints series_points(const std::variant<SeriesPoints, std::filesystem::path>& source,
                           SeriesPoints (*read_csv)(const std::filesystem::path&),
                           const std::string& csv_path, const std::string& expected) {
  if (const auto* table = std::get_if<SeriesPoints>(&source)) return *table;
  try {
    return read_csv(std::get<std::filesystem::path>(source));
  } catch (const std::runtime_error& e) {
    throw ScenarioError(csv_path, e.what(), expected);
  }
}

double slack_for(const Rectangle& r) {
  return 1e-9 * std::max({1.0, std::abs(r.x_min), std::abs(r.x_max), std::abs(r.y_min),
                          std::abs(r.y_max)});
}

std::unique_ptr<swe::Effect> make_inflow(const Inflow& in, std::size_t index,
                                         const Terrain& terrain, std::uint32_t label) {
  const std::string path = json_reading::element_path("/inflow", index);
  SeriesPoints points =
      series_points(in.hydrograph, io::read_hydrograph_csv, path + "/hydrograph_csv",
                    "a CSV file of time (s) and discharge (m^3/s) columns");
  boundaries::InflowLineSettings settings;
  settings.name = in.name;
  settings.label = label;
  settings.from = in.line[0];
  settings.to = in.line[1];
  settings.direction = in.direction
                           ? *in.direction
                           : towards_centre(in.line, terrain.domain, path + "/line",
                                            "a \"direction\" saying which way the water enters");
  settings.spacing_m = in.spacing_m;
  settings.depth_m = in.depth_m;
  settings.bed = terrain.bed;
  try {
    return std::make_unique<boundaries::InflowLine>(std::move(settings),
                                                    boundaries::Hydrograph(std::move(points)));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(path, e.what(), "an inflow line the boundary accepts");
  }
}

std::unique_ptr<swe::Effect> make_outflow(const std::vector<Outflow>& outflows) {
  std::vector<boundaries::Polyline> lines;
  for (const auto& outflow : outflows) lines.push_back(outflow.line);
  try {
    return std::make_unique<boundaries::OutflowLines>(std::move(lines));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError("/outflow", e.what(), "outflow lines the boundary accepts");
  }
}

namespace {

// The mean surface (depth + bed) of the starting water within two spacings of the line, beside
// its length; nullopt when none is.
std::optional<double> starting_level_beside(const SeaBoundarySpec& spec,
                                            const particles::SweParticles& p) {
  const auto& [a, b] = spec.line;
  const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
  const std::array<double, 2> t{(b[0] - a[0]) / length, (b[1] - a[1]) / length};
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double rx = p.x[i] - a[0], ry = p.y[i] - a[1];
    const double along = rx * t[0] + ry * t[1];
    const double across = std::abs(rx * t[1] - ry * t[0]);
    if (along < 0.0 || along > length || across > 2.0 * spec.spacing_m) continue;
    sum += p.depth[i] + p.bed[i];
    ++count;
  }
  if (count == 0) return std::nullopt;
  return sum / static_cast<double>(count);
}

// Whether a wall passes through the point (within the map's slack).
bool on_a_wall(const Point& point, const std::vector<Wall>& walls, const Rectangle& domain) {
  const double slack = std::max(1e-9, slack_for(domain));
  for (const Wall& wall : walls) {
    for (std::size_t k = 0; k + 1 < wall.polyline.size(); ++k) {
      const Point& a = wall.polyline[k];
      const Point& b = wall.polyline[k + 1];
      const double dx = b[0] - a[0], dy = b[1] - a[1];
      const double t = std::clamp(
          ((point[0] - a[0]) * dx + (point[1] - a[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      if (std::hypot(a[0] + t * dx - point[0], a[1] + t * dy - point[1]) <= slack) return true;
    }
  }
  return false;
}

}  // namespace

std::unique_ptr<swe::Effect> make_sea_boundary(const SeaBoundarySpec& spec, std::size_t index,
                                               const Terrain& terrain,
                                               const std::vector<Wall>& walls,
                                               const particles::SweParticles& seeded,
                                               std::uint32_t label) {
  const std::string path = json_reading::element_path("/sea_boundaries", index);
  boundaries::SeaBoundarySettings settings;
  settings.name = spec.name;
  settings.label = label;
  settings.from = spec.line[0];
  settings.to = spec.line[1];
  const auto inward = towards_centre(spec.line, terrain.domain, path + "/line",
                                     "a sea boundary along the domain's edge, or one whose "
                                     "extension passes beside the centre");
  settings.outward = {-inward[0], -inward[1]};
  settings.spacing_m = spec.spacing_m;
  settings.bed = terrain.bed;
  settings.walled_ends = {on_a_wall(spec.line[0], walls, terrain.domain),
                          on_a_wall(spec.line[1], walls, terrain.domain)};
  try {
    if (spec.level) {
      SeriesPoints points = series_points(*spec.level, io::read_level_csv, path + "/series_csv",
                                          "a CSV file of time (s) and level (m) columns");
      settings.level = boundaries::LevelSeries(std::move(points));
    } else if (spec.still_level_m) {
      settings.still_level_m = *spec.still_level_m;
    } else if (const auto level = starting_level_beside(spec, seeded)) {
      settings.still_level_m = *level;
    } else {
      throw ScenarioError(path + "/level", "no water within two spacings of the line at the start",
                          "the level of the sea at rest beyond the line (m)");
    }
    return std::make_unique<boundaries::SeaBoundary>(std::move(settings));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(path, e.what(), "a sea boundary the solver accepts");
  }
}

}  // namespace swemps::scenario

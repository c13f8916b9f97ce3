#include "hydrology_effects.hpp"

#include <string>
#include <utility>

#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/io/hydrograph_csv.hpp"

namespace swemps::scenario {

std::unique_ptr<swe::Effect> make_rain(const RainSpec& spec, const Terrain& terrain) {
  const std::string& path = spec.key_path;
  std::vector<std::array<double, 2>> points;
  if (const auto* table = std::get_if<std::vector<std::array<double, 2>>>(&spec.rate_mm_h)) {
    points = *table;
  } else {
    try {
      points = io::read_rain_csv(std::get<std::filesystem::path>(spec.rate_mm_h));
    } catch (const std::runtime_error& e) {
      throw ScenarioError(path + "/rate_csv", e.what(),
                          "a CSV file of time (s) and rain rate (mm/h) columns");
    }
  }
  for (auto& point : points) point[1] *= hydrology::kMetresPerSecondPerMmPerHour;
  hydrology::RainSettings settings;
  settings.name = spec.name;
  const auto& d = terrain.domain;
  settings.domain = {d.x_min, d.x_max, d.y_min, d.y_max};
  settings.spacing_m = spec.spacing_m;
  settings.polygon = spec.polygon;
  settings.creation_depth_m = spec.creation_depth_m;
  settings.losses.initial_m = spec.initial_loss_mm * 1e-3;
  settings.losses.continuing_m_s =
      spec.continuing_loss_mm_h * hydrology::kMetresPerSecondPerMmPerHour;
  settings.bed = terrain.bed;
  try {
    return std::make_unique<hydrology::Rain>(std::move(settings),
                                             boundaries::Hydrograph(std::move(points)));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(path, e.what(), "rain over cells of the domain");
  }
}

}  // namespace swemps::scenario

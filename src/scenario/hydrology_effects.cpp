#include "hydrology_effects.hpp"

#include <string>
#include <utility>

#include "boundary_effects.hpp"
#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/io/hydrograph_csv.hpp"

namespace swemps::scenario {

std::unique_ptr<swe::Effect> make_rain(const RainSpec& spec, const Terrain& terrain) {
  const std::string& path = spec.key_path;
  SeriesPoints points = series_points(spec.rate_mm_h, io::read_rain_csv, path + "/rate_csv",
                                      "a CSV file of time (s) and rain rate (mm/h) columns");
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
  settings.roofs = terrain.building_footprints;
  try {
    return std::make_unique<hydrology::Rain>(std::move(settings),
                                             boundaries::Hydrograph(std::move(points)));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(path, e.what(), "rain over cells of the domain");
  }
}

}  // namespace swemps::scenario

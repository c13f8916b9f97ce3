#include "hydrology_effects.hpp"

#include <string>
#include <utility>
#include <vector>

#include "boundary_effects.hpp"
#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/hydrology/rain_losses.hpp"
#include "swemps/hydrology/rain_rate.hpp"
#include "swemps/io/hydrograph_csv.hpp"

namespace swemps::scenario {

namespace {

constexpr double kMmH = hydrology::kMetresPerSecondPerMmPerHour;

std::unique_ptr<hydrology::RainRate> rain_rate(const RainSpec& spec,
                                               const Terrain::RainMaps& maps) {
  if (!maps.rate_mm_h.empty()) {
    std::vector<hydrology::MappedRainRate::Frame> frames;
    for (std::size_t k = 0; k < maps.rate_mm_h.size(); ++k) {
      frames.push_back({maps.rate_starts_s[k], maps.rate_mm_h[k]});
    }
    // The maps stay in mm/h, shared with the terrain rather than copied.
    return std::make_unique<hydrology::MappedRainRate>(std::move(frames), maps.rate_end_s, kMmH);
  }
  SeriesPoints points;
  if (const auto* table = std::get_if<SeriesPoints>(&spec.rate_mm_h)) {
    points = *table;
  } else {
    points = series_points(std::get<std::filesystem::path>(spec.rate_mm_h), io::read_rain_csv,
                           spec.key_path + "/rate_csv",
                           "a CSV file of time (s) and rain rate (mm/h) columns");
  }
  for (auto& point : points) point[1] *= kMmH;
  return std::make_unique<hydrology::UniformRainRate>(boundaries::Hydrograph(std::move(points)));
}

// A loss parameter in the solver's units: `factor` converts the scene's.
hydrology::CellParameter parameter(const ValueOrRaster& value, const std::string& key,
                                   double factor, const std::string& name,
                                   const Terrain::RainMaps& maps) {
  hydrology::CellParameter p;
  p.name = name;
  if (const double* number = std::get_if<double>(&value)) {
    p.value = *number * factor;
  } else {
    p.map = maps.parameters.at(key);
    p.scale = factor;
  }
  return p;
}

bool is_zero(const ValueOrRaster& value) {
  const double* number = std::get_if<double>(&value);
  return number != nullptr && *number == 0.0;
}

std::unique_ptr<hydrology::RainLoss> rain_losses(const RainSpec& spec,
                                                 const Terrain::RainMaps& maps) {
  auto initial = parameter(spec.initial_loss_mm, "initial_loss_mm", 1e-3, "initial loss", maps);
  if (spec.green_ampt) {
    const GreenAmptSpec& soil = *spec.green_ampt;
    hydrology::GreenAmptSoil s{
        parameter(soil.conductivity_mm_h, "green_ampt/conductivity_mm_h", kMmH,
                  "hydraulic conductivity", maps),
        parameter(soil.suction_mm, "green_ampt/suction_mm", 1e-3, "suction head", maps),
        parameter(soil.moisture_deficit, "green_ampt/moisture_deficit", 1.0, "moisture deficit",
                  maps)};
    s.moisture_deficit.most = 1.0;  // a fraction of the soil's volume
    return std::make_unique<hydrology::GreenAmptLoss>(std::move(s), std::move(initial));
  }
  // No losses at all cost nothing.
  if (is_zero(spec.initial_loss_mm) && is_zero(spec.continuing_loss_mm_h)) return nullptr;
  return std::make_unique<hydrology::InitialContinuingLoss>(
      std::move(initial),
      parameter(spec.continuing_loss_mm_h, "continuing_loss_mm_h", kMmH, "continuing loss", maps));
}

}  // namespace

std::unique_ptr<swe::Effect> make_rain(const RainSpec& spec, const Terrain::RainMaps& maps,
                                       const Terrain& terrain, std::uint32_t label) {
  const std::string& path = spec.key_path;
  hydrology::RainSettings settings;
  settings.name = spec.name;
  settings.label = label;
  const auto& d = terrain.domain;
  settings.domain = {d.x_min, d.x_max, d.y_min, d.y_max};
  settings.spacing_m = spec.spacing_m;
  settings.polygon = spec.polygon;
  settings.creation_depth_m = spec.creation_depth_m;
  settings.bed = terrain.bed;
  settings.roofs = terrain.building_footprints;
  try {
    return std::make_unique<hydrology::Rain>(std::move(settings), rain_rate(spec, maps),
                                             rain_losses(spec, maps));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(path, e.what(), "rain over cells of the domain");
  }
}

}  // namespace swemps::scenario

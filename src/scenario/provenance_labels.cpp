// The provenance labels of a scene's water (docs/provenance.md).

#include <algorithm>
#include <stdexcept>

#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

std::vector<std::string> provenance_labels(const Scenario& scene) {
  std::vector<std::string> labels;
  const auto add = [&](const std::string& name) {
    if (std::find(labels.begin(), labels.end(), name) == labels.end()) labels.push_back(name);
  };
  for (const WaterBody& body : scene.water) add(body.name);
  for (const Inflow& inflow : scene.inflows) add(inflow.name);
  for (const SeaBoundarySpec& sea : scene.sea_boundaries) add(sea.name);
  for (const RainSpec& rain : scene.rain) add(rain.name);
  return labels;
}

std::uint32_t provenance_label(const Scenario& scene, const std::string& name) {
  const auto labels = provenance_labels(scene);
  const auto found = std::find(labels.begin(), labels.end(), name);
  if (found == labels.end()) {
    throw std::out_of_range("no source of the scene's water is named '" + name + "'");
  }
  return static_cast<std::uint32_t>(found - labels.begin());
}

}  // namespace swemps::scenario

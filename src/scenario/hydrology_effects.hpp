#pragma once
// The effects of the water a scene brings from above: rain and its losses. Internal to the
// scenario module: build.cpp adds them to the simulation in their order within the topology
// stage.

#include <cstddef>
#include <memory>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::scenario {

// A rain of the scene over the terrain's domain, with the maps read for it (terrain.rain) and
// its rate file read now; ScenarioError at its key.
// `label`: the provenance label of its water (provenance_label()).
std::unique_ptr<swe::Effect> make_rain(const RainSpec& spec, const Terrain::RainMaps& maps,
                                       const Terrain& terrain, std::uint32_t label);

}  // namespace swemps::scenario

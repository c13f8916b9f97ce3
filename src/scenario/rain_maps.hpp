#pragma once
// Reading the maps a scene's rain names: the rate as one map or a netCDF series of maps, and
// the losses' parameters given as rasters (docs/rain.md). Internal to the scenario module.

#include "scene_crs.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

// Fills terrain.rain, one entry per scene.rain. A series' times are converted to seconds of
// the run: its units' reference date against the scene's output.start_time when both are
// given, else counted from the reference date itself. Its values are converted to mm/h from
// the variable's units (none: mm/h). Throws ScenarioError at the rain's key for a raster that
// cannot be read, units it does not know, or times that do not increase.
void read_rain_maps(const Scenario& scene, SceneCrs& crs, Terrain& terrain);

}  // namespace swemps::scenario

#pragma once
// From a validated Scenario to the objects that run it: the particles, the walls, the
// effects the scene asks for, the output grid.

#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/operators.hpp"
#include "swemps/swe/simulation.hpp"

namespace swemps::scenario {

swe::Simulation make_simulation(const Scenario& scene);

// The output grid: cell centres covering the requested bounds at the requested spacing.
swe::RegularGrid output_grid(const Scenario& scene);

}  // namespace swemps::scenario

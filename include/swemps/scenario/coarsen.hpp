#pragma once
// A scene with its particles further apart: what `swe-mps check` runs in memory, to its end
// time, to see how the run's time step and particle count develop at a fraction of the
// run's cost (a pilot run).

#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

// `scene` with every particle spacing it sets `factor` times wider: each water body's and
// each inflow's (shallow water), the tank's lattice (model ns), and a splitting cap divided by
// factor^2, so that the cap stops splitting at the same share of the water. Everything the
// spacing does not set stays: the bed, walls, friction, hydrographs, the end time. Splitting
// and merging decide by a particle's area against its own starting area, so they act alike
// at any spacing. Throws std::invalid_argument for a factor below 1, and ScenarioError for a
// Navier-Stokes tank whose sides are not whole numbers of the wider spacing.
Scenario coarsened(const Scenario& scene, int factor);

}  // namespace swemps::scenario

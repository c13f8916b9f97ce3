#pragma once
// When a run samples its flood statistics, shared by the run (swe_run.cpp) and by `check`'s
// count of the samples a run would take (wall_time_estimate.hpp).

#include "swemps/particles/swe_particles.hpp"

namespace swemps::cli {

// A sample comes once a wave could have crossed this share of the shortest length the maps
// resolve (CellAverages::resolved_length_m): the Courant number 0.5 of a grid model on cells
// of that size.
inline constexpr double kMapCourant = 0.5;

// The fastest wave speed |u| + sqrt(g h) of any fluid particle; 0 without water.
double fastest_wave_m_s(const particles::SweParticles& p, double gravity_m_s2);

}  // namespace swemps::cli

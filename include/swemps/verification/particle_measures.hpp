#pragma once
// Measures of a particle state that the seed cases are judged by (docs/verification.md):
// the wave tip, and how evenly the particles are spaced.

#include <cstddef>

#include "swemps/particles/swe_particles.hpp"

namespace swemps::verification {

// The tip of a wave running in +x: the foremost fluid particle (largest x) and its summed
// depth (eq 7). The depth is the one of the last summation, so call this on a refreshed state.
struct TipParticle {
  std::size_t index;
  double x_m;
  double depth_m;
  double volume_m3;
};
TipParticle foremost_particle(const particles::SweParticles& p);

// Distance from each fluid particle to its nearest fluid neighbour: smallest, median, largest.
// Brute force, O(n^2): meant for verification runs of up to some 1e4 particles.
struct SpacingStats {
  double min_m;
  double median_m;
  double max_m;
};
SpacingStats nearest_neighbour_spacing(const particles::SweParticles& p);

}  // namespace swemps::verification

#include "swemps/verification/particle_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::verification {

TipParticle foremost_particle(const particles::SweParticles& p) {
  const std::size_t n = p.fluid_count();
  if (n == 0) throw std::invalid_argument("foremost_particle: no fluid particles");
  std::size_t tip = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (p.x[i] > p.x[tip]) tip = i;
  }
  return {tip, p.x[tip], p.depth[tip], p.volume[tip]};
}

SpacingStats nearest_neighbour_spacing(const particles::SweParticles& p) {
  const std::size_t n = p.fluid_count();
  if (n < 2) throw std::invalid_argument("nearest_neighbour_spacing: fewer than two particles");
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  parallel_for(n, [&](std::size_t i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j) {
      if (j != i) best = std::min(best, std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]));
    }
    nearest[i] = best;
  });
  const auto middle = nearest.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(nearest.begin(), middle, nearest.end());
  const double median = *middle;
  const auto [lo, hi] = std::minmax_element(nearest.begin(), nearest.end());
  return {*lo, median, *hi};
}

}  // namespace swemps::verification

#include "swemps/cli/statistics_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace swemps::cli {

double fastest_wave_m_s(const particles::SweParticles& p, double gravity_m_s2) {
  double fastest = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double c =
        std::hypot(p.u[i], p.v[i]) + std::sqrt(gravity_m_s2 * std::max(p.depth[i], 0.0));
    fastest = std::max(fastest, c);
  }
  return fastest;
}

}  // namespace swemps::cli

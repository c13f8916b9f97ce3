#include "swemps/swe/manning_friction.hpp"

#include <cmath>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

void ManningFriction::apply(StepContext& context) {
  auto& p = context.particles;
  const double coefficient = context.dt_s * context.settings.gravity_m_s2 * manning_n_ * manning_n_;
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    const double speed = std::sqrt(p.u[i] * p.u[i] + p.v[i] * p.v[i]);
    const double factor = 1.0 / (1.0 + coefficient * speed / std::pow(p.depth[i], 4.0 / 3.0));
    p.u[i] *= factor;
    p.v[i] *= factor;
  });
}

}  // namespace swemps::swe

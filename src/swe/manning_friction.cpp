#include "swemps/swe/manning_friction.hpp"

#include <cmath>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

void ManningFriction::apply(StepContext& context) {
  auto& p = context.particles;
  const double dt_g = context.dt_s * context.settings.gravity_m_s2;
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    const double n = roughness_ ? roughness_->manning_n(p.x[i], p.y[i]) : manning_n_;
    const double coefficient = dt_g * n * n;
    const double speed = std::sqrt(p.u[i] * p.u[i] + p.v[i] * p.v[i]);
    const double factor = 1.0 / (1.0 + coefficient * speed / std::pow(p.depth[i], 4.0 / 3.0));
    p.u[i] *= factor;
    p.v[i] *= factor;
  });
}

}  // namespace swemps::swe

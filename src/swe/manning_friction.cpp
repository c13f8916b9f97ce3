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
    // The speed the step started with: the velocity before this step's acceleration.
    const double u0 = p.u[i] - context.dt_s * context.accel_x[i];
    const double v0 = p.v[i] - context.dt_s * context.accel_y[i];
    const double speed = std::sqrt(u0 * u0 + v0 * v0);
    const double factor = 1.0 / (1.0 + coefficient * speed / std::pow(p.depth[i], 4.0 / 3.0));
    p.u[i] *= factor;
    p.v[i] *= factor;
  });
}

}  // namespace swemps::swe

#include "swemps/swe/bed_slope.hpp"

#include "swemps/neighbors/parallel.hpp"
#include "swemps/swe/operators.hpp"

namespace swemps::swe {

void sample_bed_at_particles(const BedSource& bed, particles::SweParticles& p) {
  const std::size_t n = p.fluid_count();
  parallel_for(n, [&](std::size_t i) { p.bed[i] = bed.elevation(p.x[i], p.y[i]); });
  for (std::size_t k = n; k < p.size(); ++k) p.bed[k] = p.bed[p.source[k]];
}

void BedSlope::apply(StepContext& context) {
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();
  sample_bed_at_particles(*bed_, p);

  const double g = context.settings.gravity_m_s2;
  switch (gradient_) {
    case GradientVariant::mps:
      parallel_for(n, [&](std::size_t i) {
        const auto grad =
            mps_gradient_at(p, context.neighbors, context.kernel, i, p.bed, p.number_density[i]);
        context.accel_x[i] -= g * grad[0];
        context.accel_y[i] -= g * grad[1];
      });
      return;
    case GradientVariant::summation:
      parallel_for(n, [&](std::size_t i) {
        const auto grad = bed_->gradient(p.x[i], p.y[i]);
        context.accel_x[i] -= g * grad[0];
        context.accel_y[i] -= g * grad[1];
      });
      return;
  }
}

}  // namespace swemps::swe

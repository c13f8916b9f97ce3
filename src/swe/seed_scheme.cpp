#include "swemps/swe/seed_scheme.hpp"

#include <algorithm>
#include <limits>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

namespace {
// eq 8 at the radius every fluid particle carries (also after a restore, which sets the
// radii without choosing them).
Kernel common_kernel(const particles::SweParticles& p) { return Kernel(p.smoothing_length[0]); }
}  // namespace

SeedScheme::SeedScheme(const Settings& settings) : settings_(settings) {}

void SeedScheme::choose_smoothing_lengths(particles::SweParticles& p) {
  const std::size_t n = p.fluid_count();
  if (n == 0) return;
  // The radius of the last summation tells which particles it left isolated (their area is
  // 1 / w(0) of its kernel); before the first, or for a restored state, it is the one every
  // summed particle carries. None yet: no particle is known to be isolated.
  double previous = 0.0;
  for (std::size_t i = 0; i < n; ++i) previous = std::max(previous, p.smoothing_length[i]);
  const double isolated_area = previous > 0.0 ? 1.0 / Kernel(previous).w(0.0)
                                              : std::numeric_limits<double>::infinity();
  const double radius =
      influence_radius(p, settings_.alpha_e, settings_.area_ratio_cap(), isolated_area);
  std::fill(p.smoothing_length.begin(), p.smoothing_length.begin() + static_cast<std::ptrdiff_t>(n),
            radius);
}

bool SeedScheme::sum_depth(particles::SweParticles& p, const neighbors::NeighborList& nl) {
  if (p.fluid_count() > 0) swe::sum_depth(p, nl, common_kernel(p));
  return true;
}

void SeedScheme::surface_acceleration(particles::SweParticles& p,
                                      const neighbors::NeighborList& nl, double gravity_m_s2,
                                      std::span<double> accel_x, std::span<double> accel_y) {
  if (p.fluid_count() == 0) return;
  depth_gradient(settings_.gradient, p, nl, common_kernel(p), accel_x, accel_y);
  parallel_for(p.fluid_count(), [&](std::size_t i) {  // eq 2 with z_s = h on a flat bed
    accel_x[i] *= -gravity_m_s2;
    accel_y[i] *= -gravity_m_s2;
  });
}

}  // namespace swemps::swe

#include "swemps/verification/ritter.hpp"

#include <algorithm>
#include <cmath>

namespace swemps::verification {

double ritter_depth(const RitterProblem& p, double x, double t) {
  const double c0 = std::sqrt(p.gravity_m_s2 * p.initial_depth_m);
  const double xi = (x - p.dam_x_m) / t;
  if (xi <= -c0) return x >= p.reservoir_start_x_m ? p.initial_depth_m : 0.0;
  if (xi >= 2.0 * c0) return 0.0;
  const double s = 2.0 * c0 - xi;
  return s * s / (9.0 * p.gravity_m_s2);  // eq 14
}

double ritter_velocity(const RitterProblem& p, double x, double t) {
  const double c0 = std::sqrt(p.gravity_m_s2 * p.initial_depth_m);
  const double xi = (x - p.dam_x_m) / t;
  if (xi <= -c0 || xi >= 2.0 * c0) return 0.0;
  return 2.0 / 3.0 * (xi + c0);  // eq 14
}

Profile channel_profile(const particles::SweParticles& p, const swe::ParticleKernel& kernel,
                        const Channel& channel, double dx_m) {
  const auto nx = static_cast<std::size_t>(std::round((channel.x_max_m - channel.x_min_m) / dx_m));
  const auto ny = static_cast<std::size_t>(std::round((channel.y_max_m - channel.y_min_m) / dx_m));
  const swe::RegularGrid grid{
      channel.x_min_m + dx_m / 2, channel.y_min_m + dx_m / 2, dx_m, dx_m, nx, ny};
  const auto depth = swe::depth_on_grid(p, kernel, grid);
  Profile profile{grid.x0, dx_m, std::vector<double>(nx, 0.0)};
  for (std::size_t k = 0; k < ny; ++k) {
    for (std::size_t i = 0; i < nx; ++i) {
      profile.depth_m[i] += depth[k * nx + i] / static_cast<double>(ny);
    }
  }
  return profile;
}

RitterErrors compare_with_ritter(const RitterProblem& p, const Profile& profile, double t,
                                 double front_threshold) {
  const double c0 = std::sqrt(p.gravity_m_s2 * p.initial_depth_m);
  const double fan_start = p.dam_x_m - c0 * t;
  const double fan_end = p.dam_x_m + 2.0 * c0 * t;
  RitterErrors e{0.0, 0.0, 0.0, 0.0, profile.x0_m, fan_end};
  double length = 0.0, upstream_length = 0.0;
  for (std::size_t k = 0; k < profile.depth_m.size(); ++k) {
    const double x = profile.x0_m + static_cast<double>(k) * profile.dx_m;
    const double h = profile.depth_m[k];
    if (h > front_threshold) e.front_x_m = x;
    if (x < fan_start || x > fan_end) continue;
    const double diff = std::abs(h - ritter_depth(p, x, t));
    e.fan_l1 += diff * profile.dx_m;
    e.fan_l2 += diff * diff * profile.dx_m;
    e.fan_linf = std::max(e.fan_linf, diff);
    length += profile.dx_m;
    if (x <= p.dam_x_m) {
      e.upstream_fan_l1 += diff * profile.dx_m;
      upstream_length += profile.dx_m;
    }
  }
  const double h0 = p.initial_depth_m;
  e.fan_l1 = length > 0.0 ? e.fan_l1 / length / h0 : 0.0;
  e.fan_l2 = length > 0.0 ? std::sqrt(e.fan_l2 / length) / h0 : 0.0;
  e.fan_linf /= h0;
  e.upstream_fan_l1 = upstream_length > 0.0 ? e.upstream_fan_l1 / upstream_length / h0 : 0.0;
  return e;
}

}  // namespace swemps::verification

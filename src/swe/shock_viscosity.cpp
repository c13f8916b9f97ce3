#include "swemps/swe/shock_viscosity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

namespace {
// eps of mu_ij: keeps the term finite for pairs that nearly coincide.
constexpr double kSingularity = 0.01;
}  // namespace

ShockViscosity::ShockViscosity(double alpha) : alpha_(alpha) {
  if (!(alpha > 0.0) || !std::isfinite(alpha))
    throw std::invalid_argument("shock viscosity must be a finite number > 0");
}

void ShockViscosity::apply(StepContext& context) {
  const auto& p = context.particles;
  const auto& nl = context.neighbors;
  const auto& w = context.kernel;
  const double g = context.settings.gravity_m_s2;
  const std::size_t n = p.fluid_count();
  rate_.assign(n, 0.0);
  power_.assign(n, 0.0);
  // Wave speeds once per particle (ghosts included), not once per pair.
  celerity_.resize(p.size());
  parallel_for(p.size(), [&](std::size_t i) { celerity_[i] = std::sqrt(g * p.depth[i]); });
  parallel_for(n, [&](std::size_t i) {
    const double ci = celerity_[i];
    double ax = 0.0, ay = 0.0, rate = 0.0;
    for (std::uint32_t j : nl.row(i)) {
      const double dx = p.x[i] - p.x[j];
      const double dy = p.y[i] - p.y[j];
      const double du = p.u[i] - p.u[j];
      const double dv = p.v[i] - p.v[j];
      const double approach = du * dx + dv * dy;
      if (!(approach < 0.0)) continue;  // separating or at rest: no viscosity
      const double r2 = dx * dx + dy * dy;
      const double r = std::sqrt(r2);
      if (r == 0.0) continue;  // no direction to act along
      const double c_mean = 0.5 * (ci + celerity_[j]);
      const double h_mean = 0.5 * (p.depth[i] + p.depth[j]);
      // r_e of the pair (the mean of both radii), and eps r_e^2 of mu_ij.
      const double radius = 0.5 * (p.smoothing_length[i] + p.smoothing_length[j]);
      const double softening = kSingularity * radius * radius;
      const double mu = radius * approach / (r2 + softening);
      const double pi = -alpha_ * c_mean * mu / h_mean;  // > 0
      // V_j Pi_ij w'(r) / r: w' < 0, so the pair pushes i back along x_i - x_j, against
      // the approach.
      const double slope = -w.pair_dw_dr(p, i, j, r);  // > 0
      const double scale = p.volume[j] * pi * slope / r;
      ax += scale * dx;
      ay += scale * dy;
      // d a_i / d u_i along the pair: the damping rate this pair adds.
      rate += p.volume[j] * alpha_ * c_mean * radius * slope * r / ((r2 + softening) * h_mean);
    }
    context.accel_x[i] += ax;
    context.accel_y[i] += ay;
    rate_[i] = rate;
    // V_i u_i . a_i: this particle's share of the energy rate (negative).
    power_[i] = p.volume[i] * (p.u[i] * ax + p.v[i] * ay);
  });
  largest_damping_rate_ = n > 0 ? *std::max_element(rate_.begin(), rate_.end()) : 0.0;
  double power = 0.0;
  for (const double q : power_) power += q;
  dissipated_ -= power * context.dt_s;
}

double ShockViscosity::time_step_limit(const Settings& /*settings*/, double /*time_s*/) const {
  if (!(largest_damping_rate_ > 0.0)) return std::numeric_limits<double>::infinity();
  return 1.0 / largest_damping_rate_;
}

std::string ShockViscosity::report() const {
  std::ostringstream s;
  s << "alpha " << alpha_ << ", dissipated " << dissipated_ << " m^5/s^2 (times the density: J)";
  return s.str();
}

// The last apply()'s damping rate limits the next step, and the dissipated total is reported:
// a restored run must take the same steps and report the same total.
void ShockViscosity::save_state(StateWriter& out) const {
  out.number(largest_damping_rate_);
  out.number(dissipated_);
}

void ShockViscosity::restore_state(StateReader& in) {
  largest_damping_rate_ = in.number();
  dissipated_ = in.number();
}

}  // namespace swemps::swe

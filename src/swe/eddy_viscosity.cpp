#include "swemps/swe/eddy_viscosity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

namespace {
constexpr double kDimension = 2.0;      // D
constexpr double kCoincident2 = 1e-24;  // m^2: pairs closer than 1e-12 m are skipped
}  // namespace

EddyViscosity::EddyViscosity(double viscosity_m2_s) : viscosity_(viscosity_m2_s) {
  if (!(viscosity_m2_s > 0.0) || !std::isfinite(viscosity_m2_s))
    throw std::invalid_argument("eddy viscosity must be a finite number > 0 m^2/s");
}

void EddyViscosity::apply(StepContext& context) {
  auto& p = context.particles;
  const auto& nl = context.neighbors;
  const auto& w = context.kernel;
  const std::size_t n = p.fluid_count();
  std::vector<double> lambda(n, std::numeric_limits<double>::infinity());
  parallel_for(n, [&](std::size_t i) {
    double weight = 0.0, moment = 0.0, lap_u = 0.0, lap_v = 0.0;
    for (std::uint32_t j : nl.row(i)) {
      const double dx = p.x[j] - p.x[i];
      const double dy = p.y[j] - p.y[i];
      const double r2 = dx * dx + dy * dy;
      if (r2 < kCoincident2) continue;
      const double aw = p.area[j] / p.area[i] * w.pair_w(p, i, j, std::sqrt(r2));
      weight += aw;
      moment += aw * r2;
      lap_u += aw * (p.u[j] - p.u[i]);
      lap_v += aw * (p.v[j] - p.v[i]);
    }
    if (!(weight > 0.0) || !(moment > 0.0)) return;  // isolated: nothing to mix with
    lambda[i] = moment / weight;
    // 2 D / (lambda n) sum (...) with lambda n = moment: the number density cancels.
    const double factor = viscosity_ * 2.0 * kDimension / moment;
    context.accel_x[i] += factor * lap_u;
    context.accel_y[i] += factor * lap_v;
  });
  smallest_lambda_m2_ = n > 0 ? *std::min_element(lambda.begin(), lambda.end()) : 0.0;
}

double EddyViscosity::time_step_limit(const Settings& /*settings*/, double /*time_s*/) const {
  if (!(smallest_lambda_m2_ > 0.0) || !std::isfinite(smallest_lambda_m2_))
    return std::numeric_limits<double>::infinity();
  return smallest_lambda_m2_ / (4.0 * kDimension * viscosity_);
}

// The last apply()'s smallest lambda limits the next step: without it a restored run would
// take a different first step.
void EddyViscosity::save_state(StateWriter& out) const { out.number(smallest_lambda_m2_); }

void EddyViscosity::restore_state(StateReader& in) { smallest_lambda_m2_ = in.number(); }

}  // namespace swemps::swe

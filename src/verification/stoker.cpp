#include "swemps/verification/stoker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swemps::verification {

StokerState stoker_state(const StokerProblem& p) {
  const double g = p.gravity_m_s2, hl = p.upstream_depth_m, hr = p.downstream_depth_m;
  if (!(hr > 0.0) || !(hl > hr)) throw std::invalid_argument("stoker: need 0 < h_r < h_l");
  // Left side minus right side of the equation for h_m: decreasing in h_m, positive at h_r and
  // negative at h_l, so bisection finds the one root.
  const auto mismatch = [&](double hm) {
    return 2.0 * (std::sqrt(g * hl) - std::sqrt(g * hm)) -
           (hm - hr) * std::sqrt(g * (hm + hr) / (2.0 * hm * hr));
  };
  double low = hr, high = hl;
  for (int k = 0; k < 200 && high - low > 1e-15 * hl; ++k) {
    const double mid = 0.5 * (low + high);
    (mismatch(mid) > 0.0 ? low : high) = mid;
  }
  StokerState s;
  s.middle_depth_m = 0.5 * (low + high);
  s.middle_velocity_m_s = 2.0 * (std::sqrt(g * hl) - std::sqrt(g * s.middle_depth_m));
  s.shock_speed_m_s = s.middle_depth_m * s.middle_velocity_m_s / (s.middle_depth_m - hr);
  return s;
}

namespace {

struct Regions {
  double head, tail, shock;  // x of the rarefaction's head and tail, and of the shock
};

Regions regions(const StokerProblem& p, const StokerState& s, double t) {
  const double cl = std::sqrt(p.gravity_m_s2 * p.upstream_depth_m);
  const double cm = std::sqrt(p.gravity_m_s2 * s.middle_depth_m);
  return {p.dam_x_m - cl * t, p.dam_x_m + (s.middle_velocity_m_s - cm) * t,
          p.dam_x_m + s.shock_speed_m_s * t};
}

}  // namespace

double stoker_depth(const StokerProblem& p, double x, double t) {
  const auto s = stoker_state(p);
  const auto r = regions(p, s, t);
  if (x <= r.head) return p.upstream_depth_m;
  if (x <= r.tail) {  // the rarefaction fan, as Ritter's (eq 14)
    const double c = 2.0 * std::sqrt(p.gravity_m_s2 * p.upstream_depth_m) - (x - p.dam_x_m) / t;
    return c * c / (9.0 * p.gravity_m_s2);
  }
  if (x <= r.shock) return s.middle_depth_m;
  return p.downstream_depth_m;
}

double stoker_velocity(const StokerProblem& p, double x, double t) {
  const auto s = stoker_state(p);
  const auto r = regions(p, s, t);
  if (x <= r.head || x > r.shock) return 0.0;
  if (x <= r.tail)
    return 2.0 / 3.0 * ((x - p.dam_x_m) / t + std::sqrt(p.gravity_m_s2 * p.upstream_depth_m));
  return s.middle_velocity_m_s;
}

StokerErrors compare_with_stoker(const StokerProblem& p, const Profile& profile, double t) {
  const auto s = stoker_state(p);
  const auto r = regions(p, s, t);
  StokerErrors e{0.0, 0.0, 0.0, profile.x0_m, r.shock};
  const double end = r.shock + profile.dx_m;
  const double plateau_margin = 0.1 * (r.shock - r.tail);
  const double half_jump = 0.5 * (s.middle_depth_m + p.downstream_depth_m);
  double length = 0.0, plateau_max = 0.0;
  bool shock_found = false;
  for (std::size_t k = 0; k < profile.depth_m.size(); ++k) {
    const double x = profile.x0_m + static_cast<double>(k) * profile.dx_m;
    const double h = profile.depth_m[k];
    if (!shock_found && x > p.dam_x_m && h < half_jump) {
      e.shock_x_m = x;
      shock_found = true;
    }
    if (x > r.tail + plateau_margin && x < r.shock - plateau_margin)
      plateau_max = std::max(plateau_max, h);
    if (x < r.head || x > end) continue;
    const double diff = std::abs(h - stoker_depth(p, x, t));
    e.l1 += diff * profile.dx_m;
    e.linf = std::max(e.linf, diff);
    length += profile.dx_m;
  }
  e.l1 = length > 0.0 ? e.l1 / length / p.upstream_depth_m : 0.0;
  e.linf /= p.upstream_depth_m;
  e.plateau_overshoot = plateau_max / s.middle_depth_m - 1.0;
  return e;
}

}  // namespace swemps::verification

#pragma once
// The hyperbolic MPS weight of Kakuda et al. (seed eq 9), method.md section 2:
//
//   w(r) = theta (sech^2(kappa r / r_e) - sech^2(kappa)) / (1 - sech^2(kappa))   for r < r_e,
//
// 0 otherwise. A bell that is flat at the origin, where the standard and logarithmic weights
// blow up: close pairs no longer dominate the sums, which is what removes the spurious
// pressure oscillations Kakuda et al. set out to cure. kappa sets the shape (larger: narrower
// bell, closer to a delta); they use kappa = 2 or 3 for viscosity and 4 for pressure, with
// r_e = 4 l0. theta is w(0); MPS operators divide by n0, so theta cancels there.
// The slope does not vanish at r_e, so w has a kink at the support (like the standard weight).

#include <cmath>
#include <stdexcept>

namespace swemps::kernels {

// sech^2(x) = 4 e^(-2|x|) / (1 + e^(-2|x|))^2: no overflow for any x, unlike 1 / cosh(x)^2
// once cosh overflows (|x| > 710), and accurate where sech^2 is tiny.
inline double sech_squared(double x) {
  const double decay = std::exp(-2.0 * std::abs(x));
  const double one_plus = 1.0 + decay;
  return 4.0 * decay / (one_plus * one_plus);
}

class HyperbolicMps {
 public:
  static constexpr bool singular_at_origin = false;

  HyperbolicMps(double influence_radius, double kappa, double theta = 1.0)
      : influence_radius_(influence_radius), kappa_(kappa), theta_(theta) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("hyperbolic kernel: influence radius must be finite and > 0");
    }
    if (!(kappa > 0.0) || !std::isfinite(kappa)) {
      throw std::invalid_argument("hyperbolic kernel: kappa must be finite and > 0");
    }
    if (!(theta > 0.0) || !std::isfinite(theta)) {
      throw std::invalid_argument("hyperbolic kernel: theta must be finite and > 0");
    }
    // 1 - sech^2(kappa) = tanh^2(kappa), without the cancellation for small kappa.
    const double tanh_kappa = std::tanh(kappa);
    scale_ = theta / (tanh_kappa * tanh_kappa);
    floor_ = sech_squared(kappa);
  }

  double influence_radius() const { return influence_radius_; }
  double kappa() const { return kappa_; }
  double theta() const { return theta_; }
  // Distance beyond which w = 0: the influence radius itself (eq 9).
  double support() const { return influence_radius_; }

  double w(double r) const {
    if (!(r < influence_radius_)) return 0.0;
    return scale_ * (sech_squared(kappa_ * r / influence_radius_) - floor_);
  }

  // d/dx sech^2(x) = -2 sech^2(x) tanh(x): zero at the origin, and -4 kappa theta /
  // (r_e sinh(2 kappa)) just inside r_e, where the weight stops with a kink.
  double dw_dr(double r) const {
    if (!(r < influence_radius_)) return 0.0;
    const double x = kappa_ * r / influence_radius_;
    return -2.0 * scale_ * sech_squared(x) * std::tanh(x) * kappa_ / influence_radius_;
  }

 private:
  double influence_radius_;
  double kappa_;
  double theta_;
  double scale_ = 0.0;  // theta / tanh^2(kappa)
  double floor_ = 0.0;  // sech^2(kappa): the bell's value at r_e, subtracted to reach zero there
};

}  // namespace swemps::kernels

#pragma once
// The hyperbolic SPH kernel of Kakuda et al. (seed eqs 19-22), method.md section 2. With
// R = r / r_e and support 2 r_e:
//
//   W(r) = (a1 kappa / (2 r_e)) (sech^2(kappa R) - sech^2(2 kappa))   for R < 2,   0 otherwise,
//
// the hyperbolic MPS bell (eq 9) stretched to twice the radius and scaled so that it
// integrates to one in Dim dimensions, like the spiky kernel (eq 8). a1 depends on Dim:
//
//   1D: a1 = 1 / (tanh(2k) - 2k sech^2(2k))                                         (eq 18)
//   2D: a1 = 1 / (pi r_e [(1/k)(2k tanh(2k) - ln cosh(2k)) - 2k sech^2(2k)])        (eq 20)
//   3D: a1 = 1 / (2 pi r_e^2 [L / k^2 - (8k/3) sech^2(2k)]),                        (eq 21)
//       L = 4k^2 (tanh(2k) - 1) - 4k ln(exp(-4k) + 1) + Li2(-exp(-4k)) + pi^2/12     (eq 22)
//
// (k = kappa). L is the integral of u^2 sech^2(u) over 0 <= u <= 2k. These closed forms are
// used for kappa >= 0.05 and a power series below, where they cancel; the property tests check
// every Dim against quadrature for kappa from 0.001 to 16.

#include <cmath>
#include <stdexcept>

#include "swemps/kernels/hyperbolic_mps.hpp"

namespace swemps::kernels {

// The dilogarithm Li2(x) = -integral_0^x ln(1 - t) / t dt = sum_{n >= 1} x^n / n^2, for real
// x <= 1 (NaN above 1, where it is complex). Eq 22 needs it at -exp(-4 kappa).
double dilogarithm(double x);

// a1 of eqs 18, 20 and 21 for `dim` = 1, 2 or 3 (throws std::invalid_argument otherwise).
double hyperbolic_sph_a1(int dim, double influence_radius, double kappa);

template <int Dim>
class HyperbolicSph {
  static_assert(Dim >= 1 && Dim <= 3, "hyperbolic SPH kernel defined for 1, 2 and 3 dimensions");

 public:
  static constexpr bool singular_at_origin = false;

  HyperbolicSph(double influence_radius, double kappa)
      : influence_radius_(influence_radius), kappa_(kappa) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("hyperbolic SPH kernel: influence radius must be finite and > 0");
    }
    if (!(kappa > 0.0) || !std::isfinite(kappa)) {
      throw std::invalid_argument("hyperbolic SPH kernel: kappa must be finite and > 0");
    }
    amplitude_ = hyperbolic_sph_a1(Dim, influence_radius, kappa) * kappa / (2.0 * influence_radius);
    floor_ = sech_squared(2.0 * kappa);
  }

  double influence_radius() const { return influence_radius_; }
  double kappa() const { return kappa_; }
  // Distance beyond which W = 0 (eq 19: R < 2).
  double support() const { return 2.0 * influence_radius_; }

  double w(double r) const {
    if (!(r < 2.0 * influence_radius_)) return 0.0;
    return amplitude_ * (sech_squared(kappa_ * r / influence_radius_) - floor_);
  }

  // Zero at the origin; non-zero just inside 2 r_e, where W stops with a kink.
  double dw_dr(double r) const {
    if (!(r < 2.0 * influence_radius_)) return 0.0;
    const double x = kappa_ * r / influence_radius_;
    return -2.0 * amplitude_ * sech_squared(x) * std::tanh(x) * kappa_ / influence_radius_;
  }

 private:
  double influence_radius_;
  double kappa_;
  double amplitude_ = 0.0;  // a1 kappa / (2 r_e)
  double floor_ = 0.0;      // sech^2(2 kappa): the bell's value at the support
};

}  // namespace swemps::kernels

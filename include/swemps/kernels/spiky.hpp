#pragma once
// The spiky kernel (eq 8) used by the shallow-water solver for the depth summation (eq 7)
// and its gradient. Support 2 r_e. Normalised to 1 in Dim dimensions: the shallow-water
// mode uses Dim = 2; 1 and 3 are here for the Navier-Stokes mode and for tests.

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "swemps/kernels/scaled_kernel.hpp"

namespace swemps::kernels {

template <int Dim>
class Spiky : public ScaledKernel<Spiky<Dim>, Dim> {
  static_assert(Dim >= 1 && Dim <= 3, "spiky kernel defined for 1, 2 and 3 dimensions");

 public:
  static constexpr bool singular_at_origin = false;

  explicit Spiky(double influence_radius)
      : influence_radius_(influence_radius),
        inverse_radius_(1.0 / influence_radius),
        support_(2.0 * influence_radius) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("spiky kernel: influence radius must be finite and > 0");
    }
    // (2 - q)^3 integrated over |q| < 2 in Dim dimensions, times r_e^Dim, must give 1.
    // 1D: 2 * 2^4/4 = 8;  2D: 2 pi * 2^5/20 = 16 pi / 5 (eq 8);  3D: 4 pi * 2^6/60 = 64 pi / 15.
    const double r_e = influence_radius;
    if constexpr (Dim == 1) {
      normalisation_ = 1.0 / (8.0 * r_e);
    } else if constexpr (Dim == 2) {
      normalisation_ = 5.0 / (16.0 * std::numbers::pi * r_e * r_e);
    } else {
      normalisation_ = 15.0 / (64.0 * std::numbers::pi * r_e * r_e * r_e);
    }
  }

  static constexpr double support_ratio = 2.0;  // support / r_e

  // eq 8 in the form f(q) sigma_D / r_e^D with q = r / r_e, for a radius given per call
  // (ScaledKernel; the conservative scheme's per-particle radius): f(q) = (2 - q)^3.
  static constexpr double sigma() {
    if constexpr (Dim == 1) return 1.0 / 8.0;
    if constexpr (Dim == 2) return 5.0 / (16.0 * std::numbers::pi);
    return 15.0 / (64.0 * std::numbers::pi);
  }
  static double shape(double q) {
    const double a = q < 2.0 ? 2.0 - q : 0.0;
    return a * a * a;
  }
  static double shape_slope(double q) {
    const double a = q < 2.0 ? 2.0 - q : 0.0;
    return -3.0 * a * a;
  }
  using ScaledKernel<Spiky<Dim>, Dim>::w;
  using ScaledKernel<Spiky<Dim>, Dim>::dw_dr;

  double influence_radius() const { return influence_radius_; }
  // Distance beyond which w = 0.
  double support() const { return support_; }

  // eq 8: w(r) = c (2 - r/r_e)^3 for r <= 2 r_e.
  double w(double r) const {
    // (2 r_e - r) / r_e as a product, not a division: w is evaluated for every pair of every
    // sum, and a division costs several multiplications. The difference is taken first so that
    // s is exactly 0 at r = 2 r_e and negative beyond.
    // Clamped, then cubed: a select of values rather than a branch, so loops over pairs
    // vectorise.
    const double s = (support_ - r) * inverse_radius_;
    const double t = s > 0.0 ? s : 0.0;
    return normalisation_ * t * t * t;
  }

  // dw/dr = -3 c (2 - r/r_e)^2 / r_e; finite (non-zero) at r = 0, which is why the spiky
  // kernel was chosen for gradients: close particles still push each other apart.
  double dw_dr(double r) const {
    const double s = (support_ - r) * inverse_radius_;
    const double t = s > 0.0 ? s : 0.0;
    return -3.0 * normalisation_ * inverse_radius_ * t * t;
  }

 private:
  double influence_radius_;
  double inverse_radius_;
  double support_;
  double normalisation_ = 0.0;
};

}  // namespace swemps::kernels

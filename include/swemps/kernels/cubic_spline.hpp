#pragma once
// The cubic B-spline kernel (Monaghan & Lattanzio 1985), the usual SPH kernel. With
// q = r / h and support 2 h:
//
//   W(r, h) = sigma_D / h^D f(q),   f(q) = (2 - q)^3 / 4 - (1 - q)^3 for q < 1,
//                                        = (2 - q)^3 / 4           for 1 <= q < 2,   0 beyond,
//   sigma_1 = 2/3,  sigma_2 = 10 / (7 pi),  sigma_3 = 1 / pi.
//
// The shallow-water kernel of the conservative scheme: on square and hexagonal lattices its
// discrete sum is within 0.4 % of 1 for h = 1.2-1.3 spacings, at particles and between them,
// where the spiky kernel is 12-15 % off (docs/kernels.md, "Shallow water"). The static forms
// take the radius per call, for particles that each have their own.

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "swemps/kernels/scaled_kernel.hpp"

namespace swemps::kernels {

template <int Dim>
class CubicSpline : public ScaledKernel<CubicSpline<Dim>, Dim> {
  static_assert(Dim >= 1 && Dim <= 3, "cubic spline kernel defined for 1, 2 and 3 dimensions");

 public:
  static constexpr bool singular_at_origin = false;
  static constexpr double support_ratio = 2.0;  // support / h

  static constexpr double sigma() {
    if constexpr (Dim == 1) return 2.0 / 3.0;
    if constexpr (Dim == 2) return 10.0 / (7.0 * std::numbers::pi);
    return 1.0 / std::numbers::pi;
  }
  // f(q) and f'(q) without branches: max(2 - q, 0) and max(1 - q, 0) select the pieces.
  static double shape(double q) {
    const double a = q < 2.0 ? 2.0 - q : 0.0;
    const double b = q < 1.0 ? 1.0 - q : 0.0;
    return 0.25 * a * a * a - b * b * b;
  }
  static double shape_slope(double q) {
    const double a = q < 2.0 ? 2.0 - q : 0.0;
    const double b = q < 1.0 ? 1.0 - q : 0.0;
    return -0.75 * a * a + 3.0 * b * b;
  }

  explicit CubicSpline(double influence_radius) : h_(influence_radius) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("cubic spline kernel: influence radius must be finite and > 0");
    }
  }
  double influence_radius() const { return h_; }
  double support() const { return support_ratio * h_; }
  using ScaledKernel<CubicSpline<Dim>, Dim>::w;
  using ScaledKernel<CubicSpline<Dim>, Dim>::dw_dr;
  double w(double r) const { return w(r, h_); }
  double dw_dr(double r) const { return dw_dr(r, h_); }

 private:
  double h_;
};

}  // namespace swemps::kernels

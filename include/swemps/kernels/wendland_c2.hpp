#pragma once
// The Wendland C2 kernel (Wendland 1995; Dehnen & Aly 2012), in 2D and 3D. With q = r / h
// and support 2 h:
//
//   W(r, h) = sigma_D / h^D (1 - q/2)^4 (2 q + 1)   for q < 2,  0 beyond,
//   sigma_2 = 7 / (4 pi),  sigma_3 = 21 / (16 pi).
//
// Its Fourier transform is positive, so particles at rest never pair up (Dehnen & Aly); its
// lattice sum converges more slowly than the cubic spline's (docs/kernels.md, "Shallow water").

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "swemps/kernels/scaled_kernel.hpp"

namespace swemps::kernels {

template <int Dim>
class WendlandC2 : public ScaledKernel<WendlandC2<Dim>, Dim> {
  static_assert(Dim == 2 || Dim == 3, "Wendland C2 kernel defined here for 2 and 3 dimensions");

 public:
  static constexpr bool singular_at_origin = false;
  static constexpr double support_ratio = 2.0;

  static constexpr double sigma() {
    if constexpr (Dim == 2) return 7.0 / (4.0 * std::numbers::pi);
    return 21.0 / (16.0 * std::numbers::pi);
  }
  static double shape(double q) {
    const double a = q < 2.0 ? 1.0 - 0.5 * q : 0.0;
    const double a2 = a * a;
    return a2 * a2 * (2.0 * q + 1.0);
  }
  // f'(q) = -5 q (1 - q/2)^3.
  static double shape_slope(double q) {
    const double a = q < 2.0 ? 1.0 - 0.5 * q : 0.0;
    return -5.0 * q * a * a * a;
  }

  explicit WendlandC2(double influence_radius) : h_(influence_radius) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("Wendland C2 kernel: influence radius must be finite and > 0");
    }
  }
  double influence_radius() const { return h_; }
  double support() const { return support_ratio * h_; }
  using ScaledKernel<WendlandC2<Dim>, Dim>::w;
  using ScaledKernel<WendlandC2<Dim>, Dim>::dw_dr;
  double w(double r) const { return w(r, h_); }
  double dw_dr(double r) const { return dw_dr(r, h_); }

 private:
  double h_;
};

}  // namespace swemps::kernels

#pragma once
// A radial kernel W(r, h) = sigma_D / h^D f(r / h) evaluated at a radius given per call, for
// particles that each have their own (the conservative shallow-water scheme). A kernel class
// derives from ScaledKernel<Itself, Dim> and supplies sigma(), shape(q) = f(q) and
// shape_slope(q) = f'(q); this gives it W, dW/dr and dW/dh:
//
//   dW/dr = sigma_D / h^(D+1) f'(q),   dW/dh = -(sigma_D / h^(D+1)) (D f(q) + q f'(q)).

namespace swemps::kernels {

template <class Kernel, int Dim>
struct ScaledKernel {
  static double w(double r, double h) { return Kernel::sigma() / power(h) * Kernel::shape(r / h); }
  static double dw_dr(double r, double h) {
    return Kernel::sigma() / (power(h) * h) * Kernel::shape_slope(r / h);
  }
  static double dw_dh(double r, double h) {
    const double q = r / h;
    return -Kernel::sigma() / (power(h) * h) * (Dim * Kernel::shape(q) + q * Kernel::shape_slope(q));
  }
  static double power(double h) {
    if constexpr (Dim == 1) return h;
    if constexpr (Dim == 2) return h * h;
    return h * h * h;
  }
};

}  // namespace swemps::kernels

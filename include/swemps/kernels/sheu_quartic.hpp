#pragma once
// The quartic MPS weight of Sheu et al. (2011, eq 4.8), method.md section 2. In q = r / r_e:
//
//   w(r) = (1 / r_e) (a + c q^2 + d q^3 + e q^4)   for q < 1,   0 otherwise.
//
// The five polynomial coefficients (b = 0) follow from w(r_e) = 0, w'(r_e) = 0, w'(0) = 0,
// a 1D integral of one (integral_0^1 of the polynomial dq = 1/2) and w(sqrt2 l0) = w(l0) / 4
// at r_e = 2 l0, which cancels the leading error term of the nine-point Laplacian on a square
// lattice. The paper prints e as 480(sqrt2 - 600)/D0; method.md corrects it to
// (480 sqrt2 - 600)/D0, the value that satisfies the five conditions.
//
// Two facts the paper does not state, both following from the conditions: the polynomial is
// (1 - q)^2 (a + 2a q + e q^2), and that quadratic factor changes sign at
// q* = (a + sqrt(a^2 - a e)) / (-e) = 0.99724, so w dips below zero on q* < q < 1 (at most
// -1.6e-8 / r_e, 1.2e-8 of w(0)). The kernel keeps the paper's formula; the dip is far below
// anything an MPS sum resolves, and the property tests pin its size.

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace swemps::kernels {

class SheuQuartic {
 public:
  static constexpr bool singular_at_origin = false;

  // The paper's coefficients have D0 = 512 sqrt2 - 745 = -20.9 in the denominator, which
  // cancels 1.5 digits; multiplying through by 512 sqrt2 + 745 gives D0 (512 sqrt2 + 745) =
  // 2 * 512^2 - 745^2 = -30737 and numerators without cancellation. Same values as
  // method.md section 2 (the tests compare both forms).
  static constexpr double a = (33705.0 + 3360.0 * std::numbers::sqrt2) / 30737.0;
  static constexpr double c = -(145635.0 + 60480.0 * std::numbers::sqrt2) / 30737.0;
  static constexpr double d = (156450.0 + 107520.0 * std::numbers::sqrt2) / 30737.0;
  static constexpr double e = -(44520.0 + 50400.0 * std::numbers::sqrt2) / 30737.0;

  explicit SheuQuartic(double influence_radius) : influence_radius_(influence_radius) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("Sheu quartic kernel: influence radius must be finite and > 0");
    }
  }

  double influence_radius() const { return influence_radius_; }
  // Distance beyond which w = 0: the influence radius itself (eq 4.8).
  double support() const { return influence_radius_; }

  // eq 4.8 in Horner form.
  double w(double r) const {
    const double q = r / influence_radius_;
    if (!(q < 1.0)) return 0.0;
    return (a + q * q * (c + q * (d + q * e))) / influence_radius_;
  }

  // Zero at the origin (b = 0) and at r_e: the weight is flat at both ends.
  double dw_dr(double r) const {
    const double q = r / influence_radius_;
    if (!(q < 1.0)) return 0.0;
    return q * (2.0 * c + q * (3.0 * d + q * 4.0 * e)) / (influence_radius_ * influence_radius_);
  }

 private:
  double influence_radius_;
};

}  // namespace swemps::kernels

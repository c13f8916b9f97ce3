#pragma once
// The logarithmic MPS weight of Kakuda et al. (seed eq 8), method.md section 2:
//
//   w(r) = ln(r_e / r)   for 0 < r < r_e,   0 otherwise.
//
// Like the standard weight it is singular at the origin (w(0) = +inf, dw_dr(0) = -inf), but
// only logarithmically, so close pairs weigh much less than with r_e / r - 1; Kakuda et al.
// report smoother pressure with it and use it as the stepping stone to the hyperbolic weight.

#include <cmath>
#include <stdexcept>

namespace swemps::kernels {

class Logarithmic {
 public:
  static constexpr bool singular_at_origin = true;

  explicit Logarithmic(double influence_radius) : influence_radius_(influence_radius) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("logarithmic kernel: influence radius must be finite and > 0");
    }
  }

  double influence_radius() const { return influence_radius_; }
  // Distance beyond which w = 0: the influence radius itself.
  double support() const { return influence_radius_; }

  double w(double r) const { return r < influence_radius_ ? std::log(influence_radius_ / r) : 0.0; }

  double dw_dr(double r) const { return r < influence_radius_ ? -1.0 / r : 0.0; }

 private:
  double influence_radius_;
};

}  // namespace swemps::kernels

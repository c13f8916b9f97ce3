#pragma once
// The standard MPS weight of Koshizuka & Oka (1996), method.md section 2:
//
//   w(r) = r_e / r - 1   for 0 < r < r_e,   0 otherwise.
//
// Not normalised: MPS divides every sum by the lattice's own number density n0, so only the
// shape matters. The weight grows without bound as r -> 0, which keeps particles apart but
// also makes the pressure noisy when two particles come close (the reason Kakuda et al.
// replace it); w(0) = +inf and dw_dr(0) = -inf, and callers never evaluate the self pair.

#include <cmath>
#include <stdexcept>

namespace swemps::kernels {

class StandardMps {
 public:
  static constexpr bool singular_at_origin = true;

  explicit StandardMps(double influence_radius) : influence_radius_(influence_radius) {
    if (!(influence_radius > 0.0) || !std::isfinite(influence_radius)) {
      throw std::invalid_argument("standard MPS kernel: influence radius must be finite and > 0");
    }
  }

  double influence_radius() const { return influence_radius_; }
  // Distance beyond which w = 0: the influence radius itself.
  double support() const { return influence_radius_; }

  double w(double r) const { return r < influence_radius_ ? influence_radius_ / r - 1.0 : 0.0; }

  double dw_dr(double r) const {
    return r < influence_radius_ ? -influence_radius_ / (r * r) : 0.0;
  }

 private:
  double influence_radius_;
};

}  // namespace swemps::kernels

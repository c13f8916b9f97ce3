#pragma once
// The kernel of a shallow-water scheme as the rest of the solver sees it: one shape (from the
// kernel module) and a radius per particle, read from SweParticles::smoothing_length. Effects
// (splitting, viscosities, bed slope) and output weigh pairs and points through it, so that
// they work the same under every scheme: under the seed scheme every particle has the one
// radius of eq 9, under the conservative scheme each its own.

#include <cstddef>
#include <string_view>

#include "swemps/kernels/cubic_spline.hpp"
#include "swemps/kernels/spiky.hpp"
#include "swemps/kernels/wendland_c2.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/settings.hpp"

namespace swemps::swe {

// Scene names: "cubic-spline", "spiky", "wendland-c2".
std::string_view kernel_shape_name(KernelShape shape);

// Calls f(kernel) with the kernel-module type of `shape` (a 2D kernel class with static
// w(r, h), dw_dr(r, h) and dw_dh(r, h)), so that a loop can be compiled for each shape and
// the choice made once, outside it.
template <class F>
decltype(auto) with_kernel_shape(KernelShape shape, F&& f) {
  switch (shape) {
    case KernelShape::spiky: return f(kernels::Spiky<2>(1.0));
    case KernelShape::wendland_c2: return f(kernels::WendlandC2<2>(1.0));
    case KernelShape::cubic_spline: break;
  }
  return f(kernels::CubicSpline<2>(1.0));
}

class ParticleKernel {
 public:
  explicit ParticleKernel(KernelShape shape) : shape_(shape) {}

  KernelShape shape() const { return shape_; }
  // Every kernel of the module that is offered here reaches 2 h.
  static constexpr double support(double h) { return 2.0 * h; }

  double w(double r, double h) const {
    return with_kernel_shape(shape_, [&](const auto& k) { return k.w(r, h); });
  }
  double dw_dr(double r, double h) const {
    return with_kernel_shape(shape_, [&](const auto& k) { return k.dw_dr(r, h); });
  }

  // The weight of the pair (i, j) at distance r: the mean of both particles' kernels, so that
  // w_ij = w_ji and a pair acts on both alike. With one radius for all it is w(r) itself.
  double pair_w(const particles::SweParticles& p, std::size_t i, std::size_t j, double r) const {
    const double hi = p.smoothing_length[i], hj = p.smoothing_length[j];
    return hi == hj ? w(r, hi) : 0.5 * (w(r, hi) + w(r, hj));
  }
  double pair_dw_dr(const particles::SweParticles& p, std::size_t i, std::size_t j,
                    double r) const {
    const double hi = p.smoothing_length[i], hj = p.smoothing_length[j];
    return hi == hj ? dw_dr(r, hi) : 0.5 * (dw_dr(r, hi) + dw_dr(r, hj));
  }
  // The pair's reach: the larger of the two supports.
  double pair_support(const particles::SweParticles& p, std::size_t i, std::size_t j) const {
    const double hi = p.smoothing_length[i], hj = p.smoothing_length[j];
    return support(hi > hj ? hi : hj);
  }

 private:
  KernelShape shape_;
};

}  // namespace swemps::swe

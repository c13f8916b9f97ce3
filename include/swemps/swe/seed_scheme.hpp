#pragma once
// The seed paper's scheme (method.md section 1, eqs 5-9): depth by eq 7 with the spiky kernel
// and one influence radius for all particles (eq 9, with the guards of docs/method.md), the
// flow driven by eq 6 or by the exact gradient of eq 7 (Settings::gradient). Kept as
// `numerics.scheme: "seed"` so that the paper's results can still be reproduced.

#include "swemps/swe/operators.hpp"
#include "swemps/swe/scheme.hpp"

namespace swemps::swe {

class SeedScheme final : public Scheme {
 public:
  explicit SeedScheme(const Settings& settings);

  std::string_view name() const override { return "seed"; }
  const ParticleKernel& kernel() const override { return particle_kernel_; }
  // eq 9 from the areas of the last summation: every particle gets the one radius.
  void choose_smoothing_lengths(particles::SweParticles& p) override;
  double search_radius(double h) const override { return ParticleKernel::support(h); }
  bool uniform_radius() const override { return true; }
  bool sum_depth(particles::SweParticles& p, const neighbors::NeighborList& nl) override;
  void surface_acceleration(particles::SweParticles& p, const neighbors::NeighborList& nl,
                            double gravity_m_s2, std::span<double> accel_x,
                            std::span<double> accel_y) override;

 private:
  Settings settings_;
  ParticleKernel particle_kernel_{KernelShape::spiky};
};

}  // namespace swemps::swe

#pragma once
// The conservative shallow-water scheme (docs/method.md, "The conservative scheme"), after
// the variable-smoothing-length SPH shallow-water formulation (Rodriguez-Paz & Bonet 2005;
// Vacondio, Rogers, Stansby & Mignosa 2012).
//
// Depth. Each particle has its own radius h_i = kappa sqrt(A_i), A_i = V_i / d_i, and its
// depth is the kernel sum at that radius, self term included:
//
//   d_i = sum_j V_j W(|x_i - x_j|, h_i),   h_i = kappa sqrt(V_i / d_i).
//
// The two depend on each other, so d_i is found by Newton's method on
// f(d) = d - sum_j V_j W(r_ij, h(d)), whose derivative is the grad-h factor
//
//   Omega_i = 1 + (h_i / (2 d_i)) sum_j V_j dW/dh(r_ij, h_i)     (dh/dd = -h / (2 d) in 2D).
//
// h_i is capped at kappa sqrt(max_area_ratio A_0,i) (Settings::max_area_ratio): without a cap
// an isolated particle has no solution (d -> 0, h -> infinity); while capped, Omega_i = 1.
//
// Force. The Lagrangian L = sum_i V_i (|u_i|^2 / 2 - g d_i / 2) with the summed depths gives
//
//   du_i/dt = -(g/2) sum_j V_j [grad_i W(r_ij, h_i) / Omega_i + grad_i W(r_ij, h_j) / Omega_j],
//
// equal and opposite in every pair (V_i du_i/dt = -V_j du_j/dt for its pair term), so total
// momentum is conserved to round-off and energy up to the time integration. On a uniform
// lattice it is the summed-depth gradient -g grad d.
//
// Dissipation. Approaching pairs only ((u_i - u_j) . (x_i - x_j) < 0), as an artificial
// pressure from a Riemann-solver signal speed (Monaghan 1997, in shallow-water form):
//
//   du_i/dt += -sum_j V_j Pi_ij grad_i Wbar_ij,   Pi_ij = -alpha v_sig w_ij / (2 dbar_ij),
//   w_ij = (u_i - u_j) . (x_i - x_j) / r,   v_sig = c_i + c_j - 3 w_ij,   c = sqrt(g d),
//
// with Wbar the mean of both kernels. Zero at rest and in expansion; it only removes energy.

#include <cstdint>
#include <vector>

#include "swemps/swe/particle_shifting.hpp"
#include "swemps/swe/scheme.hpp"

namespace swemps::swe {

class ConservativeScheme final : public Scheme {
 public:
  explicit ConservativeScheme(const Settings& settings);

  std::string_view name() const override { return "conservative"; }
  const ParticleKernel& kernel() const override { return kernel_; }
  // New particles (smoothing length 0) start from their current area; the others keep the
  // radius of the last summation, which the next one starts its iteration from.
  void choose_smoothing_lengths(particles::SweParticles& p) override;
  double search_radius(double h) const override {
    return ParticleKernel::support(h) * (1.0 + kSearchMargin);
  }
  bool uniform_radius() const override { return false; }
  bool sum_depth(particles::SweParticles& p, const neighbors::NeighborList& nl) override;
  bool sum_depth_of(particles::SweParticles& p, const neighbors::NeighborList& nl,
                    std::span<const std::uint32_t> which) override;
  std::span<const std::uint32_t> outgrown() const override { return outgrown_; }
  void surface_acceleration(particles::SweParticles& p, const neighbors::NeighborList& nl,
                            double gravity_m_s2, std::span<double> accel_x,
                            std::span<double> accel_y) override;
  // Particle shifting (particle_shifting.hpp) when Settings::shifting > 0, from the
  // concentration field the last surface_acceleration() summed.
  bool regularising_shift(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                          double dt_s, std::span<double> shift_x,
                          std::span<double> shift_y) override;

  // Newton iterations of the last sum_depth() or sum_depth_of(), summed over the particles it
  // summed, and its largest count.
  std::size_t last_iterations() const { return last_iterations_; }
  std::size_t last_most_iterations() const { return last_most_iterations_; }

  // Relative margin on the search radius: h may grow by this much in one summation before the
  // neighbours must be searched again. Depth changes by a few per cent per step at most (eq 13
  // moves a particle half a spacing), h by half as much.
  static constexpr double kSearchMargin = 0.05;

 private:
  ParticleKernel kernel_;
  double kappa_, max_area_ratio_, dissipation_, shifting_;
  std::size_t last_iterations_ = 0, last_most_iterations_ = 0;
  std::vector<std::uint32_t> iterations_;
  std::vector<std::uint8_t> grown_;      // per particle summed: its radius outgrew its search
  std::vector<std::uint32_t> outgrown_;  // those particles, ascending
  bool sum_depths(particles::SweParticles& p, const neighbors::NeighborList& nl,
                  std::span<const std::uint32_t> which, bool every);
  std::vector<double> celerity_;  // sqrt(g d) per particle and ghost, kept between steps
  // C and grad C, summed in the force pass for the shift that follows it.
  ConcentrationField concentration_;
};

}  // namespace swemps::swe

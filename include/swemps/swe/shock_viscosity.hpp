#pragma once
// Shock viscosity: the artificial viscosity of Monaghan (1992), written for the shallow-water
// particle system with depth in the place of density and volume in the place of mass:
//
//   a_i += -sum_j V_j Pi_ij grad_i w_ij,      grad_i w_ij = w'(r_ij) (x_i - x_j) / r_ij,
//   Pi_ij = -alpha c_ij mu_ij / h_ij  when (u_i - u_j).(x_i - x_j) < 0, else 0,
//   mu_ij = r_e (u_i - u_j).(x_i - x_j) / (r_ij^2 + eps r_e^2),
//
// with c_ij and h_ij the means of sqrt(g h) and h over the pair, r_e the influence radius
// (eq 9) and eps = 0.01. It acts only between particles that approach each other, so water at
// rest or in uniform motion feels nothing. Pi_ij is symmetric and grad_i w_ij antisymmetric,
// so sum_i V_i a_i = 0 (momentum is kept), and
//   dE/dt = -1/2 sum_ij V_i V_j Pi_ij (u_i - u_j).grad_i w_ij <= 0
// term by term (w' < 0): mechanical energy can only be taken, never added. That is what a
// shock does physically: across a bore, energy goes into turbulence and heat. Without it a
// particle shock rings; with it the shock is spread over a few particles and the ringing is
// damped (docs/robustness.md). A scene asks for it with numerics.shock_viscosity = alpha.
//
// Explicit: the effect limits the step so that it damps any particle's velocity by at most
// its own size in one step, dt <= 1 / max_i k_i with k_i = d|a_i|/d|u_i|, the damping rate.

#include <vector>

#include "swemps/swe/effect.hpp"

namespace swemps::swe {

class ShockViscosity final : public Effect {
 public:
  // alpha: dimensionless, > 0 (0.1 to 1 are usual).
  explicit ShockViscosity(double alpha);
  std::string_view name() const override { return "shock viscosity"; }
  Stage stage() const override { return Stage::forces; }
  void apply(StepContext& context) override;
  double time_step_limit(const Settings& settings, double time_s) const override;
  std::string report() const override;
  void save_state(StateWriter& out) const override;
  void restore_state(StateReader& in) override;
  double alpha() const { return alpha_; }

 private:
  double alpha_;
  double largest_damping_rate_ = 0.0;  // 1/s, of the last apply(): sets the next step's limit
  double dissipated_ = 0.0;  // m^5 s^-2: energy taken over the run (times rho gives J)
  std::vector<double> rate_, power_, celerity_;  // per particle, reused between steps
};

}  // namespace swemps::swe

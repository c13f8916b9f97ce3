#pragma once
// Horizontal eddy viscosity: a_i += nu lap(u)_i, the MPS Laplacian (Koshizuka's form, with
// the area weights of eq 5 and 6):
//   lap(u)_i = 2 D / (lambda_i n_i) sum_j (A_j / A_i) (u_j - u_i) w_ij,
//   lambda_i = sum_j (A_j / A_i) r_ij^2 w_ij / n_i,
// so that lap of a quadratic field is exact on a regular lattice. Velocity differences only:
// water at rest feels nothing, and a lake balanced by Simulation::balance_volumes() stays
// balanced. A scene asks for it (numerics.eddy_viscosity) to represent turbulent mixing, and
// to damp the slow growth of particle-scale disturbances that eq 6 alone allows over still
// water (docs/method.md, "Water at rest over a bed"). Explicit: the effect limits the step
// to dt <= lambda / (4 D nu) (the diffusion limit of the forward step).

#include "swemps/swe/effect.hpp"

namespace swemps::swe {

class EddyViscosity final : public Effect {
 public:
  // nu in m^2/s, > 0.
  explicit EddyViscosity(double viscosity_m2_s);
  std::string_view name() const override { return "eddy viscosity"; }
  Stage stage() const override { return Stage::forces; }
  void apply(StepContext& context) override;
  double time_step_limit(const Settings& settings, double time_s) const override;
  void save_state(StateWriter& out) const override;
  void restore_state(StateReader& in) override;
  double viscosity() const { return viscosity_; }

 private:
  double viscosity_;
  double smallest_lambda_m2_ = 0.0;  // of the last apply(): sets the next step's limit
};

}  // namespace swemps::swe

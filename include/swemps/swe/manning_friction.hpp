#pragma once
// Bed friction by Manning's law (eq 3, with n_M squared as method.md corrects, R = h):
// du/dt = -g n^2 |u| u / h^(4/3). Integrated semi-implicitly,
//   u_new = u* / (1 + dt g n^2 |u_0| / h^(4/3)),
// u* the velocity after this step's acceleration a (u* = u_0 + dt a), u_0 the one before it
// (read back as u* - dt a: friction is the velocity stage's only effect), so that friction can
// only slow a particle, never reverse it, however thin the water. Two answers are exact:
//  - with no other force, 1/|u| grows by dt g n^2 / h^(4/3) per step, which is the
//    closed-form decay |u(t)| = |u0| / (1 + g n^2 |u0| t / h^(4/3));
//  - in steady uniform flow (u_new = u_0 = U) the update holds only where g n^2 U^2 / h^(4/3)
//    = |a|, Manning's law itself, whatever dt.
// The factor once took |u*| instead. Its steady state is then U (U + dt |a|) = U_Manning^2:
// a flow slowed by the step itself, most where the water is thin and the step long against
// U / |a|. A 1.1 cm sheet on a 1 % slope ran 19 % slow and 17 % deep (docs/rain.md,
// "Friction in thin water"). Like LISFLOOD-FP's update of the discharge (Bates et al. 2010),
// the speed in the factor is the step's starting one. Its fixed point is approached
// alternating from either side when dt g n^2 U / h^(4/3) > 1, damped by the ratio
// (1 - that) / (1 + that) each step.
// n is one value for the whole bed, or varies in space (a land-use map): then each particle
// takes the n under it, each step.

#include <memory>

#include "swemps/swe/effect.hpp"

namespace swemps::swe {

// Where Manning's n varies in space: the roughness under a point.
class RoughnessSource {
 public:
  virtual ~RoughnessSource() = default;
  virtual double manning_n(double x_m, double y_m) const = 0;  // s m^-1/3, > 0
};

class ManningFriction final : public Effect {
 public:
  explicit ManningFriction(double manning_n) : manning_n_(manning_n) {}  // s m^-1/3
  // n sampled at each particle's position.
  explicit ManningFriction(std::shared_ptr<const RoughnessSource> roughness)
      : roughness_(std::move(roughness)) {}
  std::string_view name() const override { return "Manning friction"; }
  Stage stage() const override { return Stage::velocity; }
  void apply(StepContext& context) override;

 private:
  double manning_n_ = 0.0;  // used when roughness_ is null
  std::shared_ptr<const RoughnessSource> roughness_;
};

}  // namespace swemps::swe

#pragma once
// Bed friction by Manning's law (eq 3, with n_M squared as method.md corrects, R = h):
// du/dt = -g n^2 |u| u / h^(4/3). Integrated semi-implicitly,
//   u_new = u* / (1 + dt g n^2 |u*| / h^(4/3)),
// so that friction can only slow a particle, never reverse it, however thin the water.
// For constant depth this update is exact: 1/|u| grows by dt g n^2 / h^(4/3) per step, which
// is the closed-form solution |u(t)| = |u0| / (1 + g n^2 |u0| t / h^(4/3)).
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

#pragma once
// The bed in the momentum equation (eq 2): the flow accelerates down the gradient of the
// water surface z_s = h + z_b, not of the depth alone. Each step the bed elevation is
// sampled at every particle (ghosts take their fluid particle's, as method.md prescribes for
// z_s) and -g grad z_b is added to the acceleration, discretised like the depth gradient so
// that the sum is the gradient of z_s:
//  - with the eq 6 (mps) depth gradient, eq 6 applied to z_b: eq 6 is linear in phi, so
//    eq6(h) + eq6(z_b) = eq6(z_s) exactly, and a flat water surface gives no force;
//  - with the summation depth gradient, the exact gradient of the bed at the particle.

#include <memory>

#include "swemps/swe/bed.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::swe {

// z_b at every fluid particle from the bed, and each ghost's from its fluid particle (as
// method.md prescribes for z_s): the first thing every bed term does in a step.
void sample_bed_at_particles(const BedSource& bed, particles::SweParticles& p);

class BedSlope final : public Effect {
 public:
  BedSlope(std::shared_ptr<const BedSource> bed, GradientVariant gradient)
      : bed_(std::move(bed)), gradient_(gradient) {}
  std::string_view name() const override { return "bed slope"; }
  Stage stage() const override { return Stage::forces; }
  void apply(StepContext& context) override;

 private:
  std::shared_ptr<const BedSource> bed_;
  GradientVariant gradient_;
};

}  // namespace swemps::swe

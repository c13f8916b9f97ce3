#pragma once
// What an effect needs from a step, without a simulation around it: particles, an empty
// neighbour list, the spiky kernel, default settings and a ledger, handed to one apply().

#include <span>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/effect.hpp"
#include "swemps/swe/particle_kernel.hpp"
#include "swemps/swe/settings.hpp"

namespace swemps::testing {

struct EffectStepper {
  particles::SweParticles particles;
  neighbors::NeighborList neighbors;
  swe::ParticleKernel kernel{swe::KernelShape::spiky};
  std::vector<double> accel_x, accel_y;
  swe::Settings settings;
  swe::VolumeLedger ledger;

  // One apply() of the step [t, t + dt]; the positions before the move for the topology
  // stage's effects that read them.
  void step(swe::Effect& effect, double t, double dt, std::span<const double> previous_x = {},
            std::span<const double> previous_y = {}) {
    swe::StepContext context{particles, neighbors, kernel, accel_x, accel_y,
                             settings,  ledger,    t,      dt};
    context.previous_x = previous_x;
    context.previous_y = previous_y;
    effect.apply(context);
  }
};

}  // namespace swemps::testing

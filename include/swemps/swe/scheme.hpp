#pragma once
// A shallow-water scheme: how the depth is summed from the particles and what force the water
// surface exerts on them. The simulation holds one and calls it at fixed points of the step
// (simulation.hpp); walls, effects, integration and output know it only through this
// interface and through the kernel it names (ParticleKernel), so a new scheme is a new class,
// not flags inside another.
//
// Two are implemented: the seed paper's eqs 5-9 (seed_scheme.hpp) and the conservative,
// per-particle-radius scheme (conservative_scheme.hpp); make_scheme() picks by Settings.

#include <memory>
#include <span>
#include <string_view>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/particle_kernel.hpp"
#include "swemps/swe/settings.hpp"

namespace swemps::swe {

class Scheme {
 public:
  virtual ~Scheme() = default;
  virtual std::string_view name() const = 0;
  virtual const ParticleKernel& kernel() const = 0;

  // Before the neighbour search: sets the smoothing length of every fluid particle from the
  // fields the last summation left (a particle with smoothing length 0 has had none: a new
  // one, from its creation area).
  virtual void choose_smoothing_lengths(particles::SweParticles& p) = 0;
  // How far particle i's neighbours are searched for, given its smoothing length h: the
  // support, and a margin for a scheme whose summation may widen it.
  virtual double search_radius(double h) const = 0;
  // Whether every particle has the same search radius (a cheaper neighbour search).
  virtual bool uniform_radius() const = 0;
  // The depth of every fluid particle, its area A = V / h, and whatever else the force reads
  // (smoothing length, grad-h factor). Returns false when some particle's kernel outgrew the
  // radius it was searched with: the caller searches again and calls this once more.
  virtual bool sum_depth(particles::SweParticles& p, const neighbors::NeighborList& nl) = 0;
  // As sum_depth(), for the fluid particles in `which` (ascending) alone, the others' fields
  // kept: after a repair rewrote a few rows (neighbors/row_repair.hpp). A scheme whose depths
  // are not each a sum over the particle's own row sums them all.
  virtual bool sum_depth_of(particles::SweParticles& p, const neighbors::NeighborList& nl,
                            std::span<const std::uint32_t> /*which*/) {
    return sum_depth(p, nl);
  }
  // The particles whose kernel outgrew its search in the last sum_depth() or sum_depth_of()
  // (ascending), when the scheme can name them; empty when it cannot or none did.
  virtual std::span<const std::uint32_t> outgrown() const { return {}; }
  // The acceleration by the water surface on a flat bed (-g grad h) and the scheme's own
  // dissipation, written into accel (fluid particles). Ghosts must carry the fields sum_depth()
  // set (GhostWalls::copy_fields_to_ghosts).
  virtual void surface_acceleration(particles::SweParticles& p, const neighbors::NeighborList& nl,
                                    double gravity_m_s2, std::span<double> accel_x,
                                    std::span<double> accel_y) = 0;
  // A displacement of every fluid particle for a step of dt besides its velocity's, which keeps
  // the arrangement even (particle shifting); false, and nothing written, for a scheme
  // without one. Called with the fields of the last summation, before the particles move.
  virtual bool regularising_shift(const particles::SweParticles& /*p*/,
                                  const neighbors::NeighborList& /*nl*/, double /*dt_s*/,
                                  std::span<double> /*shift_x*/, std::span<double> /*shift_y*/) {
    return false;
  }
};

std::unique_ptr<Scheme> make_scheme(const Settings& settings);

}  // namespace swemps::swe

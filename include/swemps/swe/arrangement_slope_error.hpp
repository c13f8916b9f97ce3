#pragma once
// The smooth error the particles' arrangement puts in their planes' slopes, found from their
// neighbours' levels and taken out (docs/method.md, "Planes that agree with their neighbours").
//
// The balanced bed term (balanced_bed_slope.hpp) gives particle i the plane eta_i + s_i . o
// whose water holds i's depth sum and its gradient. That gradient carries, besides the
// surface's and the bed's slopes, a term of the arrangement, d_i sum_j A_j grad W_ij, which is
// zero on a lattice and not zero where the particles' sizes and spacings vary, as they do
// wherever an inflow, splitting and merging have laid them down. Where it varies smoothly it
// holds a surface that steps down from particle to particle while every plane is flat: a pond
// filled by flow that does not come to one level (measured on the valley flood's upper basin:
// 0.6 m over 2 km half an hour after the inflow stops, planes flat to 4e-4).
//
// The neighbours' levels show that slope: G_i, the weighted least-squares gradient of eta_j
// about eta_i (weighted as the depth sum's gradient is), is first-order consistent whatever
// the arrangement. A force from G_i alone has no stiffness against particle-scale
// rearrangement, though: lakes at rest, perturbed by round-off, set off at metres per second
// within the hour (measured). So the two are split by scale, as a collocated grid's pressure
// is (Rhie and Chow): the error e_i = s_i - G_i is averaged over the kernel,
// <e>_i = sum_j A_j W_ij e_j / sum_j A_j W_ij, and the slope becomes
//
//   s_i - <e>_i,
//
// which keeps the particle-scale part of s_i, the part that holds particles apart, and takes
// the surface's slope at the scale of the kernel from the levels.
//
// Only interior particles (a plane that wets every node of the support) are corrected, and only
// their errors averaged: a shore particle's plane is fitted on part of its support, and its
// level moves far with small changes of its depth; with shore particles in the average, lakes
// at rest doubled their round-off speeds every ten minutes (measured on the valley lakes). Their
// levels still serve their interior neighbours' gradients. Water seeded to a level has s_i = 0
// and equal levels, so G_i = 0, e_i = 0, and rest stays exact.

#include <cstddef>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/particle_kernel.hpp"

namespace swemps::swe {

// One plane per fluid particle, as the balanced bed term found it.
struct ParticlePlanes {
  std::vector<double> slope_x, slope_y;
  std::vector<double> level;   // eta_i; NaN where no plane holds the depth
  std::vector<char> interior;  // the plane wets every node of the support
  void resize(std::size_t n) {
    slope_x.resize(n);
    slope_y.resize(n);
    level.resize(n);
    interior.resize(n);
  }
};

class ArrangementSlopeError {
 public:
  // Replaces the slope of every interior plane by s_i - <e>_i (above). Fluid particles only
  // (ghosts carry no plane); `planes` holds one per fluid particle.
  void remove(const particles::SweParticles& p, const neighbors::NeighborList& neighbors,
              KernelShape shape, ParticlePlanes& planes);

 private:
  std::vector<double> average_weight_;     // per neighbour pair: its weight in <e>_i
  std::vector<double> error_x_, error_y_;  // e_i, per fluid particle
};

}  // namespace swemps::swe

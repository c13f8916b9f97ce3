#pragma once
// Particle shifting for the conservative scheme (docs/method.md, "Particle shifting"), after
// Lind, Xu, Stansby & Rogers (2012, J. Comput. Phys. 231, eqs 16-18): each step moves a
// particle, besides its velocity, down the particle-scale part of the gradient of the particle
// concentration
//
//   C_i = sum_j A_j W(r_ij, h_i)          (A_j = V_j / d_j; about 1 where particles are even),
//   grad C_i = sum_j A_j (dW(r_ij, h_i) + dW(r_ij, h_j)) / 2 e_ij,
//   <grad C>_i = sum_j A_j W(r_ij, h_i) grad C_j / sum_j A_j W(r_ij, h_i)   (j: i and its
//                                                                            fluid neighbours),
//   delta x_i = -D_i (grad C_i - <grad C>_i),   D_i = beta h_i |u_i| dt min(1, Fr_i / 0.1).
//
// Why: a rarefaction (a dam break, a flood spreading down a valley) stretches the water in one
// direction only, so a lattice of particles becomes columns whose spacing outgrows the kernel;
// the columns then collapse into an even arrangement all at once, and that sends a spurious
// bore through the flow (measured: two thirds of the 50 m Ritter fan's L1 error came from it).
// The shift fills the gaps between columns as they open, a little each step.
//
// Why the kernel average is taken off (our choice, by measurement, docs/method.md): grad C
// also has a smooth part, from the kernel sum's bias on a stretched lattice, the depth's own
// variation and the edge of the water. A shift along it moves whole regions of particles, and
// their volume with them, in one direction: Lind's shift as it stands took water from the dam
// to the front of the 10 m Ritter case (fan L1 2.7 -> 3.5 %). Disorder is at the particle
// scale, which the average leaves in.
//
// What it keeps. Volume and momentum exactly (a shift moves a particle, not its volume or
// velocity); still water stays still (D is 0 at rest). Where a particle's support is cut by
// the edge of the water (C_i below kEdgeConcentration), it is not shifted: there -grad C
// points into the dry land and would spread the water. Walls take part through their ghosts,
// which make C even up to a wall. A shift is at most kLargestShift of the particle's spacing.

#include <span>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/settings.hpp"

namespace swemps::swe {

// C_i and grad C_i of every fluid particle (the header's formulas).
struct ConcentrationField {
  std::vector<double> concentration, gradient_x, gradient_y;
};

// The field in a pass of its own. The conservative scheme sums the same terms in its force
// pass, where the pair distances and kernel slopes are at hand anyway; this is the reference
// it is tested against.
void concentration_field(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                         KernelShape shape, ConcentrationField& field);

// Writes each fluid particle's shift for a step of dt into shift_x, shift_y (sized to the
// fluid particles), from `field`, the particles' fields of the last summation, ghosts
// included, and each fluid particle's celerity sqrt(g d_i).
void particle_shift(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                    KernelShape shape, double beta, double dt_s, const ConcentrationField& field,
                    std::span<const double> celerity, std::span<double> shift_x,
                    std::span<double> shift_y);

// The concentration below which a particle counts as at the water's edge and is not shifted.
inline constexpr double kEdgeConcentration = 0.95;
// A shift is at most this fraction of the particle's spacing sqrt(A_i).
inline constexpr double kLargestShift = 0.1;
// Below this Froude number |u_i| / sqrt(g d_i), D_i falls in proportion to it: the shift goes
// as |u|^2 in slow water, so that it is of second order about rest. Why: a shift in proportion
// to |u| is of first order, and where the particles at rest are unevenly spread (a lake's
// fingers over a DEM, particles of several cells' area with few neighbours) a velocity of
// round-off moved them off their balanced places by enough to drive a larger velocity: a lake
// grew from 1e-9 to metres per second within minutes (docs/method.md, "Particle shifting").
// The columns the shift is for open in fast water, a rarefaction's fan.
inline constexpr double kSlowFroude = 0.1;

}  // namespace swemps::swe

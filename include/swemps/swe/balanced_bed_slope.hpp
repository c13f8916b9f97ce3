#pragma once
// The bed in the momentum equation, balanced by construction (docs/method.md, "Water at rest
// over a bed"): the force the water surface and the bed exert together on particle i is
//
//   a_i = -g s_i   (with the scheme's dissipation beside it),
//
// where s_i is the slope of the plane surface that i's depth sum sees. The bed is known at the
// nodes of the seeding lattice (bed_lattice.hpp), each weighed by w_k = a W(x_i - x_k, h_i);
// a plane surface eta(x) = eta_i + s . (x - x_i) puts water (eta(x_k) - z_k)+ on them. The
// plane of i is the one whose water gives, through i's kernel, both i's summed depth and its
// gradient in x_i:
//
//   sum_k w_k (eta_i + s . o_k - z_k)+ = h_i(summed),                                   (*)
//   sum_k grad w_k (eta_i + s . o_k - z_k)+ = grad h_i(summed),    o_k = x_k - x_i.
//
// Water seeded on the nodes with V_j = a (eta_0 - z_j) sums at every point to the left side of
// (*) with s = 0 and eta = eta_0 (dry nodes add nothing on either side), and so does its
// gradient: s = 0 at every particle, shores included, whatever the roughness, radii or volumes,
// and the force is zero to round-off. A plane surface over any bed is read exactly, shoreline
// included, for particles on the nodes; a lone particle, whose depth sum has no gradient, sees
// the bed's slope under a uniform film and slides as a particle on a slope does. Dry nodes
// count only up to the surface (the positive part), which is the hydrostatic reconstruction of
// a shoreline.
//
// The scheme has already applied its pressure force -g sum_j V_j K_ij (K with the grad-h
// factors Omega); this effect adds the balanced force and takes that one back, so that the
// total is the balanced force plus the scheme's dissipation. It is not antisymmetric in pairs:
// the bed is an external force, and the price is momentum conservation on level reaches and a
// total energy that is not bound to fall.
//
// The plane's slope carries an error of the particles' arrangement that, where it varies
// smoothly, holds water that has come to rest by flow at levels stepping down from particle to
// particle; before the force is applied, interior planes trade the smooth part of that error
// for their neighbours' levels' slope (arrangement_slope_error.hpp).
//
// Kernels narrower than a lattice cell (water squeezed against a wall) see the bed through
// finer points between the nodes, and a plane steeper than twice the depth sum's and the bed's
// slopes together (a bore's toe, wet on a sliver) is cut back to that.
//
// What it costs and where it falls short (docs/method.md, "The balanced bed term"): exact for
// water filled to a level; Thacker's oscillation to 1.6 % of the volume (1.5 % with the point
// bed); a sheet spreading over a dry or micrometre-wet bed gains energy (up to 2 % of E0 in
// 4 s), where the point bed's force, the gradient of the particles' potential energy, never
// adds any. The default (Settings::bed_term) all the same: the point bed leaves a sea at rest
// over a shelf moving at 0.36 m/s and a lake over a rough bed at 0.25 m/s before anything
// happens, which no flood or tsunami study can start from.

#include <memory>
#include <span>
#include <vector>

#include "swemps/swe/arrangement_slope_error.hpp"
#include "swemps/swe/bed.hpp"
#include "swemps/swe/bed_lattice.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::swe {

// The eta of (*) with s = 0, for nodes of elevation z and weight w (>= 0) holding `depth` (> 0)
// (a tilted plane is the same over the tilted bed z_k - s . o_k): the
// root of a convex, piecewise linear, increasing function, found by Newton's method from the
// level that would hold the depth if every node were wet (never below the root), which ends
// on the exact root in as many steps as nodes change from wet to dry. Returns NaN when no
// weight is positive.
double level_holding(std::span<const double> z, std::span<const double> w, double depth);

class BalancedBedSlope final : public Effect {
 public:
  BalancedBedSlope(std::shared_ptr<const BedSource> bed, std::shared_ptr<const BedLattice> lattice)
      : bed_(std::move(bed)), lattice_(std::move(lattice)) {}
  std::string_view name() const override { return "bed slope (balanced)"; }
  Stage stage() const override { return Stage::forces; }
  void apply(StepContext& context) override;

 private:
  std::shared_ptr<const BedSource> bed_;
  std::shared_ptr<const BedLattice> lattice_;
  std::vector<char> occupied_;    // by lattice node: whether a particle sits nearest to it
  std::vector<std::size_t> marked_;  // the nodes occupied_ marks
  ParticlePlanes planes_;         // this step's planes, one per fluid particle
  ArrangementSlopeError arrangement_error_;
};

}  // namespace swemps::swe

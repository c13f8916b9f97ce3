#pragma once
// The bed in the momentum equation, balanced by construction (docs/method.md, "Water at rest
// over a bed"): the force the water surface and the bed exert together on particle i is
//
//   a_i = -g grad(eta)_i   (with the scheme's dissipation beside it),
//
// where eta_i is the water surface at i seen through i's own kernel: the level at which the
// bed nodes around i (bed_lattice.hpp), each weighed by a W(x_i - x_k, h_i), hold the summed
// depth of i,
//
//   sum_k a W(x_i - x_k, h_i) max(0, eta_i - z_k) = h_i(summed).                  (*)
//
// Water seeded on the lattice's nodes with V_j = a (eta_0 - z_j) sums at every particle to the
// left side of (*) at eta_0 (dry nodes add nothing on either side), so eta_i = eta_0 at every
// particle, shore included, whatever the roughness, the radii or the volumes, and the force is
// zero to round-off. Dry nodes count only up to the surface (the max), which is the
// hydrostatic reconstruction of a shoreline.
//
// The gradient is the corrected difference form, M_i^-1 sum_j A_j (eta_j - eta_i) grad W_ij
// with M_i = sum_j A_j grad W_ij (x_j - x_i)^T, grad W_ij the mean of both particles' kernel
// gradients: exact for a plane surface even where a shore cuts the support (uncorrected, a
// shore particle feels a third of the slope; Bonet & Lok 1999). It is zero at rest whatever M.
// The scheme has already applied its pressure force -g sum_j V_j K_ij (K with the grad-h
// factors Omega); this effect adds the balanced force and takes that one back, so that the
// total is the balanced force plus the scheme's dissipation. It is not antisymmetric in pairs:
// the bed is an external force, and the price is momentum conservation on level reaches.
//
// What it costs and where it falls short (docs/method.md, "Water at rest over a bed"): exact
// for water filled to a level, 1e-14 m/s over six hours on a rough bed at one particle per
// cell; a shoreline that moves far from the seeding lattice reads a surface up to a millimetre
// low, and Thacker's oscillation loses accuracy (6.9 % of the volume against 1.8 % with the
// point bed). Hence an option (Settings::bed_term), not yet the default.

#include <memory>
#include <span>
#include <vector>

#include "swemps/swe/bed.hpp"
#include "swemps/swe/bed_lattice.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::swe {

// The eta of (*) for nodes of elevation z and weight w (>= 0) holding `depth` (> 0): the
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
  std::vector<double> surface_;  // eta, fluid particles then ghosts: kept to reuse its memory
};

}  // namespace swemps::swe

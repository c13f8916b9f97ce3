#pragma once
// The sea floor's vertical displacement by slip on rectangular fault planes in an elastic
// half-space, Okada (1985), "Surface deformation due to shear and tensile faults in a
// half-space", Bull. Seism. Soc. Am. 75(4), 1135-1154, eqs 25-30 (the vertical component
// u_z of each of strike slip, dip slip and tensile opening, with I4 and I5 of eq 28 and
// their vertical-fault limits of eq 29). What a tsunami source needs of it: u_z at the
// surface, for any number of subfaults given in the scene's plane coordinates.
//
// Left out, as tsunami models that start from Okada commonly leave them out
// (docs/tsunami.md, "Fault sources"): the horizontal displacement's contribution to the
// water column over a sloping floor (Tanioka & Satake 1996), the filtering of the floor's
// deformation by the water above it (Kajiura 1963), the rupture's rise time and spread (the
// rupture here is instantaneous), and the Earth's curvature (a flat half-space; the scene is
// projected).

#include <array>
#include <memory>
#include <vector>

#include "swemps/swe/bed.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::tsunami {

// One rectangular fault plane, placed as earthquake catalogues give it.
struct FaultPlane {
  std::array<double, 2> top_centre_m{0.0, 0.0};  // the top edge's midpoint, on the map (x, y)
  double top_depth_m = 0.0;                      // of the top edge below the surface, >= 0
  double strike_deg = 0.0;  // clockwise from the map's +y; the plane dips to the right of it
  double dip_deg = 0.0;     // (0, 90]
  double rake_deg = 0.0;    // the slip's direction in the plane: 90 a thrust, 0 left-lateral
  double slip_m = 0.0;      // >= 0
  double length_m = 0.0;    // > 0, along strike
  double width_m = 0.0;     // > 0, down dip
};

// u_z at the surface point (x, y) in Okada's own frame: x along strike from the fault's
// lower corner, y normal to strike with the plane rising towards +y, the lower edge at depth
// `depth`, for dislocations u1 (strike slip), u2 (dip slip) and u3 (tensile opening). `alpha`
// is mu / (lambda + mu) = 1 - 2 nu (0.5 for a Poisson solid).
double okada_vertical(double x, double y, double depth, double dip_rad, double length, double width,
                      double u1, double u2, double u3, double alpha);

// The summed vertical displacement of a set of fault planes.
class FaultSource {
 public:
  // Throws std::invalid_argument for a plane with a non-positive length or width, a dip
  // outside (0, 90], a negative depth or slip, a non-finite value, or a Poisson's ratio
  // outside (0, 0.5).
  explicit FaultSource(std::vector<FaultPlane> planes, double poisson_ratio = 0.25);

  double vertical_displacement(double x_m, double y_m) const;
  const std::vector<FaultPlane>& planes() const { return planes_; }

 private:
  std::vector<FaultPlane> planes_;
  double alpha_;
};

// The source's vertical displacement sampled at the centres of a grid of square cells of side
// `cell_m` (at most) covering [x_min, x_max] x [y_min, y_max] and a cell beyond, computed once
// in parallel: the floor is read at every particle every step, and Okada's u_z costs 234 ns a
// plane, a bilinear read 32 ns (measured), where a finite-fault model has hundreds of planes.
// The displacement varies over the source's depth, kilometres, and the particles resolve it
// at their spacing, so a grid at the finest particle spacing loses nothing they can see.
terrain::GriddedField sample_displacement(const FaultSource& source, double x_min, double x_max,
                                          double y_min, double y_max, double cell_m);

// The sea floor after an instantaneous rupture: the bed before it (null: flat at z = 0) raised
// by the source's vertical displacement, read from its sampled grid. Water keeps its depth
// over it, so its surface rises with the floor (docs/tsunami.md, "Fault sources").
class RupturedBed final : public swe::BedSource {
 public:
  RupturedBed(std::shared_ptr<const swe::BedSource> before, terrain::GriddedField displacement)
      : before_(std::move(before)), displacement_(std::move(displacement)) {}
  double elevation(double x_m, double y_m) const override {
    return (before_ ? before_->elevation(x_m, y_m) : 0.0) + displacement_.sample(x_m, y_m);
  }
  std::array<double, 2> gradient(double x_m, double y_m) const override {
    const auto lift = displacement_.gradient(x_m, y_m);
    if (!before_) return lift;
    const auto base = before_->gradient(x_m, y_m);
    return {base[0] + lift[0], base[1] + lift[1]};
  }
  const terrain::GriddedField& displacement() const { return displacement_; }

 private:
  std::shared_ptr<const swe::BedSource> before_;
  terrain::GriddedField displacement_;
};

}  // namespace swemps::tsunami

#pragma once
// Filling a polygon with particles on a square lattice.

#include <array>
#include <vector>

namespace swemps::particles {

struct Lattice {
  std::vector<std::array<double, 2>> points;  // m
  double cell_area_m2 = 0.0;                  // the area each point stands for
  // Point (i, k) of the lattice sits at corner + ((i + 1/2) dx, (k + 1/2) dy); the points are
  // those of the shape (swe/bed_lattice.hpp continues the lattice over the whole domain).
  std::array<double, 2> corner{0.0, 0.0};
  double dx_m = 0.0, dy_m = 0.0;
};

// An axis-aligned rectangle gets a lattice fitted to it: the spacing is adjusted (by at
// most half a cell over the side) so that a whole number of cells covers it exactly and
// the outer particles sit half a cell from its edges, where the mirrored wall ghosts
// continue the lattice. Any other polygon gets the cell centres of a square lattice that
// fall inside it, and each point stands for an equal share of the polygon's area, so the
// water volume is exactly area x depth either way.
Lattice fill_polygon(const std::vector<std::array<double, 2>>& polygon, double spacing_m);

// The points of `lattice` connected to the one nearest `from` through points marked in `wet`
// (one flag per lattice point), each to its eight neighbours on the lattice: a lake filled to a
// level from one point, whose rim keeps the lower ground beyond it dry. Diagonal neighbours
// count: a kernel reaches across the corner between them, so water there is one body (with four
// neighbours, lakes filled over the Jacksboro DEM ended 1.4 cells from lower ground). All false
// when the point nearest `from` is not wet.
std::vector<char> connected_to(const Lattice& lattice, const std::vector<char>& wet,
                               std::array<double, 2> from);

double polygon_area(const std::vector<std::array<double, 2>>& polygon);
bool point_in_polygon(const std::vector<std::array<double, 2>>& polygon, std::array<double, 2> p);

}  // namespace swemps::particles

#pragma once
// What is measured on a Navier-Stokes run, for output and for comparison with experiment and
// with the shallow-water mode: the surge front, the water depth over a plan grid, and the
// pressure at a point.

#include <array>
#include <cstddef>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/ns/particles.hpp"

namespace swemps::ns {

// The leading edge along +x: the largest x of a fluid particle that has another fluid
// particle within 1.5 l_0 (a lone droplet thrown ahead is not the front), plus l_0 / 2,
// because a particle stands for the cell of water around it (at t = 0 the edge of a column
// of n particles is n l_0 from the wall, as in the experiment).
template <int Dim>
double front_position(const Particles<Dim>& particles, double spacing_m);

// A regular plan grid of cell centres x0 + i dx, y0 + k dy (i < nx, k < ny), row-major
// with x fastest.
struct PlanGrid {
  double x0 = 0.0, y0 = 0.0, dx = 0.0, dy = 0.0;
  std::size_t nx = 0, ny = 0;
};

// Depth of water over each plan cell: the volume of the fluid particles whose (x, y) fall in
// the cell divided by its area (3D), or the area in the x-z plane per unit width over dx
// (2D: a vertical section, the same for every row k). Volume-based, so it conserves water
// and counts spray and overhangs where they are.
template <int Dim>
std::vector<double> column_depth(const Particles<Dim>& particles, double spacing_m,
                                 const PlanGrid& grid);

// Pressure at `point`: the kernel-weighted mean of the fluid and wall particles' pressures
// around it (Shepard average), 0 with no particle in the support. Used for pressure probes
// on walls and floors, where wall particles carry the pressure the water exerts.
template <int Dim>
double pressure_at(const Particles<Dim>& particles, const kernels::AnyKernel<Dim>& kernel,
                   const std::array<double, Dim>& point);

}  // namespace swemps::ns

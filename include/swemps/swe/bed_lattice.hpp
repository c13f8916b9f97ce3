#pragma once
// The bed as the water particles see it: elevations at the nodes of a regular lattice, the
// lattice the water was seeded on, each node standing for one lattice cell of bed
// (docs/method.md, "Water at rest over a bed"). The balanced bed term (balanced_bed_slope.hpp)
// weighs these nodes with a particle's own kernel, the same weights its depth sum gives the
// particles seeded on them, so that water filled to a level feels no force.
//
// The lattice reaches past the domain by a margin; a node outside the domain carries the bed
// of its mirror image across the domain's edge, as a ghost particle carries its fluid
// particle's water, so that a lake against a wall along the domain's edge is balanced too.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "swemps/swe/bed.hpp"

namespace swemps::swe {

struct BedLatticeGeometry {
  // Node (i, k) sits at (x0 + (i + 1/2) dx, y0 + (k + 1/2) dy), for any integers i, k: the
  // water seeding lattice (particles/seeding.hpp) with its corner at (x0, y0).
  double x0_m = 0.0, y0_m = 0.0;
  double dx_m = 1.0, dy_m = 1.0;
  // The area a node stands for: the area each seeded particle's volume was reckoned with
  // (dx dy on a rectangle; a polygon's area over its points otherwise).
  double node_area_m2 = 1.0;
};

// Where a node sits in the lattice's stored block: its column and row, and its index
// row * columns() + column.
struct LatticeNode {
  std::size_t index;
  long column, row;
};

struct DomainBox {
  double x_min, x_max, y_min, y_max;
};

class BedLattice {
 public:
  // The nodes of `geometry` that lie within `margin_m` of `domain` (margin: the widest
  // kernel support a particle may reach).
  BedLattice(const BedSource& bed, const BedLatticeGeometry& geometry, const DomainBox& domain,
             double margin_m);

  // Raises the node at (x, y), if there is one there, and its mirror images beyond the domain
  // to `level_m`: a seeded point whose water was too thin to keep (min_depth) must read as dry
  // to the water beside it, or its empty cell would hold water in the balance that no
  // particle carries.
  void raise_node_at(double x_m, double y_m, double level_m);

  double node_area_m2() const { return geometry_.node_area_m2; }
  // The nodes are numbered row by row, columns() to a row: node index + 1 is the next along x,
  // index + columns() the next along y.
  std::size_t node_count() const { return z_.size(); }
  std::size_t columns() const { return static_cast<std::size_t>(nx_); }
  // The index of the node nearest (x, y), or node_count() where that node lies beyond the
  // stored block.
  std::size_t nearest_node(double x, double y) const {
    const double i = std::round((x - first_x_) / geometry_.dx_m);
    const double k = std::round((y - first_y_) / geometry_.dy_m);
    if (!(i >= 0.0 && k >= 0.0 && i < static_cast<double>(nx_) && k < static_cast<double>(ny_)))
      return z_.size();
    return static_cast<std::size_t>(k) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(i);
  }
  // The longer side of a lattice cell.
  double cell_size_m() const { return std::max(geometry_.dx_m, geometry_.dy_m); }

  // Calls visit(r2, z) for every node closer than `radius` to (x, y): its squared distance
  // and its elevation. Nodes beyond the lattice's margin are not visited.
  template <class Visit>
  void for_each_node_within(double x, double y, double radius, Visit&& visit) const {
    for_each_node_offset_within(
        x, y, radius, [&](double, double, double r2, double z, LatticeNode) { visit(r2, z); });
  }

  // As for_each_node_within, with each node's offset from (x, y) first and its place in the
  // lattice last: visit(x_node - x, y_node - y, r2, z, LatticeNode).
  template <class Visit>
  void for_each_node_offset_within(double x, double y, double radius, Visit&& visit) const {
    const double gx = (x - first_x_) / geometry_.dx_m, gy = (y - first_y_) / geometry_.dy_m;
    const long i0 = std::max(0L, static_cast<long>(std::ceil(gx - radius / geometry_.dx_m)));
    const long i1 = std::min(nx_ - 1, static_cast<long>(std::floor(gx + radius / geometry_.dx_m)));
    const long k0 = std::max(0L, static_cast<long>(std::ceil(gy - radius / geometry_.dy_m)));
    const long k1 = std::min(ny_ - 1, static_cast<long>(std::floor(gy + radius / geometry_.dy_m)));
    const double r2_max = radius * radius;
    for (long k = k0; k <= k1; ++k) {
      const double dy = first_y_ + static_cast<double>(k) * geometry_.dy_m - y;
      const double* row = z_.data() + static_cast<std::size_t>(k * nx_);
      for (long i = i0; i <= i1; ++i) {
        const double dx = first_x_ + static_cast<double>(i) * geometry_.dx_m - x;
        const double r2 = dx * dx + dy * dy;
        if (r2 < r2_max) visit(dx, dy, r2, row[i], LatticeNode{static_cast<std::size_t>(k * nx_ + i), i, k});
      }
    }
  }

  // The lattice seen finer, for a kernel narrower than its cells: m x m points per cell, at the
  // centres of the cell's m x m sub-cells, each standing for node_area_m2() / m^2 of bed, with
  // the elevation interpolated bilinearly between the nodes (exact for a plane bed; a node's
  // own point keeps its elevation for odd m). visit(ox, oy, r2, z) is called for every point
  // closer than `radius` to (x, y).
  template <class Visit>
  void for_each_fine_point_within(double x, double y, double radius, int m, Visit&& visit) const {
    const double dx = geometry_.dx_m, dy = geometry_.dy_m, fm = static_cast<double>(m);
    // Point f along an axis sits at node coordinate (f + 1/2) / m - 1/2 of the stored block.
    const auto first = [&](double g, double reach) {
      return std::max(0L, static_cast<long>(std::ceil((g - reach + 0.5) * fm - 0.5)));
    };
    const auto last = [&](double g, double reach, long count) {
      return std::min(count * m - 1, static_cast<long>(std::floor((g + reach + 0.5) * fm - 0.5)));
    };
    const double gx = (x - first_x_) / dx, gy = (y - first_y_) / dy;
    const long f0 = first(gx, radius / dx), f1 = last(gx, radius / dx, nx_);
    const long g0 = first(gy, radius / dy), g1 = last(gy, radius / dy, ny_);
    const double r2_max = radius * radius;
    for (long g = g0; g <= g1; ++g) {
      const double node_y = (static_cast<double>(g) + 0.5) / fm - 0.5;
      const double oy = (node_y - gy) * dy;
      const long k = std::clamp(static_cast<long>(std::floor(node_y)), 0L, std::max(ny_ - 2, 0L));
      const long k_up = std::min(k + 1, ny_ - 1);
      const double ty = node_y - static_cast<double>(k);
      for (long f = f0; f <= f1; ++f) {
        const double node_x = (static_cast<double>(f) + 0.5) / fm - 0.5;
        const double ox = (node_x - gx) * dx;
        const double r2 = ox * ox + oy * oy;
        if (!(r2 < r2_max)) continue;
        const long i = std::clamp(static_cast<long>(std::floor(node_x)), 0L, std::max(nx_ - 2, 0L));
        const long i_up = std::min(i + 1, nx_ - 1);
        const double tx = node_x - static_cast<double>(i);
        const auto z = [&](long a, long b) { return z_[static_cast<std::size_t>(b * nx_ + a)]; };
        const double low = z(i, k) + tx * (z(i_up, k) - z(i, k));
        const double high = z(i, k_up) + tx * (z(i_up, k_up) - z(i, k_up));
        visit(ox, oy, r2, low + ty * (high - low));
      }
    }
  }

 private:
  BedLatticeGeometry geometry_;
  DomainBox domain_;
  double first_x_ = 0.0, first_y_ = 0.0;  // the node (0, 0) of the stored block
  long nx_ = 0, ny_ = 0;
  std::vector<double> z_;  // row-major, ny_ rows of nx_
};

}  // namespace swemps::swe

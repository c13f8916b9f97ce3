#pragma once
// The bed lattice's nodes around one particle, as the balanced bed term weighs them
// (balanced_bed_slope.hpp): gathered once a step for each particle, with their kernel weights,
// and the lower ground beyond a rim that the particle's plane must leave out. Internal to the
// bed term (src/swe/balanced_bed_slope.cpp).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "swemps/swe/bed_lattice.hpp"

namespace swemps::swe::support {

// The narrowest kernel radius, in lattice cells, that the lattice's own nodes serve; the radius,
// in spacings of the finer points, that a narrower kernel is given: 2 kappa, the reach of a
// seeded particle's kernel in cells at the default kappa (some twenty points); and the finest
// points (m = 64 per cell side: a particle squeezed to 1/4096 of a cell's area).
inline constexpr double kNarrowestSupport = 1.0;
inline constexpr double kRefinedSupport = 2.6;
inline constexpr int kFinestSubdivision = 64;

// The nodes around one particle: elevation z, weight w = a W(x_i - x_k, h_i), the weight's
// gradient with respect to x_i, (wx, wy), and the node's offset x_k - x_i, (ox, oy); gathered
// once so that the Newton steps are tight loops over contiguous values.
struct NodeBuffer {
  std::vector<double> z, w, wx, wy, ox, oy, tilted;
  std::vector<char> wet, previous_wet, wetted, wetted_by_all_wet_plane;
  // The lattice index of each node (empty for the finer points), and the rim search's work
  // space (drop_ground_beyond_rims).
  std::vector<std::size_t> node;
  std::vector<long> column, row, slot;
  std::vector<std::size_t> pending;
  std::vector<char> reached, beyond_rim, previous_beyond_rim;
  std::vector<double> kept_w;

  // Keeps the lattice nodes for which keep(k) holds, in their order (keep reads node k before
  // any later node is moved).
  template <class Keep>
  void keep_only(const Keep& keep) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < z.size(); ++k) {
      if (!keep(k)) continue;
      for (auto* v : {&z, &w, &wx, &wy, &ox, &oy}) (*v)[kept] = (*v)[k];
      node[kept] = node[k];
      column[kept] = column[k];
      row[kept] = row[k];
      ++kept;
    }
    for (auto* v : {&z, &w, &wx, &wy, &ox, &oy}) v->resize(kept);
    node.resize(kept);
    column.resize(kept);
    row.resize(kept);
  }
};

// How finely the bed is seen by a kernel of radius 2h: through the lattice's own nodes while the
// radius reaches a neighbouring node (five nodes or more: a plane can be fitted), through m x m
// points per cell, the bed interpolated between the nodes, where it does not. Such narrow
// kernels belong to particles squeezed well below their seeded area, as water piles against a
// wall; without the finer points they hold one node or none, their plane is undetermined, and
// they feel no force (measured: a thin film piled against a wall into a 3 mm band 0.6 mm deep and
// broke down). The finer points are not the nodes the water was seeded on, so they must not
// serve water at rest: seeded water's kernels reach 1.3 cells or more at the default kappa
// (measured on the lakes over steps and rough beds), past the threshold.
inline int subdivision(double cell_size, double h) {
  if (2.0 * h >= kNarrowestSupport * cell_size) return 1;
  const double needed = std::ceil(kRefinedSupport * cell_size / (2.0 * h));
  return static_cast<int>(std::min(needed, static_cast<double>(kFinestSubdivision)));
}

template <class K>
void gather_nodes(const BedLattice& lattice, double x, double y, double h, NodeBuffer& b) {
  for (auto* v : {&b.z, &b.w, &b.wx, &b.wy, &b.ox, &b.oy}) v->clear();
  b.node.clear();
  b.column.clear();
  b.row.clear();
  const int m = subdivision(lattice.cell_size_m(), h);
  const double a = lattice.node_area_m2() / static_cast<double>(m * m);
  auto add = [&](double ox, double oy, double r2, double z) {
    const double r = std::sqrt(r2);
    const double weight = a * K::w(r, h);
    if (!(weight > 0.0)) return;
    // grad_x W(x - x_k) = W'(r) (x - x_k) / r with x - x_k = -(ox, oy), W' <= 0.
    const double slope = r > 0.0 ? -a * K::dw_dr(r, h) / r : 0.0;
    b.z.push_back(z);
    b.w.push_back(weight);
    b.wx.push_back(slope * ox);
    b.wy.push_back(slope * oy);
    b.ox.push_back(ox);
    b.oy.push_back(oy);
  };
  if (m == 1) {
    // The nodes first, then their weights in one pass that vectorises, with the kernel's
    // constants and 1/h taken once instead of a kernel evaluated node by node, with its
    // divisions (with the pair sums gathered below: the term's own instructions over the first
    // 2 s of Thacker's bowl 1.70e9 -> 1.48e9, docs/performance.md).
    lattice.for_each_node_offset_within(
        x, y, 2.0 * h, [&](double ox, double oy, double, double z, LatticeNode node) {
          b.ox.push_back(ox);
          b.oy.push_back(oy);
          b.z.push_back(z);
          b.node.push_back(node.index);
          b.column.push_back(node.column);
          b.row.push_back(node.row);
        });
    const std::size_t count = b.z.size();
    b.w.resize(count);
    b.wx.resize(count);
    b.wy.resize(count);
    const double inverse_h = 1.0 / h;
    const double w_scale = a * K::sigma() * inverse_h * inverse_h;
    const double slope_scale = w_scale * inverse_h;
    // Raw pointers and an int flag: through the vectors' own accessors, and with a bool
    // reduction, the loop did not vectorise (the vectors' starts were read again at each node).
    const double *ox = b.ox.data(), *oy = b.oy.data();
    double *w = b.w.data(), *wx = b.wx.data(), *wy = b.wy.data();
    int weightless = 0;
#pragma omp simd reduction(| : weightless)
    for (std::size_t k = 0; k < count; ++k) {
      const double r = std::sqrt(ox[k] * ox[k] + oy[k] * oy[k]);
      const double q = r * inverse_h;
      const double weight = w_scale * K::shape(q);
      // grad_x W(x - x_k) = W'(r) (x - x_k) / r with x - x_k = -(ox, oy), W' <= 0.
      const double slope = r > 0.0 ? -slope_scale * K::shape_slope(q) / r : 0.0;
      w[k] = weight;
      wx[k] = slope * ox[k];
      wy[k] = slope * oy[k];
      weightless |= weight > 0.0 ? 0 : 1;
    }
    // A node at the support's edge to round-off weighs nothing and is not part of it.
    if (weightless != 0) b.keep_only([&](std::size_t k) { return b.w[k] > 0.0; });
  } else {  // see subdivision()
    lattice.for_each_fine_point_within(x, y, 2.0 * h, m, add);
  }
}

// Lower ground beyond a rim: the nodes of i's support below the level that holds its depth sum
// (level_holding), that neither hold water (`occupied`, by lattice node: within sqrt(A/2) of a
// particle, fluid or ghost, or nearest to it; apply_with) nor connect to a node that does through
// nodes below that level (all eight neighbours, as a lake is filled from a point). Drops them from
// b and returns true, with `level` (on entry: the level on all of b's nodes) the level on the nodes
// kept; returns false and leaves b as it was when there are none.
//
// Why: a particle in a finger of a lake one cell wide sums its depth mostly from itself, so its
// area is several cells and its support reaches across the finger's rim to lower ground beyond,
// which holds water in (*) that no particle carries: the lake at rest drains towards it
// (measured on the Jacksboro basins: 5e-4 m/s within a second). The water a plane puts on a node
// is water that could be there; a node walled off by higher ground, with no water of its own,
// cannot hold any until the water tops the wall. Dropping such a node leaves rest exact: every
// seeded particle sits on a node it marks, and the nodes of its lake connect to it below the
// level. Dropped nodes raise the level, which may put more of the ground beyond below it (or
// top the rim): the search is repeated with the new level until the dropped set settles.
bool drop_ground_beyond_rims(const std::vector<char>& occupied, std::size_t own_node, double depth,
                             NodeBuffer& b, double& level);

}  // namespace swemps::swe::support

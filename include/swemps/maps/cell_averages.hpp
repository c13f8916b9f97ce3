#pragma once
// What a map cell reads: the water the particles hold in it. Each particle's volume is spread
// over the ground its kernel covers, weighted by the kernel and by how deep the particle's own
// surface stands over the bed there, and the shares that fall in a cell are added up; the
// cell's depth is that volume over its area, its velocity the share-weighted velocity.
// So (docs/outputs.md, "What a map cell means"):
//  - the map holds the particles' volume: every particle's shares add up to its volume, and a
//    share is lost only where it falls outside the map (output grid bounds smaller than the
//    domain), never at a wall or between cell centres, whatever the cell size. The kernel is
//    mirrored at walls (by the walls' ghost particles, as in the depth sum) and at the
//    domain's edges, so uniform water reads uniform up to them, and no share falls behind a
//    wall;
//  - no cell reads water from a particle whose surface stands below the bed of the whole
//    cell: a share goes only where the particle's surface z_b(x_i) + h_i stands over the bed;
//  - the depth is the mean over the cell, as a grid model's finite volume holds it, not a
//    point sample of the kernel sum at the cell's centre (which the spiky kernel's peak makes
//    jump as particles pass over the centre).
// The ground is sampled at sub-points, at most the finest particle spacing apart and at least
// one a cell: each share is a quadrature of the kernel at them, so within a sub-point spacing
// of a wall or a cell edge a share may land in the neighbouring cell (measured: uniform water
// reads its depth within 0.6 % inside, 1.2 % in a corner of the domain), whose bed elevations are
// read once. Results do not depend on the number of threads.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/bed.hpp"
#include "swemps/swe/operators.hpp"
#include "swemps/swe/particle_kernel.hpp"

namespace swemps::maps {

// What the map's cells hold (ny * nx values each, x fastest): depth (the water's volume over
// the cell's area), u and v (the particles' momentum over their volume there), and the
// volume-weighted mean of the surfaces z_b + h of the particles whose water is there (which
// leans towards the higher surfaces where the surface slopes: level() is a cell's water
// level). u, v and the surface are NaN in a cell without water.
struct CellFields {
  std::vector<double> depth, u, v, surface;
  // Provenance, when the particles track it (docs/provenance.md); empty otherwise. Per label,
  // the depth of that label's water (label k's map is label_depth[k * cells, (k + 1) * cells));
  // the volume-weighted mean time the cell's water entered the domain (s; NaN without water).
  std::vector<double> label_depth = {}, entry_time = {};
};

// The domain: sub-points outside it take no share, and the kernel is mirrored at its edges.
struct Bounds {
  double x_min, x_max, y_min, y_max;
};

class CellAverages {
 public:
  // `bed` may be null (flat at z = 0). `finest_spacing_m` is the smallest spacing the scene
  // creates particles at; sub-points are at most that far apart (and at most a cell apart),
  // capped at kMaxSubdivisions across a cell. A fields() call is not safe to run alongside
  // another on the same object (it keeps its scratch space).
  // Up to `stored_sub_points` sub-points have their bed read once and kept; beyond, each share
  // reads the bed where it falls (the same values, more slowly).
  CellAverages(const swe::RegularGrid& grid, std::shared_ptr<const swe::BedSource> bed,
               Bounds domain, double finest_spacing_m,
               std::size_t stored_sub_points = kMaxStoredSubPoints);

  CellFields fields(const particles::SweParticles& p, const swe::ParticleKernel& w) const;

  // The level of the water a cell holds, as a grid model's cell with this ground under it
  // holds it: the flat surface over the cell's sub-points (those inside the domain) under
  // which their ground holds depth_m times the cell's area. A gauge reads the depth at its
  // point as this level less the bed there. The mean of the particles' own surfaces is no
  // measure of it where the surface slopes: a particle sends more of its water down-slope
  // than up (its shares follow how deep its surface stands over the ground), so the water in
  // a cell comes more from the higher surfaces up-slope (measured on uniform flow down a 1.5 %
  // plane: 20 % too deep at 20 m spacing, 52 % at 40 m; docs/outputs.md). NaN without water or
  // ground.
  double level(std::size_t cell, double depth_m) const;

  // The shortest length over which the fields can change: a cell, or the finest spacing the
  // scene creates particles at where cells are finer (each particle's water is spread over
  // its kernel, a few spacings wide).
  double resolved_length_m() const { return resolved_length_m_; }

  // Sub-points across one cell, in each direction.
  std::size_t subdivisions() const { return sub_; }

  static constexpr std::size_t kMaxSubdivisions = 32;
  // Sub-points whose bed is read once and kept (128 MB); beyond, it is read at each share.
  static constexpr std::size_t kMaxStoredSubPoints = std::size_t{1} << 24;

 private:
  // What one particle puts in one cell: a fraction of its volume. kOffMap: inside the domain
  // but outside the map's bounds.
  struct Share {
    std::size_t cell;
    double fraction;
  };
  static constexpr std::size_t kOffMap = static_cast<std::size_t>(-1);
  using Point = std::array<double, 2>;
  // One thread's scratch space for shares_of: the kernel's centres (the particle and its
  // images), and the kernel's values along one row of sub-points.
  struct Scratch {
    std::vector<Point> images;
    std::vector<double> row_weight;
  };
  // The sub-points [first, last] along each axis that a particle's support may reach.
  struct SubRange {
    long i0, i1, k0, k1;
  };
  // Appends fluid particle j's shares, which add up to 1. `ghosts`: its wall ghosts' indices.
  template <class Kernel>
  void shares_of(const particles::SweParticles& p, std::size_t j,
                 std::span<const std::uint32_t> ghosts, const Kernel& kernel, Scratch& scratch,
                 std::vector<Share>& shares) const;
  // The weights of a particle whose kernel has no image (no wall ghost, no edge within reach),
  // row by row over the sub-points inside its support; returns their total.
  template <class Kernel>
  double unmirrored_weights(const particles::SweParticles& p, std::size_t j, const SubRange& range,
                            Scratch& scratch, std::vector<Share>& shares) const;
  // The cell of sub-point (si, sk) (kOffMap: not on the map), and a sub-point's weight added
  // to that cell's share in `shares` from index `first` on.
  std::size_t cell_of_sub_point(long si, long sk, bool row_on_map) const;
  static void add_share(std::size_t cell, double weight, std::size_t first,
                        std::vector<Share>& shares) {
    if (shares.size() > first && shares.back().cell == cell) {
      shares.back().fraction += weight;  // the next sub-point of the same cell
    } else {
      shares.push_back({cell, weight});
    }
  }
  double sub_bed(long si, long sk) const;
  // Particle j's shares list[first, end) added to the provenance maps of `out` (volumes of
  // each label, and volumes times entry times, until fields() divides them).
  static void add_provenance(const particles::SweParticles& p, std::size_t j,
                             const std::vector<Share>& list, std::size_t first, std::size_t end,
                             CellFields& out);
  static std::size_t grid_cells(const CellFields& out) { return out.depth.size(); }

  swe::RegularGrid grid_;
  std::shared_ptr<const swe::BedSource> bed_;
  Bounds domain_;
  double resolved_length_m_ = 0.0;
  std::size_t sub_ = 1;
  double sdx_ = 0.0, sdy_ = 0.0;    // sub-point spacing, m
  double sx0_ = 0.0, sy0_ = 0.0;    // the first sub-point, m
  long snx_ = 0, sny_ = 0;          // sub-points over the grid
  std::vector<double> bed_at_sub_;  // sny_ * snx_, x fastest; empty: not kept
  // Scratch space of fields(), kept between calls: each block's shares, and where each
  // particle's end in its block's list.
  mutable std::vector<std::vector<Share>> shares_;
  mutable std::vector<std::size_t> ends_;
  mutable std::vector<std::size_t>
      ghost_start_;  // fluid particle j's ghosts: [start[j], start[j+1])
  mutable std::vector<std::uint32_t> ghost_list_;
};

}  // namespace swemps::maps

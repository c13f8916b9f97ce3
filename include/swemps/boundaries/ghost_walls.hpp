#pragma once
// Ghost-particle walls (method.md section 1, "Walls"). Each fluid particle within reach of
// a straight wall segment gets one ghost mirrored across it; a particle near two walls that
// meet at a corner also gets the ghost mirrored across both, so a right-angled corner is
// filled like the open water beside it. Ghost normal velocity is minus the particle's;
// tangential velocity is equal (slip) or opposite (no-slip); every other field is copied.
// Ghosts take part in the sums of fluid particles and are never integrated.
//
// Water either side of a wall is two bodies of water: no particle sums another, or another's
// ghosts, through a wall (hide_pairs_across_walls). So a wall may be a single line with water
// on both sides, or a building thinner than a kernel's support, and a ghost may stand beyond
// a thin building among the water there, which does not see it.
//
// Ghost layers alone do not stop a fast particle: after each move, a particle whose path
// crossed a wall is put back on its side by reflection (position and normal velocity).
//
// The walls near a particle are looked up in a WallIndex, so a step's cost grows with the
// particles near walls, not with particles x segments (docs/buildings.md, "Cost").

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "swemps/boundaries/wall_index.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"

namespace swemps::boundaries {

class GhostWalls {
 public:
  GhostWalls() = default;
  explicit GhostWalls(std::vector<WallSegment> segments);

  bool empty() const { return index_.empty(); }
  std::span<const WallSegment> segments() const { return index_.segments(); }

  // Appends the ghosts of every fluid particle within `reach` (m) of a wall and remembers
  // which particles are near which walls for keep_inside(). Requires no ghosts present.
  void add_ghosts(particles::SweParticles& p, double reach);
  // As above; a ghost that stands beyond a second wall as well (behind a building thinner
  // than twice the particle's distance from it) is placed only within own_reach[i] of its
  // wall, particle i's own search radius: the wider kernels of a thin sheet nearby would
  // otherwise fill whole blocks of houses with ghosts, each a point of the search.
  void add_ghosts(particles::SweParticles& p, double reach, std::span<const double> own_reach);

  // Removes from the fluid particles' rows of `nl` every pair that sees each other through a
  // wall: j is hidden from row i when the straight path from particle i to j's particle (its
  // source, for a ghost) crosses a wall. A particle always sees its own ghosts. The test is
  // symmetric, so symmetric rows stay symmetric. Requires the ghosts and walls of the last
  // add_ghosts(), at the same positions, and rows no wider than its reach. Returns the pairs
  // hidden (each pair of fluid particles counted once per row).
  std::size_t hide_pairs_across_walls(const particles::SweParticles& p,
                                      neighbors::NeighborList& nl);
  // As above, for the rows in `rows` (ascending) alone: the rows a repair rewrote.
  std::size_t hide_pairs_across_walls(const particles::SweParticles& p, neighbors::NeighborList& nl,
                                      std::span<const std::uint32_t> rows);

  // Copies depth, area, number density, bed, smoothing length and grad-h factor of each
  // ghost's fluid particle (after the depth summation has set them).
  static void copy_fields_to_ghosts(particles::SweParticles& p);

  // After a move from (old_x, old_y): reflects back every particle whose path crossed a wall
  // segment. Returns how many were reflected.
  std::size_t keep_inside(particles::SweParticles& p, std::span<const double> old_x,
                          std::span<const double> old_y);

  // Signed distance helpers, exposed for tests: true if segment p0-p1 crosses the wall.
  static bool crosses(const WallSegment& wall, std::array<double, 2> p0, std::array<double, 2> p1);
  // True if segment p0-p1 crosses any of the walls: a particle placed at p1 from p0 (a split
  // daughter, a merged pair) would be on another side of one.
  static bool crosses_any(std::span<const WallSegment> walls, std::array<double, 2> p0,
                          std::array<double, 2> p1);

 private:
  struct Line {  // a segment in the frame the reflections need
    std::array<double, 2> origin, tangent, normal;
    double length;
  };
  // The squared distance from x to the segment (its ends included).
  static double distance2_to(const Line& line, std::array<double, 2> x);
  WallIndex index_;
  std::vector<Line> lines_;
  // Hides the pairs of row i seen through a wall; returns how many of its points it keeps (at
  // the row's start).
  std::uint32_t hide_in_row(const particles::SweParticles& p, neighbors::NeighborList& nl,
                            std::uint32_t i) const;
  // Moves each row's kept points (kept_) together after hide_in_row; returns the pairs hidden.
  std::size_t close_rows(neighbors::NeighborList& nl);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> near_wall_;  // (particle, segment)
  // Particle i's walls are near_wall_[near_wall_start_[i] .. near_wall_start_[i + 1]).
  std::vector<std::uint32_t> near_wall_start_;
  std::vector<double> near_wall_distance2_;  // each near_wall_ segment's from its particle
  // Reflects particle i back from the walls (segment ids) its path from `start` crossed, as
  // a billiard ball; true if it moved.
  bool bounce_inside(particles::SweParticles& p, std::size_t i, std::array<double, 2> start,
                     std::span<const std::uint32_t> walls) const;
  std::vector<std::uint32_t> walls_met_;          // keep_inside's walls of one particle
  void place_ghosts(particles::SweParticles& p);  // add_ghosts() with the reaches set
  // True if the path from a particle at x to its ghost at g crosses a wall other than a and b,
  // those it is mirrored across: the ghost would stand beyond them.
  bool behind_another_wall(std::array<double, 2> x, std::array<double, 2> g, std::uint32_t a,
                           std::uint32_t b) const;
  double reach_ = 0.0;             // that of the last add_ghosts()
  std::vector<double> own_reach_;  // each fluid particle's, in the last add_ghosts()
  // The walls each ghost of the last add_ghosts() was mirrored across, in ghost order.
  std::vector<std::array<std::uint32_t, 2>> mirrored_across_;
  std::vector<std::uint32_t> kept_;  // per row: how many points hide_pairs_across_walls keeps
  // add_ghosts' work per chunk of particles, kept so that a step allocates nothing new.
  struct PlacedGhost {
    std::uint32_t particle;
    std::array<double, 2> x, velocity;
    std::array<std::uint32_t, 2> mirrored_across;  // one wall twice, or a corner's two
  };
  struct Chunk {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> near_wall;
    std::vector<double> near_wall_distance2;
    std::vector<PlacedGhost> ghosts;
  };
  std::vector<Chunk> chunks_;
};

}  // namespace swemps::boundaries

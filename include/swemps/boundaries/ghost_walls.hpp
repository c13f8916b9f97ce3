#pragma once
// Ghost-particle walls (method.md section 1, "Walls"). Each fluid particle within reach of
// a straight wall segment gets one ghost mirrored across it; a particle near two walls that
// meet at a corner also gets the ghost mirrored across both, so a right-angled corner is
// filled like the open water beside it. A ghost that would stand behind a second wall as
// well (beyond a building thinner than twice the particle's distance from it) is left out. Ghost
// normal velocity is minus the particle's; tangential velocity is equal (slip) or opposite
// (no-slip); every other field is copied. Ghosts take part in the sums of fluid particles and are
// never integrated.
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

  // Copies depth, area, number density, bed, smoothing length and grad-h factor of each
  // ghost's fluid particle (after the depth summation has set them).
  static void copy_fields_to_ghosts(particles::SweParticles& p);

  // After a move from (old_x, old_y): reflects back every near-wall particle whose path
  // crossed a wall segment. Returns how many were reflected.
  std::size_t keep_inside(particles::SweParticles& p, std::span<const double> old_x,
                          std::span<const double> old_y) const;

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
  // The distance from x to the segment (its ends included).
  static double distance_to(const Line& line, std::array<double, 2> x);
  WallIndex index_;
  std::vector<Line> lines_;
  // True if the path from a particle at x to its ghost at g crosses a wall other than a and b,
  // those it is mirrored across: the ghost would stand beyond them.
  bool behind_another_wall(std::array<double, 2> x, std::array<double, 2> g, std::uint32_t a,
                           std::uint32_t b) const;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> near_wall_;  // (particle, segment)
  // add_ghosts' work per chunk of particles, kept so that a step allocates nothing new.
  struct PlacedGhost {
    std::uint32_t particle;
    std::array<double, 2> x, velocity;
  };
  struct Chunk {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> near_wall;
    std::vector<PlacedGhost> ghosts;
  };
  std::vector<Chunk> chunks_;
};

}  // namespace swemps::boundaries

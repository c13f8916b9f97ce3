#include "swemps/boundaries/ghost_walls.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::boundaries {

namespace {

using Vec = std::array<double, 2>;

double dot(Vec a, Vec b) { return a[0] * b[0] + a[1] * b[1]; }
double cross(Vec a, Vec b) { return a[0] * b[1] - a[1] * b[0]; }
Vec sub(Vec a, Vec b) { return {a[0] - b[0], a[1] - b[1]}; }

// Where along the path p0 -> p1 it meets the wall, as a fraction of the path in (0, 1], or a
// negative number when it does not. The wall counts `slack` (a fraction of its length) past
// each end: a path through the very point where two walls meet must hit one of them, which
// exact arithmetic does not promise.
double crossing_fraction(const WallSegment& wall, Vec p0, Vec p1, double slack) {
  const Vec d = sub(p1, p0);
  const Vec e = sub(wall.to, wall.from);
  const double denom = cross(d, e);
  if (denom == 0.0) return -1.0;  // parallel: cannot pass through
  const Vec w = sub(wall.from, p0);
  const double t = cross(w, e) / denom;  // along the path
  const double s = cross(w, d) / denom;  // along the wall
  return t > 0.0 && t <= 1.0 && s >= -slack && s <= 1.0 + slack ? t : -1.0;
}

// Fraction of a wall's length that counts past each end (crossing_fraction).
constexpr double kEndSlack = 1e-9;
// How far from half way (as a fraction of the path) a wall met on the way from a particle to
// its ghost is taken as met at the mirror point (behind_another_wall).
constexpr double kMirrorTolerance = 1e-9;
// Reflections followed per particle and step: a path into a corner bounces off both walls; more
// than this only in a corner sharper than any a scene should have, and then the particle goes
// back to where the step started, which was inside.
constexpr int kMaxReflections = 4;

}  // namespace

GhostWalls::GhostWalls(std::vector<WallSegment> segments) : index_(std::move(segments)) {
  lines_.reserve(index_.segments().size());
  for (const auto& s : index_.segments()) {
    const Vec d = sub(s.to, s.from);
    const double length = std::hypot(d[0], d[1]);
    if (!(length > 0.0) || !std::isfinite(length)) {
      throw std::invalid_argument("wall segment of zero or non-finite length");
    }
    const Vec t{d[0] / length, d[1] / length};
    lines_.push_back({s.from, t, Vec{-t[1], t[0]}, length});
  }
}

void GhostWalls::add_ghosts(particles::SweParticles& p, double reach) {
  reach_ = reach;
  own_reach_.assign(p.fluid_count(), reach);
  place_ghosts(p);
}

void GhostWalls::add_ghosts(particles::SweParticles& p, double reach,
                            std::span<const double> own_reach) {
  if (own_reach.size() != p.fluid_count())
    throw std::logic_error("add_ghosts: one reach a particle");
  reach_ = reach;
  own_reach_.assign(own_reach.begin(), own_reach.end());
  place_ghosts(p);
}

void GhostWalls::place_ghosts(particles::SweParticles& p) {
  if (p.ghost_count() != 0) throw std::logic_error("add_ghosts: ghosts already present");
  near_wall_.clear();
  near_wall_distance2_.clear();
  const std::size_t n = p.fluid_count();
  // Half-open [0, length) along the segment: where two collinear segments join, one ghost,
  // not two.
  const auto within_reach = [&](const Line& line, const Vec& x, double reach) {
    const Vec rel = sub(x, line.origin);
    const double along = dot(rel, line.tangent);
    return along >= 0.0 && along < line.length && std::abs(dot(rel, line.normal)) < reach;
  };
  // Each chunk of particles finds its walls and places its ghosts in parallel; the ghosts are
  // then appended chunk after chunk, so their order is particle order for any thread count.
  // Why in parallel: in a town nearly every particle is near a wall, and one thread placing
  // them was half of the urban case's run on two.
  chunks_.resize(reduction_chunks);
  for (auto& chunk : chunks_) {  // a short list runs as one chunk: the others hold old work
    chunk.near_wall.clear();
    chunk.near_wall_distance2.clear();
    chunk.ghosts.clear();
  }
  parallel_chunks(n, [&](std::size_t c, std::size_t begin, std::size_t end) {
    auto& out = chunks_[c];
    std::vector<std::uint32_t> touching, near;  // segments within reach; those mirrored across
    for (std::size_t i = begin; i < end; ++i) {
      const Vec x{p.x[i], p.y[i]};
      const double reach = reach_, reach2 = reach * reach;
      // Whether to place the ghost at g of the particle at x, `depth` from the walls a and b
      // it is mirrored across (see own_reach in the header).
      const auto wanted = [&](const Vec& g, std::uint32_t a, std::uint32_t b, double depth) {
        return depth < own_reach_[i] || !behind_another_wall(x, g, a, b);
      };
      // Reflections need every segment within reach, its ends included: a particle beyond
      // the end of both walls of a building's outer corner, in neither's half-open range,
      // could otherwise step round the corner's tip into the building (keep_inside tests
      // only these segments).
      touching.clear();
      index_.for_each_candidate(x[0] - reach, x[1] - reach, x[0] + reach, x[1] + reach,
                                [&](std::uint32_t s) {
                                  if (distance2_to(lines_[s], x) < reach2) touching.push_back(s);
                                });
      if (touching.empty()) continue;
      // A segment filed under several cells is met once per cell; ascending order keeps the
      // ghosts in the order a test of every segment gave.
      std::sort(touching.begin(), touching.end());
      touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
      const auto id = static_cast<std::uint32_t>(i);
      near.clear();
      for (std::uint32_t s : touching) {
        out.near_wall.emplace_back(id, s);
        out.near_wall_distance2.push_back(distance2_to(lines_[s], x));
        if (within_reach(lines_[s], x, reach)) near.push_back(s);
      }
      for (std::uint32_t s : near) {
        const Line& line = lines_[s];
        const double d = dot(sub(x, line.origin), line.normal);
        const double un = p.u[i] * line.normal[0] + p.v[i] * line.normal[1];
        const double ut = p.u[i] * line.tangent[0] + p.v[i] * line.tangent[1];
        const double ghost_ut = index_.segments()[s].condition == WallCondition::slip ? ut : -ut;
        const Vec g{x[0] - 2.0 * d * line.normal[0], x[1] - 2.0 * d * line.normal[1]};
        if (!wanted(g, s, s, std::abs(d))) continue;
        out.ghosts.push_back({id,
                              g,
                              {ghost_ut * line.tangent[0] - un * line.normal[0],
                               ghost_ut * line.tangent[1] - un * line.normal[1]},
                              {s, s}});
      }
      // Corner: mirror across both walls (a point reflection for a right angle), so the
      // quadrant behind the corner holds water too.
      for (std::size_t a = 0; a < near.size(); ++a) {
        for (std::size_t b = a + 1; b < near.size(); ++b) {
          const Line& la = lines_[near[a]];
          const Line& lb = lines_[near[b]];
          if (std::abs(cross(la.tangent, lb.tangent)) < 1e-9) continue;  // parallel walls
          Vec g = x;
          Vec vel{p.u[i], p.v[i]};
          for (const auto* line : {&la, &lb}) {
            const double d = dot(sub(g, line->origin), line->normal);
            g = {g[0] - 2.0 * d * line->normal[0], g[1] - 2.0 * d * line->normal[1]};
            const double un = dot(vel, line->normal);
            vel = {vel[0] - 2.0 * un * line->normal[0], vel[1] - 2.0 * un * line->normal[1]};
          }
          const double depth = std::max(std::abs(dot(sub(x, la.origin), la.normal)),
                                        std::abs(dot(sub(x, lb.origin), lb.normal)));
          if (!wanted(g, near[a], near[b], depth)) continue;
          out.ghosts.push_back({id, g, vel, {near[a], near[b]}});
        }
      }
    }
  });
  mirrored_across_.clear();
  for (const auto& chunk : chunks_) {
    near_wall_.insert(near_wall_.end(), chunk.near_wall.begin(), chunk.near_wall.end());
    near_wall_distance2_.insert(near_wall_distance2_.end(), chunk.near_wall_distance2.begin(),
                                chunk.near_wall_distance2.end());
    for (const PlacedGhost& g : chunk.ghosts) {
      p.add_ghost(g.particle, g.x[0], g.x[1], g.velocity[0], g.velocity[1]);
      mirrored_across_.push_back(g.mirrored_across);
    }
  }
  near_wall_start_.assign(n + 1, 0);
  for (const auto& [i, s] : near_wall_) ++near_wall_start_[i + 1];
  for (std::size_t i = 0; i < n; ++i) near_wall_start_[i + 1] += near_wall_start_[i];
}

// Why: the kernel of a particle by a wall reaches past it, over the water on the other side
// when the wall is a single line or a building thinner than the support (about 2.4 spacings).
// Summing that water, a particle in 0.3 m of water beside a 1 m basin read 0.65 m and was
// driven from the wall at 0.5 m/s in a second (tests/boundaries/test_ghost_walls.cpp); a ghost
// mirrored onto a particle on the far side of a line wall summed a depth of 10^14 m.
std::size_t GhostWalls::hide_pairs_across_walls(const particles::SweParticles& p,
                                                neighbors::NeighborList& nl) {
  const std::size_t n = nl.row_count();
  kept_.resize(n);
  parallel_for(
      n, [&](std::size_t i) { kept_[i] = hide_in_row(p, nl, static_cast<std::uint32_t>(i)); });
  return close_rows(nl);
}

std::size_t GhostWalls::hide_pairs_across_walls(const particles::SweParticles& p,
                                                neighbors::NeighborList& nl,
                                                std::span<const std::uint32_t> rows) {
  const std::size_t n = nl.row_count();
  kept_.resize(n);
  for (std::size_t i = 0; i < n; ++i) kept_[i] = nl.offsets[i + 1] - nl.offsets[i];
  parallel_for(rows.size(), [&](std::size_t r) { kept_[rows[r]] = hide_in_row(p, nl, rows[r]); });
  return close_rows(nl);
}

std::uint32_t GhostWalls::hide_in_row(const particles::SweParticles& p, neighbors::NeighborList& nl,
                                      std::uint32_t i) const {
  const std::uint32_t begin = nl.offsets[i], end = nl.offsets[i + 1];
  const std::uint32_t walls_begin = near_wall_start_[i], walls_end = near_wall_start_[i + 1];
  const auto fluid = static_cast<std::uint32_t>(p.fluid_count());
  // A point nearer than the reach is seen unless one of i's walls is in the way: a wall
  // between them crosses their path within that distance of i. Only a ghost's particle may lie
  // farther, behind walls that are not i's: the ghost's own walls, then the index, find those.
  if (walls_begin == walls_end && std::all_of(nl.index.begin() + begin, nl.index.begin() + end,
                                              [&](std::uint32_t j) { return j < fluid; })) {
    return end - begin;
  }
  const Vec xi{p.x[i], p.y[i]};
  // Which side of each of its walls' lines i stands on: a particle strictly on the same side
  // of a line cannot be behind that wall, and most of a row's are.
  constexpr std::uint32_t kSidesKept = 32;
  std::array<double, kSidesKept> side{};
  const std::uint32_t sides = std::min(walls_end - walls_begin, kSidesKept);
  for (std::uint32_t w = 0; w < sides; ++w) {
    const Line& line = lines_[near_wall_[walls_begin + w].second];
    side[w] = dot(sub(xi, line.origin), line.normal);
  }
  const double reach2 = reach_ * reach_;
  const auto wall_ghosts = static_cast<std::uint32_t>(mirrored_across_.size());
  std::uint32_t kept = begin;
  // A particle's ghosts follow one another in a row (they are numbered together): the first
  // one's answer holds for the others.
  std::uint32_t last_source = i;
  bool last_hidden = false;
  for (std::uint32_t e = begin; e < end; ++e) {
    const std::uint32_t j = nl.index[e];
    const std::uint32_t k = p.source[j];
    bool hidden = false;
    if (k == last_source) {
      hidden = last_hidden;
    } else {
      // The path runs from the lower index to the higher, so that both rows of a pair test
      // the same path and agree.
      const Vec xk{p.x[k], p.y[k]};
      const Vec from = i < k ? xi : xk, to = i < k ? xk : xi;
      const Vec d = sub(xk, xi);
      const double distance2 = dot(d, d);
      if (j < fluid || distance2 < reach2) {
        for (std::uint32_t w = walls_begin; w < walls_end && !hidden; ++w) {
          // A wall the path crosses is no farther from i than k is. In a town most of i's
          // walls within the widest kernel of the scene lie beyond its neighbours.
          if (near_wall_distance2_[w] > distance2) continue;
          const std::uint32_t s = near_wall_[w].second;
          if (w - walls_begin < sides) {
            const Line& line = lines_[s];
            if (side[w - walls_begin] * dot(sub(xk, line.origin), line.normal) > 0.0) continue;
          }
          hidden = crosses(index_.segments()[s], from, to);
        }
      } else {
        const bool wall_ghost = j - fluid < wall_ghosts;
        if (wall_ghost) {
          for (const std::uint32_t s : mirrored_across_[j - fluid])
            hidden = hidden || crosses(index_.segments()[s], from, to);
        }
        if (!hidden) hidden = index_.crosses_any(from, to);
      }
      last_source = k;
      last_hidden = hidden;
    }
    if (!hidden) nl.index[kept++] = j;
  }
  return kept - begin;
}

std::size_t GhostWalls::close_rows(neighbors::NeighborList& nl) {
  const std::size_t n = nl.row_count();
  std::size_t hidden = 0;
  for (std::size_t i = 0; i < n; ++i) hidden += nl.offsets[i + 1] - nl.offsets[i] - kept_[i];
  if (hidden == 0) return 0;
  // Each row moves down by what the rows before it lost: never onto points not yet moved.
  std::uint32_t write = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t begin = nl.offsets[i];
    nl.offsets[i] = write;
    std::copy(nl.index.begin() + begin, nl.index.begin() + begin + kept_[i],
              nl.index.begin() + write);
    write += kept_[i];
  }
  nl.offsets[n] = write;
  nl.index.resize(write);
  return hidden;
}

// The path from a particle to its ghost meets the walls it is mirrored across half way (a
// point reflection through a right-angled corner also half way); another wall met there (a
// neighbour joined at that very point) does not count.
bool GhostWalls::behind_another_wall(Vec x, Vec g, std::uint32_t a, std::uint32_t b) const {
  bool behind = false;
  index_.for_each_candidate(std::min(x[0], g[0]), std::min(x[1], g[1]), std::max(x[0], g[0]),
                            std::max(x[1], g[1]), [&](std::uint32_t s) {
                              if (behind || s == a || s == b) return;
                              const double t = crossing_fraction(index_.segments()[s], x, g, 0.0);
                              behind = t >= 0.0 && std::abs(t - 0.5) > kMirrorTolerance;
                            });
  return behind;
}

double GhostWalls::distance2_to(const Line& line, Vec x) {
  const Vec rel = sub(x, line.origin);
  const double along = std::clamp(dot(rel, line.tangent), 0.0, line.length);
  const Vec off{rel[0] - along * line.tangent[0], rel[1] - along * line.tangent[1]};
  return dot(off, off);
}

void GhostWalls::copy_fields_to_ghosts(particles::SweParticles& p) {
  for (std::size_t k = p.fluid_count(); k < p.size(); ++k) {
    const std::uint32_t i = p.source[k];
    p.depth[k] = p.depth[i];
    p.area[k] = p.area[i];
    p.number_density[k] = p.number_density[i];
    p.bed[k] = p.bed[i];
    p.smoothing_length[k] = p.smoothing_length[i];
    p.omega[k] = p.omega[i];
  }
}

bool GhostWalls::crosses(const WallSegment& wall, Vec p0, Vec p1) {
  // Proper or touching intersection of segment p0-p1 with the wall; ending exactly on the
  // wall counts as crossing, so no particle is ever left on a wall line.
  return crossing_fraction(wall, p0, p1, 0.0) >= 0.0;
}

bool GhostWalls::crosses_any(std::span<const WallSegment> walls, Vec p0, Vec p1) {
  return std::any_of(walls.begin(), walls.end(),
                     [&](const WallSegment& wall) { return crosses(wall, p0, p1); });
}

std::size_t GhostWalls::keep_inside(particles::SweParticles& p, std::span<const double> old_x,
                                    std::span<const double> old_y) {
  std::size_t reflected = 0;
  const std::size_t n = std::min({old_x.size(), old_y.size(), p.fluid_count()});
  // A path shorter than the reach meets only walls within reach of its start: its particle's
  // near-wall list (near_wall_ holds each particle's segments together). A longer one, which
  // the time step (eq 13) makes rare, asks the index for every wall within its length.
  const auto short_path = [&](std::size_t i) {
    const double dx = p.x[i] - old_x[i], dy = p.y[i] - old_y[i];
    return dx * dx + dy * dy < reach_ * reach_;
  };
  for (std::size_t k = 0; k < near_wall_.size();) {
    const std::uint32_t i = near_wall_[k].first;
    walls_met_.clear();
    for (; k < near_wall_.size() && near_wall_[k].first == i; ++k)
      walls_met_.push_back(near_wall_[k].second);
    if (i < n && short_path(i) && bounce_inside(p, i, {old_x[i], old_y[i]}, walls_met_))
      ++reflected;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (short_path(i)) continue;
    const double length = std::hypot(p.x[i] - old_x[i], p.y[i] - old_y[i]);
    walls_met_.clear();
    index_.for_each_candidate(old_x[i] - length, old_y[i] - length, old_x[i] + length,
                              old_y[i] + length, [&](std::uint32_t s) { walls_met_.push_back(s); });
    std::sort(walls_met_.begin(), walls_met_.end());
    walls_met_.erase(std::unique(walls_met_.begin(), walls_met_.end()), walls_met_.end());
    if (bounce_inside(p, i, {old_x[i], old_y[i]}, walls_met_)) ++reflected;
  }
  return reflected;
}

bool GhostWalls::bounce_inside(particles::SweParticles& p, std::size_t i, Vec start,
                               std::span<const std::uint32_t> walls) const {
  // The path is followed like a billiard ball: reflect off the first wall it meets, then
  // follow the reflected rest of the path, which may meet another wall. Reflecting off each
  // crossed wall in turn, in the order of the list, is not enough: a path past a corner that
  // first crosses the second wall's line, once reflected, can end behind the first.
  const Vec old = start;
  Vec end{p.x[i], p.y[i]};
  std::size_t last_wall = walls.size();  // the wall the path now starts on, if any
  bool inside = false;
  for (int bounce = 0; bounce < kMaxReflections && !inside; ++bounce) {
    double first = 2.0;
    std::size_t hit = walls.size();
    for (std::size_t g = 0; g < walls.size(); ++g) {
      if (g == last_wall) continue;
      const double t = crossing_fraction(index_.segments()[walls[g]], start, end, kEndSlack);
      if (t >= 0.0 && t < first) {
        first = t;
        hit = g;
      }
    }
    if (hit == walls.size()) {
      inside = true;
      break;
    }
    const Line& line = lines_[walls[hit]];
    const double side = dot(sub(start, line.origin), line.normal);
    const double d = dot(sub(end, line.origin), line.normal);
    // Mirror the overshoot back to the starting side; a particle ending on the line is pushed
    // off it by a hair so that it cannot sit on the wall.
    const double sign = side >= 0.0 ? 1.0 : -1.0;
    const double back = std::max(-d * sign, 1e-9 * line.length);  // behind the wall, >= 0
    const Vec on_wall{start[0] + first * (end[0] - start[0]),
                      start[1] + first * (end[1] - start[1])};
    end = {end[0] + (sign * back - d) * line.normal[0],
           end[1] + (sign * back - d) * line.normal[1]};
    start = on_wall;
    last_wall = hit;
    const double un = p.u[i] * line.normal[0] + p.v[i] * line.normal[1];
    if (un * sign < 0.0) {  // moving into the wall: bounce
      p.u[i] -= 2.0 * un * line.normal[0];
      p.v[i] -= 2.0 * un * line.normal[1];
    }
  }
  if (!inside) end = old;  // see kMaxReflections
  if (end[0] == p.x[i] && end[1] == p.y[i]) return false;
  p.x[i] = end[0];
  p.y[i] = end[1];
  return true;
}

}  // namespace swemps::boundaries

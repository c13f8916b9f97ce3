#pragma once
// Pathlines (docs/provenance.md, "Pathlines"): the tracks of chosen particles over a run, as
// lists of vertices (x, y, t). A particle keeps its identity from step to step, so its track
// is where its water went: no velocity field is integrated after the fact, and no map cell
// blurs it. The particles carry the index of their line (SweParticles::pathline) through
// sorts, splits (the first daughter keeps it) and merges (the particle kept takes it over);
// a line ends where its particle leaves the domain or merges into another followed particle
// (whose line its water goes on along).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "swemps/particles/swe_particles.hpp"
#include "swemps/terrain/footprints.hpp"

namespace swemps::maps {

// Which particles to follow: those that pass every filter given, at most `count` of them.
struct PathlineChoice {
  std::size_t count = 100;
  // Only particles at least half of whose water came from this provenance label.
  std::optional<std::uint32_t> label;
  const terrain::Footprints* area = nullptr;  // only particles inside; null: anywhere
};

// The fluid particles chosen, in index order: all that pass the filters when they are at most
// `count`, otherwise `count` of them spread evenly over the list (the k-th of them at
// floor(k m / count) of the m that pass). The particles are sorted by cell, so an even spread
// over the list is one over the water they cover.
std::vector<std::uint32_t> choose_pathline_particles(const particles::SweParticles& p,
                                                     const PathlineChoice& choice);

struct Pathline {
  std::vector<double> x, y, t;  // the vertices: m, m, s
  // The particle's largest share of water when it was chosen, where the particles carry
  // provenance labels.
  std::optional<std::uint32_t> label;
  // How the line ends: its particle still in the domain at the last vertex, gone out of it,
  // or merged into another followed particle.
  enum class Fate { in_domain, left, merged };
  Fate fate = Fate::in_domain;
  // Merged: the line whose particle took its water in, along which that water goes on.
  std::optional<std::uint32_t> merged_into;
};

class PathlineRecorder {
 public:
  // One line a chosen particle, line k for chosen[k], each starting where its particle is at
  // time_s. The caller has each particle carry its line (swe::Simulation::start_pathline).
  void start(const particles::SweParticles& p, std::span<const std::uint32_t> chosen,
             double time_s);
  bool started() const { return started_; }
  // A vertex for every line still followed, where its particle is at time_s: at most once a
  // time, and only after the last vertex.
  void record(const particles::SweParticles& p, double time_s);
  // The lines whose particles went in the step that ended at time_s: a last vertex where each
  // particle was as it went.
  void end(std::span<const particles::PathlineEnd> ends, double time_s);

  const std::vector<Pathline>& lines() const { return lines_; }
  std::size_t vertices() const;

  // Everything above as numbers, for a checkpoint; restore() refuses a record that does not
  // fit with std::invalid_argument.
  std::vector<double> state() const;
  void restore(std::span<const double> state);

 private:
  std::vector<Pathline> lines_;
  bool started_ = false;
  double last_time_s_ = 0.0;
};

}  // namespace swemps::maps

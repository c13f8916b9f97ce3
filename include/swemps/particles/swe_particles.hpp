#pragma once
// Shallow-water particles in structure-of-arrays form. Fluid particles come first
// (indices [0, fluid_count())); ghost particles of the walls are appended behind them for
// one step and dropped before the next, so every neighbour loop sees one contiguous set.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace swemps::particles {

// Where a new particle's water comes from (docs/provenance.md): the label of its source (a
// water body, an inflow, a sea boundary, rain) and when it entered the domain. Kept only by
// particles that track provenance (SweParticles::track_provenance); ignored otherwise.
struct Origin {
  std::uint32_t label = 0;
  double entry_time_s = 0.0;
};

// A pathline (docs/provenance.md, "Pathlines") that ended in a step: its particle was removed
// (it left the domain) or merged into another particle that already carried a pathline, whose
// line its water goes on along (`into`). Where the particle was when it went.
struct PathlineEnd {
  enum class Cause { left, merged };
  std::int32_t pathline = 0;
  double x = 0.0, y = 0.0;
  Cause cause = Cause::left;
  std::int32_t into = -1;  // merged: the line it joined
};

// The pathline index of a particle that carries none.
inline constexpr std::int32_t kNoPathline = -1;

class SweParticles {
 public:
  // Per-particle fields. Units: m, m/s, m^3, m, m^2.
  std::vector<double> x, y;            // horizontal position
  std::vector<double> u, v;            // depth-averaged velocity
  std::vector<double> volume;          // V, conserved
  std::vector<double> depth;           // h, eq 7
  std::vector<double> area;            // A = V / h
  std::vector<double> initial_area;    // A_0, the area a particle was created with
  std::vector<double> bed;             // z_b at the particle
  std::vector<double> number_density;  // n, eq 5
  // The particle's own kernel radius H (m; support 2 H): r_e of eq 9, the same for all under
  // the seed scheme, kappa sqrt(A) under the conservative scheme. 0 until the first summation.
  std::vector<double> smoothing_length;
  // The grad-h factor Omega = d(summed depth)/d(depth) of the conservative scheme (1 when the
  // radius does not follow the depth; docs/method.md, "The conservative scheme").
  std::vector<double> omega;
  // For ghosts: the fluid particle mirrored; for fluid particles: its own index.
  std::vector<std::uint32_t> source;

  // Provenance (docs/provenance.md), for fluid particles only and empty unless tracked: the
  // share of each particle's volume that came from each of label_count() labels (particle i's
  // shares are label_share[i * label_count(), (i + 1) * label_count())), and the volume-weighted
  // mean time its water entered the domain (s). A share is a fraction, not a volume, so that
  // every change of a particle's volume that is not a mixing of water (the volume balance at
  // rest, losses) leaves it alone, and splitting copies it.
  std::vector<double> label_share;
  std::vector<double> entry_time;

  // Pathlines (docs/provenance.md), for fluid particles only and empty unless tracked: the
  // index of the pathline each particle carries, kNoPathline for most. The pathlines that
  // ended since the owner last took them (remove() appends them) are in pathline_ends.
  std::vector<std::int32_t> pathline;
  std::vector<PathlineEnd> pathline_ends;

  std::size_t size() const { return x.size(); }
  std::size_t fluid_count() const { return fluid_count_; }
  std::size_t ghost_count() const { return size() - fluid_count_; }

  // Appends a fluid particle (only while there are no ghosts); `origin` is kept when provenance
  // is tracked.
  void add_fluid(double px, double py, double pu, double pv, double vol, double h, double a0,
                 double zb, Origin origin = {});
  // Appends a ghost copying every field of fluid particle `from`, then overriding position
  // and velocity.
  void add_ghost(std::uint32_t from, double px, double py, double pu, double pv);
  void drop_ghosts();
  // Ghosts [fluid_count(), mirror_end()) are mirror images of their particle across a wall;
  // those added after close_mirror_images() (until the ghosts are dropped) stand for water
  // beyond an open boundary and only borrow their particle's radius. The maps spread a
  // particle's water over its mirror images alone.
  void close_mirror_images() { mirrors_closed_ = true; }
  std::size_t mirror_end() const { return mirror_end_; }

  // Reorders fluid particles so that new index k holds old index order[k] (no ghosts allowed).
  void reorder(std::span<const std::uint32_t> order);
  // Removes the fluid particles flagged true (no ghosts allowed); keeps the order of the rest.
  // A removed particle's pathline ends there, as having left the domain.
  void remove(std::span<const std::uint8_t> flagged);

  double total_fluid_volume() const;  // summed in index order: reproducible

  // Provenance. track_provenance() starts keeping `labels` shares (0: none) and, with `ages`,
  // entry times; only while there are no particles. Each is then carried through add_fluid,
  // reorder and remove, and mixed by the calls below; untracked, they cost nothing.
  void track_provenance(std::size_t labels, bool ages);
  std::size_t label_count() const { return label_count_; }
  bool tracks_ages() const { return tracks_ages_; }
  // Fluid particle `to` takes the shares and entry time of `from` (a daughter of a split).
  void copy_provenance(std::size_t from, std::size_t to);
  // Fluid particle `a`, of volume `volume_a`, takes in the water of `b`, of volume `volume_b`:
  // shares and entry times mixed by volume, so that each label's volume is kept (a merge).
  // Call before the volumes change.
  void mix_provenance(std::size_t a, double volume_a, std::size_t b, double volume_b);
  // `added_m3` of water from `origin` joins fluid particle i, of volume `volume_m3` before it
  // (rain falling on water). Call before the volume changes.
  void mix_in(std::size_t i, double volume_m3, double added_m3, Origin origin);
  // The fluid particles' volume of label k, summed in index order.
  double label_volume(std::size_t k) const;

  // Pathlines. track_pathlines() starts keeping each particle's pathline index, only while
  // there are no particles; new particles carry none (a split's second daughter included:
  // the first keeps its parent's index, and its place). Untracked, they cost nothing.
  void track_pathlines();
  bool tracks_pathlines() const { return tracks_pathlines_; }
  // Particle `kept` takes in particle `absorbed` (a merge, before `absorbed` is removed): it
  // takes over the pathline of `absorbed` when it carries none of its own, so that a line
  // goes on with the water it followed; with two, the absorbed one's ends at the merge, where
  // `absorbed` stands, as joining the other (pathline_ends).
  void hand_over_pathline(std::size_t absorbed, std::size_t kept);

 private:
  void resize(std::size_t n);
  std::size_t fluid_count_ = 0;
  std::size_t mirror_end_ = 0;
  std::size_t label_count_ = 0;
  bool tracks_ages_ = false;
  bool tracks_pathlines_ = false;
  bool mirrors_closed_ = false;
};

}  // namespace swemps::particles

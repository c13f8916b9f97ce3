#pragma once
// Shallow-water particles in structure-of-arrays form. Fluid particles come first
// (indices [0, fluid_count())); ghost particles of the walls are appended behind them for
// one step and dropped before the next, so every neighbour loop sees one contiguous set.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace swemps::particles {

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

  std::size_t size() const { return x.size(); }
  std::size_t fluid_count() const { return fluid_count_; }
  std::size_t ghost_count() const { return size() - fluid_count_; }

  // Appends a fluid particle (only while there are no ghosts).
  void add_fluid(double px, double py, double pu, double pv, double vol, double h, double a0,
                 double zb);
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
  void remove(std::span<const std::uint8_t> flagged);

  double total_fluid_volume() const;  // summed in index order: reproducible

 private:
  void resize(std::size_t n);
  std::size_t fluid_count_ = 0;
  std::size_t mirror_end_ = 0;
  bool mirrors_closed_ = false;
};

}  // namespace swemps::particles

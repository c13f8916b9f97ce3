#pragma once
// The discrete operators of the shallow-water MPS method (method.md section 1). Each loops
// over fluid particles [0, fluid_count()) and their neighbour rows; ghosts contribute as
// neighbours. Every particle's result depends only on its own row, in a fixed order, so
// results are the same for any number of threads.

#include <array>
#include <span>
#include <vector>

#include "swemps/kernels/spiky.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/particle_kernel.hpp"
#include "swemps/swe/settings.hpp"

namespace swemps::swe {

using Kernel = kernels::Spiky<2>;

// eq 9: one influence radius for all particles, from the largest fluid area. Two guards
// (docs/method.md, "The influence radius"): a particle whose area is `isolated_area`, the
// area 1 / w(0) that eq 7 gives a particle with no neighbour, does not count, because that
// area is made by the kernel, not by the water; and each area counts at most
// max_area_ratio times the particle's creation area A_0. When every particle is isolated,
// the bounded areas of all of them are used.
double influence_radius(const particles::SweParticles& p, double alpha_e, double max_area_ratio,
                        double isolated_area);

// eq 7: h_i = sum_j V_j w_ij including the self term; then A_i = V_i / h_i.
void sum_depth(particles::SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w);

// eq 5: n_i = sum_{j != i} (A_j / A_i) w_ij.
void sum_number_density(particles::SweParticles& p, const neighbors::NeighborList& nl,
                        const ParticleKernel& w);

// eq 5 at one fluid particle, with the pair weights of any scheme's kernel (for the seed
// scheme, eq 8 at the common radius).
double number_density_at(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                         const ParticleKernel& w, std::size_t i);

// eq 6 at one fluid particle for any per-particle field phi (indexed like the particles,
// ghosts included), given that particle's number density n_i (eq 5), with the pair weights of
// any scheme's kernel.
std::array<double, 2> mps_gradient_at(const particles::SweParticles& p,
                                      const neighbors::NeighborList& nl, const ParticleKernel& w,
                                      std::size_t i, std::span<const double> phi,
                                      double number_density);

// Gradient of the depth h at every fluid particle, by the chosen variant (see Settings). The
// mps variant also stores eq 5's number density in p.number_density, which it sums on the way.
void depth_gradient(GradientVariant variant, particles::SweParticles& p,
                    const neighbors::NeighborList& nl, const Kernel& w, std::span<double> grad_x,
                    std::span<double> grad_y);

// eq 13: dt = CFL min_i sqrt(A_i) / (sqrt(g h_i) + |u_i|). Also reports which particle
// limits the step (for error messages).
struct TimeStepLimit {
  double dt_s;
  std::size_t particle;
};
TimeStepLimit stable_time_step(const particles::SweParticles& p, double gravity_m_s2, double cfl);
// Particle i's own step by eq 13 (the minimum over the fluid particles is stable_time_step()).
double particle_time_step(const particles::SweParticles& p, std::size_t i, double gravity_m_s2,
                          double cfl);

// Depth at arbitrary points, h(x) = sum_j V_j W(|x - x_j|, h_j), over the fluid particles,
// each with its own radius: the summation of eq 7 (and of the conservative scheme), so the
// field integrates to the particles' volume.
struct RegularGrid {
  double x0, y0, dx, dy;  // first cell centre and spacing, m
  std::size_t nx, ny;
};
std::vector<double> depth_on_grid(const particles::SweParticles& p, const ParticleKernel& w,
                                  const RegularGrid& grid);

// Depth and depth-averaged velocity at a point: h from the summation above, and
// u = sum_j V_j u_j w / sum_j V_j w, the discharge of the summation divided by its depth, so
// that h u carries the particles' momentum. u and v are NaN where h = 0 (no particle in reach).
struct PointFields {
  double depth_m = 0.0, u_m_s = 0.0, v_m_s = 0.0;
};
PointFields fields_at(const particles::SweParticles& p, const ParticleKernel& w, double x_m,
                      double y_m);

// The same at every cell centre of a grid; ny * nx values each, x fastest.
struct GridFields {
  std::vector<double> depth, u, v;
};
GridFields fields_on_grid(const particles::SweParticles& p, const ParticleKernel& w,
                          const RegularGrid& grid);

}  // namespace swemps::swe

#pragma once
// Wall and dummy pressures extrapolated from the fluid (Adami, Hu & Adams 2012, eq. 27, for a
// wall at rest), and the pressure Poisson equation with them eliminated (BoundaryPressure::
// extrapolated in settings.hpp).
//
// A boundary particle b (wall or dummy) takes
//   p_b = sum_k alpha_bk p_k + c_b,   alpha_bk = w_bk / sum_k w_bk,
//   c_b = rho g sum_k alpha_bk (z_k - z_b)
// over its fluid neighbours k (free-surface ones included, with p = 0): the kernel mean of
// the fluid pressures carried to b along the hydrostatic gradient. A linear hydrostatic
// field is reproduced exactly at every wall and dummy particle, whatever side of the
// particle the fluid lies on, so the water next to a wall feels the same pressure
// gradient as the water far from it.
//
// Substituted into the fluid rows of the Poisson equation (poisson.hpp), the coupling of
// fluid particles i and k through b is w_ib w_bk / sum_k w_bk, symmetric in i and k, and the
// row stays weakly diagonally dominant (sum_k alpha_bk = 1): the matrix is still symmetric
// positive definite and conjugate gradients still apply. c_b moves to the right-hand side.

#include <cstdint>
#include <span>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/poisson.hpp"

namespace swemps::ns {

// For boundary particle b (index fluid_count + m), its fluid neighbours fluid[offsets[m]..
// offsets[m + 1]) with weights alpha, and c_b = constant[m].
struct BoundaryExtrapolation {
  std::size_t fluid_count = 0;
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> fluid;
  std::vector<double> alpha;
  std::vector<double> constant;
};

// Builds the extrapolation from the fluid rows of the neighbour list (the relation is
// symmetric, so boundary rows are not needed). `vertical` is each particle's last
// coordinate; `rho_g` is rho times gravity.
void build_boundary_extrapolation(const neighbors::NeighborList& pairs,
                                  std::span<const double> pair_weight, std::size_t fluid_count,
                                  std::size_t particle_count, std::span<const double> vertical,
                                  double rho_g, BoundaryExtrapolation& out);

// The Poisson system over the marked fluid particles (unknown[i], i < fluid_count), boundary
// neighbours eliminated through `boundary`; otherwise as assemble_poisson. Row i is
// laplacian_factor sum_j c_ij (p_j - p_i) = b_i over the pairs whose kernel weight is
// positive, with c_ij the pair's `coefficient`, or its kernel weight where none are given (the
// MPS Laplacian). The least-squares operators give theirs with factor 1; they may be
// negative, and then the matrix is not symmetric.
void assemble_poisson_extrapolated(const neighbors::NeighborList& pairs,
                                   std::span<const double> pair_weight,
                                   std::span<const char> unknown, std::span<const double> source,
                                   const BoundaryExtrapolation& boundary, double laplacian_factor,
                                   PoissonSystem& out, std::span<const double> coefficient = {});

// Sets p_b for every boundary particle from the fluid pressures in `pressure` (0 where a
// boundary particle has no fluid neighbour).
void extrapolate_boundary_pressure(const BoundaryExtrapolation& boundary,
                                   std::span<double> pressure);

}  // namespace swemps::ns

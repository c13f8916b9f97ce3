#pragma once
// Least-squares MPS operators (LSMPS, Tamai & Koshizuka 2014, "type A"): at each particle i a
// polynomial is fitted to the differences f_j - f_i over its neighbours j, weighted by the
// kernel, and the gradient and Laplacian are the fitted polynomial's. Unlike the standard MPS
// operators (method.md section 3), whose lattice constants lambda and n0 hold only on the
// lattice the particles start on, the fit is exact for every polynomial of its degree
// whatever the neighbours' arrangement, beside walls and the surface included.
//
// With offsets x_ij = x_j - x_i scaled by r_s (the spacing), the basis q(x) holds the
// monomials of degree 1 and 2: 2D [x, z, x^2, x z, z^2] (5 terms), 3D [x, y, z, x^2, x y,
// x z, y^2, y z, z^2] (9 terms). The moment matrix is M_i = sum_j w_ij q_ij q_ij^T, and the
// coefficients a = M_i^-1 sum_j w_ij q_ij (f_j - f_i) are the Taylor coefficients r_s f_d and
// r_s^2 f_dd / 2 (the mixed terms r_s^2 f_de). So each derivative is a weighted sum over
// the neighbours,
//   grad f_i = sum_j G_ij (f_j - f_i),   lap f_i = sum_j L_ij (f_j - f_i),
//   G_ij,d = e_d^T M_i^-1 q_ij w_ij / r_s,   L_ij = 2 sum_d e_dd^T M_i^-1 q_ij w_ij / r_s^2,
// and the weights of a particle are computed once a step and serve the Poisson equation's
// rows (L) and the pressure gradient (G).
//
// Order: exact for quadratics, so on an irregular arrangement the gradient's error falls as
// l0^2 and the Laplacian's as l0 (its error is the cubic term over r^2); on a lattice, or
// any arrangement symmetric about i, the cubic terms cancel and the Laplacian is second
// order too (tests/ns/test_least_squares.cpp measures both).
//
// Stabilisation: a neighbourhood that does not span the quadratics (neighbours on one line,
// a splash droplet's handful) makes M_i singular. Such a particle is not fitted to degree 2
// (fit_quadratic() returns false, judged by the pivots of M_i's L D L^T factors) and the caller falls back to a
// lower-order operator (the corrected gradient, mps_operators.hpp, and the MPS Laplacian).
// What the pressure operators do with the fits, and where they do not
// trust them (the free surface), is in least_squares_operators.hpp.

#include <array>
#include <span>

namespace swemps::ns {

template <int Dim>
constexpr int quadratic_terms = Dim == 2 ? 5 : 9;

// One neighbour of the particle being fitted: its offset x_j - x_i and its kernel weight.
template <int Dim>
struct FitNeighbour {
  std::array<double, Dim> offset;
  double weight;
};

// The per-neighbour weights of one particle's fit.
template <int Dim>
struct FitWeights {
  std::array<double, Dim> gradient;  // G_ij
  double laplacian;                  // L_ij
};

// A fit is refused when a pivot of the L D L^T factorisation of its moment matrix is below this
// fraction of its own diagonal entry: one basis term is then all but a combination of the
// others over these neighbours. A particle on a flat surface (neighbours below and beside it
// only) is still fitted; a line of neighbours is not.
inline constexpr double least_squares_min_pivot = 1e-4;

// Fits particle i to degree 2 over `neighbours` (offsets in metres, scale r_s = `scale_m`)
// and writes one FitWeights per neighbour into `out` (same length). Returns false and leaves
// `out` unspecified when the moment matrix is near singular (fewer neighbours than terms, or
// neighbours that do not span them; least_squares_min_pivot).
template <int Dim>
bool fit_quadratic(std::span<const FitNeighbour<Dim>> neighbours, double scale_m,
                   std::span<FitWeights<Dim>> out);

extern template bool fit_quadratic<2>(std::span<const FitNeighbour<2>>, double,
                                      std::span<FitWeights<2>>);
extern template bool fit_quadratic<3>(std::span<const FitNeighbour<3>>, double,
                                      std::span<FitWeights<3>>);

}  // namespace swemps::ns

#pragma once
// The least-squares MPS pressure operators (LSMPS; Tamai & Koshizuka 2014): the Poisson
// equation's Laplacian and the pressure gradient from each fluid particle's quadratic fit
// (least_squares.hpp), with the walls' pressures extrapolated from the fluid
// (boundary_pressure.hpp) and eliminated, as in the well-balanced MPS scheme.
//
// Row i of the Poisson equation is sum_j L_ij (p_j - p_i) = b_i over every neighbour: fluid
// unknowns, fluid on the free surface (p = 0), and walls and dummies through p_b = sum_k
// alpha_bk p_k + c_b. The fit is exact for quadratics, so a hydrostatic (linear) pressure has
// a zero Laplacian and the exact gradient rho g beside walls and under the surface alike:
// water at rest on a lattice is a discrete equilibrium. L_ij is not symmetric in i and j
// and may be negative, so the system is solved by BiCGSTAB (poisson.hpp).
//
// The gradient is sum_j G_ij (p_j - p_i), plus, with Settings::gradient corrected-repulsive,
// the standard MPS repulsion (d / n0) sum_j (p_i - p_min,i) x_ij w_ij / r_ij^2 over the pairs
// closer than the repulsion distance: none on a lattice, a push apart where particles crowd.
//
// Where the fits are not trusted, and why (measured, docs/ns-dam-break.md "Least-squares
// operators"):
//  - The particles on the free surface (p = 0) take the first-order fit for their gradient
//    (the corrected gradient), every other fluid particle the quadratic one. With the
//    quadratic gradient on the surface too, water at rest in the 2D tank grew a surface mode
//    from about 2 s (e-fold 0.3 s) and broke up by 4 s; with the first-order gradient on every
//    particle within the support of the surface, the 2D tank held, but in 3D a mode grew two
//    rows under the surface from about 1 s, and the 2D dam break's front moved 0.015 a further
//    from the experiment.
//  - A Poisson row takes the fit's Laplacian only when its negative weights sum to at most
//    least_squares_max_negative_share of its positive ones, else the MPS Laplacian
//    (2d / (lambda n0)) w_ij. A full neighbourhood has none (every weight of a lattice at 2.1
//    l0 is positive); a sparse, one-sided one (a splash) has large ones of both signs, and with
//    those rows the 2D dam break's incomplete LU met a zero pivot at T = 1.8.
//  - A particle whose neighbourhood does not fix a quadratic at all (fit_quadratic() refuses)
//    takes the first-order fit for its gradient (then the standard sum) and the MPS Laplacian.

#include <vector>

#include "swemps/ns/least_squares.hpp"
#include "swemps/ns/pressure_operators.hpp"

namespace swemps::ns {

template <int Dim>
class LeastSquaresOperators final : public PressureOperators<Dim> {
 public:
  std::string_view name() const override { return "least-squares"; }
  void assemble(const StepGeometry<Dim>& g, std::vector<char>& unknown,
                std::span<const double> source, const BoundaryExtrapolation* boundary,
                PoissonSystem& out) override;
  void velocity_change(const StepGeometry<Dim>& g, double dt,
                       std::array<std::vector<double>, Dim>& change) override;

  // Fluid particles fitted to degree 2 in the last assemble().
  std::size_t fitted() const { return fitted_count_; }

 private:
  // Every fluid particle's fit at the step's positions: weights per pair of g.pairs.
  void fit(const StepGeometry<Dim>& g);

  std::vector<FitWeights<Dim>> weights_;  // per pair of the neighbour list
  std::vector<char> fitted_;              // per fluid particle: degree 2 held
  std::vector<double> coefficient_;       // per pair: the Poisson row's L_ij
  std::vector<char> on_surface_;          // per fluid particle: p = 0, not an unknown
  std::size_t fitted_count_ = 0;
};

// A Poisson row keeps its least-squares Laplacian while its negative weights sum to at most
// this share of its positive ones (above). Measured on the 2D dam break (a/l0 = 40): 0.1 and
// 0.2 both run to the end; 0.05 and 0.02 replace so many rows that the front moves (0.166
// and 0.139 a mean error against 0.118).
inline constexpr double least_squares_max_negative_share = 0.1;

// Unmarks every fluid unknown of a group that no free-surface particle reaches, directly or
// through a wall's extrapolation (such a group's pressure is undetermined); returns how many.
// Judged on the neighbour graph, not on the matrix: LSMPS rows need not be diagonally
// dominant.
std::size_t drop_ungrounded_unknowns(const neighbors::NeighborList& pairs,
                                     std::span<const double> pair_weight,
                                     const BoundaryExtrapolation& boundary,
                                     std::vector<char>& unknown);

extern template class LeastSquaresOperators<2>;
extern template class LeastSquaresOperators<3>;

}  // namespace swemps::ns

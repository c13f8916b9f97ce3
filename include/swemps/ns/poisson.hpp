#pragma once
// The pressure Poisson equation of semi-implicit MPS (method.md section 3) as a sparse linear
// system, and its solution by preconditioned conjugate gradients.
//
// For each unknown particle i (fluid or wall, not on the free surface)
//   (2d / (lambda n0)) sum_j (p_j - p_i) w_ij = b_i
// over its fluid and wall neighbours j (dummies only pad the number density). Free-surface
// neighbours are Dirichlet (p = 0): they add to the diagonal only. Multiplied by
// -lambda n0 / 2d the system is A p = -b lambda n0 / 2d with
//   A_ii = sum_j w_ij,   A_ij = -w_ij (j an unknown),
// symmetric because w_ij = w_ji, and positive definite because every connected group of
// unknowns touches the free surface (weakly diagonally dominant, strictly in some row).
// That is what lets conjugate gradients solve it, rather than the BiCGSTAB that
// non-symmetric MPS variants need.

#include <Eigen/Sparse>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/settings.hpp"

namespace swemps::ns {

struct PoissonSystem {
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> matrix;
  Eigen::VectorXd rhs;
  std::vector<std::uint32_t> particle_of_unknown;  // unknown k is particle particle_of_unknown[k]
  // Symmetric positive definite (the MPS operators: conjugate gradients) or general (the
  // least-squares operators: BiCGSTAB).
  bool symmetric = true;
  // A residual entry of this system times this is the compression it leaves per step
  // (PoissonSettings::compression_tolerance): the operators' scale from a row to the
  // Laplacian, times dt^2 / rho. 0 where unknown (the relative rule is used).
  double residual_to_compression = 0.0;
};

// Builds the system. `pairs` is the neighbour list (rows for at least the candidates);
// `pair_weight[k]` the pressure-kernel weight of pair k of that list; `unknown[i]` marks the
// particles solved for (only i < candidate_count may be set); `source[i]` is b_i; a neighbour
// j counts when j < candidate_count (fluid and wall particles come first). `laplacian_factor`
// is 2d / (lambda n0).
void assemble_poisson(const neighbors::NeighborList& pairs, std::span<const double> pair_weight,
                      std::span<const char> unknown, std::span<const double> source,
                      std::size_t candidate_count, double laplacian_factor, PoissonSystem& out);

// Numbers the marked particles among the first `count` in order: fills
// out.particle_of_unknown and returns each particle's unknown (-1 where unmarked).
std::vector<std::int32_t> number_unknowns(std::span<const char> unknown, std::size_t count,
                                          PoissonSystem& out);

struct PoissonReport {
  int iterations = 0;
  double relative_residual = 0.0;  // |rhs - A p| / |rhs| as the solver estimates it
  double compression_left = 0.0;   // its root mean square in compression per step, where known
  bool converged = false;
  bool setup_kept = false;  // the multigrid kept an earlier step's coarse levels
};

// Conjugate gradients (a symmetric system) or BiCGSTAB (a general one) with the chosen
// preconditioner. Keeps its workspace between calls.
class PoissonSolver {
 public:
  explicit PoissonSolver(const PoissonSettings& settings);
  ~PoissonSolver();
  PoissonSolver(PoissonSolver&&) noexcept;
  PoissonSolver& operator=(PoissonSolver&&) noexcept;

  // Solves system.matrix p = system.rhs starting from `guess` (one value per unknown);
  // the solution replaces it. A zero right-hand side gives p = 0 at once.
  PoissonReport solve(const PoissonSystem& system, Eigen::VectorXd& guess);

  // A multigrid setup kept across solves follows the unknowns by particle: the caller says
  // when the particles are renumbered. `old_of_new[k]` is the former index of particle k
  // (particles from old_of_new.size() on keep theirs); forget_kept_setup() when the
  // numbering changed otherwise (particles removed).
  void follow_renumbering(std::span<const std::uint32_t> old_of_new);
  void forget_kept_setup();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace swemps::ns

#pragma once
// Smoothed-aggregation algebraic multigrid (Vanek, Mandel & Brezina, Computing 56, 1996) as
// the preconditioner of the pressure Poisson solve: one V-cycle per Krylov iteration.
//
// Why: zero-fill incomplete factorisations need a number of iterations that grows like
// 1/l0 (the smooth pressure modes cross the domain one row per sweep), and the well-balanced
// pressure is smooth in space. Multigrid removes those modes on coarse levels, so the
// iteration count stays about constant; what it costs is the setup, which here is O(nnz)
// and rebuilt with every matrix (a step's unknowns change with its free surface):
//   - aggregates: Vanek's greedy three-pass grouping of each unknown with its strongly
//     connected neighbours (|a_ij| >= theta sqrt(a_ii a_jj)), about one kernel support each;
//   - prolongation: the aggregates' indicator functions (they carry the constant, the
//     Laplacian's near-null space) smoothed by one damped Jacobi step,
//     P = (I - omega D^-1 A) P0 with omega = (4/3) / rho, rho bounding D^-1 A's spectrum
//     by Gershgorin's theorem;
//   - coarse operators by Galerkin's product R A P with R = P^T, down to a level small
//     enough to factorise densely.
// The cycle smooths with one forward Gauss-Seidel sweep before the coarse correction and one
// backward sweep after it, so for a symmetric matrix the preconditioner is symmetric
// positive definite, as conjugate gradients need. A general (least-squares) matrix gets the
// same cycle under BiCGSTAB.

#include <Eigen/Dense>
#include <cstdint>
#include <utility>
#include <vector>

#include "swemps/ns/row_preconditioner.hpp"

namespace swemps::ns {

class AggregationMultigrid : public RowPreconditioner<AggregationMultigrid> {
 public:
  // Makes the next compute() keep the coarse levels of the last full setup and take only the
  // new matrix as the finest level: its row k is row setup_row[k] of the matrix that setup
  // was built on, and takes that row's prolongation (-1: an unknown the setup did not have,
  // whose prolongation row is its neighbours' rows averaged by their couplings in the new
  // matrix). The coarse correction is then that of a nearby matrix, which keeps the cycle a
  // symmetric preconditioner (a Krylov solve converges with it, in more iterations as the
  // two matrices drift apart); its cost is a copy of the matrix and of the prolongation's
  // rows. Without a multilevel setup to keep, compute() sets up anew.
  void keep_setup_for_next(std::vector<std::int32_t> setup_row) {
    setup_row_ = std::move(setup_row);
    keep_next_ = true;
  }
  // Whether the last compute() kept the previous setup.
  bool kept_setup() const { return kept_; }

  // Levels of the last setup, the finest first (the coarsest is solved densely).
  struct LevelSize {
    int unknowns = 0;
    int entries = 0;
  };
  const std::vector<LevelSize>& level_sizes() const { return level_sizes_; }

 private:
  friend class RowPreconditioner<AggregationMultigrid>;
  void factorize_rows(int n, const int* row_start, const int* column, const double* value);
  void solve_in_place(double* x) const;  // x = (one V-cycle from zero) x
  Eigen::Index size() const { return fine_size_; }

  struct Rows {  // compressed rows
    int n = 0;
    std::vector<int> start{0}, column;
    std::vector<double> value;
  };
  struct Level {
    Rows matrix;                           // this level's operator
    std::vector<double> inverse_diagonal;  // 0 where a row has no usable diagonal
    Rows prolongation;                     // to this level from the next coarser one
    Rows restriction;                      // its transpose
    mutable std::vector<double> rhs, solution, residual;
  };

  void cycle(std::size_t level) const;  // levels_[level]: solution from rhs
  void set_up(int n, const int* row_start, const int* column, const double* value);
  void take_finest(int n, const int* row_start, const int* column, const double* value);

  Eigen::Index fine_size_ = 0;
  std::vector<Level> levels_;
  Eigen::PartialPivLU<Eigen::MatrixXd> coarsest_;
  std::vector<LevelSize> level_sizes_;
  Rows setup_prolongation_;  // the finest level's, as the full setup built it
  std::vector<std::int32_t> setup_row_;
  bool keep_next_ = false, kept_ = false;
};

}  // namespace swemps::ns

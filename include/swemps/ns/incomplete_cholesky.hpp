#pragma once
// Zero-fill incomplete Cholesky factorisation, A ~ L L^T with L on the pattern of A's lower
// triangle, as a preconditioner for Eigen's ConjugateGradient.
//
// Why not Eigen's IncompleteCholesky: that one is general (any SPD matrix), so it rescales,
// may shift the diagonal and retry, and keeps fill lists; on the Poisson matrix of a 20,000
// particle dam break its factorisation and triangular solves took 40 % of a step. The MPS
// Poisson matrix is an M-matrix (positive diagonal, non-positive off-diagonal, weakly
// diagonally dominant, see poisson.hpp), and for M-matrices the zero-fill factorisation
// exists with positive pivots without any shift (Meijerink & van der Vorst 1977). So this
// one does only that, on the compressed rows it is given.
//
// Requirements on the matrix: row-major compressed storage, columns sorted in each row, a
// diagonal entry in every row, symmetric pattern and values.

#include <vector>

#include "swemps/ns/row_preconditioner.hpp"

namespace swemps::ns {

// info() is NumericalIssue when a pivot was not positive (the matrix was not an M-matrix).
class ZeroFillIncompleteCholesky : public RowPreconditioner<ZeroFillIncompleteCholesky> {
 private:
  friend class RowPreconditioner<ZeroFillIncompleteCholesky>;
  void factorize_rows(int n, const int* row_start, const int* column, const double* value);
  void solve_in_place(double* x) const;  // x = (L L^T)^-1 x
  Eigen::Index size() const { return static_cast<Eigen::Index>(diagonal_.size()); }

  // Strictly lower part of L in compressed rows, and its diagonal apart.
  std::vector<int> lower_start_, lower_column_;
  std::vector<double> lower_value_, diagonal_;
};

}  // namespace swemps::ns

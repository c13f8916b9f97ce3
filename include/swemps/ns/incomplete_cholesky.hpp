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

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace swemps::ns {

class ZeroFillIncompleteCholesky {
 public:
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  ZeroFillIncompleteCholesky() = default;

  Eigen::Index rows() const { return static_cast<Eigen::Index>(diagonal_.size()); }
  Eigen::Index cols() const { return rows(); }

  template <class MatrixType>
  ZeroFillIncompleteCholesky& analyzePattern(const MatrixType&) {
    return *this;
  }
  template <class MatrixType>
  ZeroFillIncompleteCholesky& factorize(const MatrixType& matrix) {
    factorize_rows(static_cast<int>(matrix.rows()), matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                   matrix.valuePtr());
    return *this;
  }
  template <class MatrixType>
  ZeroFillIncompleteCholesky& compute(const MatrixType& matrix) {
    return factorize(matrix);
  }

  // x = (L L^T)^-1 b
  template <class Rhs, class Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    x = b;
    solve_in_place(x.data());
  }
  template <class Rhs>
  Eigen::Solve<ZeroFillIncompleteCholesky, Rhs> solve(const Eigen::MatrixBase<Rhs>& b) const {
    return Eigen::Solve<ZeroFillIncompleteCholesky, Rhs>(*this, b.derived());
  }

  // NumericalIssue when a pivot was not positive (the matrix was not an M-matrix).
  Eigen::ComputationInfo info() const { return info_; }

 private:
  void factorize_rows(int n, const int* row_start, const int* column, const double* value);
  void solve_in_place(double* x) const;

  // Strictly lower part of L in compressed rows, and its diagonal apart.
  std::vector<int> lower_start_, lower_column_;
  std::vector<double> lower_value_, diagonal_;
  Eigen::ComputationInfo info_ = Eigen::Success;
};

}  // namespace swemps::ns

#pragma once
// What Eigen's iterative solvers (ConjugateGradient, BiCGSTAB) ask of a preconditioner, for
// the preconditioners built from a matrix's own compressed rows: the zero-fill incomplete
// factorisations (incomplete_cholesky.hpp, incomplete_lu.hpp) and the aggregation multigrid
// (aggregation_multigrid.hpp). `Derived` provides
//   void factorize_rows(int n, const int* row_start, const int* column, const double* value);
//   void solve_in_place(double* x) const;   // x = (approximate A)^-1 x
//   Eigen::Index size() const;
// and sets info_ in factorize_rows.

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace swemps::ns {

template <class Derived>
class RowPreconditioner {
 public:
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  Eigen::Index rows() const { return derived().size(); }
  Eigen::Index cols() const { return rows(); }

  template <class MatrixType>
  Derived& analyzePattern(const MatrixType&) {
    return derived();
  }
  template <class MatrixType>
  Derived& factorize(const MatrixType& matrix) {
    derived().factorize_rows(static_cast<int>(matrix.rows()), matrix.outerIndexPtr(),
                             matrix.innerIndexPtr(), matrix.valuePtr());
    return derived();
  }
  template <class MatrixType>
  Derived& compute(const MatrixType& matrix) {
    return factorize(matrix);
  }

  template <class Rhs, class Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    x = b;
    derived().solve_in_place(x.data());
  }
  template <class Rhs>
  Eigen::Solve<Derived, Rhs> solve(const Eigen::MatrixBase<Rhs>& b) const {
    return Eigen::Solve<Derived, Rhs>(derived(), b.derived());
  }

  Eigen::ComputationInfo info() const { return info_; }

 protected:
  Eigen::ComputationInfo info_ = Eigen::Success;

 private:
  Derived& derived() { return static_cast<Derived&>(*this); }
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
};

}  // namespace swemps::ns

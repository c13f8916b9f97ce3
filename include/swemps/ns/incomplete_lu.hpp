#pragma once
// Zero-fill incomplete LU factorisation, A ~ L U on the pattern of A (L unit lower, U upper),
// as the preconditioner of Eigen's BiCGSTAB for the least-squares Poisson system, which is
// not symmetric (least_squares_operators.hpp). The counterpart of the zero-fill incomplete
// Cholesky (incomplete_cholesky.hpp) for a general matrix: same storage, same interface.
//
// Requirements on the matrix: row-major compressed storage, columns sorted in each row, a
// diagonal entry in every row.

#include <vector>

#include "swemps/ns/row_preconditioner.hpp"

namespace swemps::ns {

// info() is NumericalIssue when a value was not finite or a row had no diagonal entry.
class ZeroFillIncompleteLU : public RowPreconditioner<ZeroFillIncompleteLU> {
 public:
  // Pivots below least_pivot_share of their row's absolute sum (or negative) in the last
  // factorisation, each replaced by that sum.
  int replaced_pivots() const { return replaced_pivots_; }
  static constexpr double least_pivot_share = 1e-3;

 private:
  friend class RowPreconditioner<ZeroFillIncompleteLU>;
  void factorize_rows(int n, const int* row_start, const int* column, const double* value);
  void solve_in_place(double* x) const;  // x = (L U)^-1 x
  Eigen::Index size() const { return static_cast<Eigen::Index>(diagonal_.size()); }

  // L (below the diagonal) and U (from it) share A's pattern: row i is
  // [start_[i], start_[i + 1]), its diagonal at diagonal_[i].
  std::vector<int> start_, column_, diagonal_;
  std::vector<double> value_;
  std::vector<int> position_;  // factorisation scratch: column -> slot in the current row
  int replaced_pivots_ = 0;
};

}  // namespace swemps::ns

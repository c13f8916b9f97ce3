#include "swemps/ns/incomplete_lu.hpp"

#include <cmath>

namespace swemps::ns {

void ZeroFillIncompleteLU::factorize_rows(int n, const int* row_start, const int* column,
                                          const double* value) {
  info_ = Eigen::Success;
  replaced_pivots_ = 0;
  const auto size = static_cast<std::size_t>(n);
  start_.assign(row_start, row_start + n + 1);
  column_.assign(column, column + row_start[n]);
  value_.assign(value, value + row_start[n]);
  diagonal_.assign(size, -1);
  position_.assign(size, -1);
  for (int i = 0; i < n; ++i) {
    for (int m = start_[i]; m < start_[i + 1]; ++m) {
      position_[static_cast<std::size_t>(column_[static_cast<std::size_t>(m)])] = m;
      if (column_[static_cast<std::size_t>(m)] == i) diagonal_[static_cast<std::size_t>(i)] = m;
    }
    if (diagonal_[static_cast<std::size_t>(i)] < 0) {
      info_ = Eigen::NumericalIssue;
      return;
    }
    // Row i left to right (the IKJ form): l_ik = a_ik / u_kk, then row k's part right of its
    // diagonal is taken off row i where row i has those columns (no fill).
    for (int m = start_[i]; m < start_[i + 1]; ++m) {
      const int k = column_[static_cast<std::size_t>(m)];
      if (k >= i) break;
      const double factor =
          value_[static_cast<std::size_t>(m)] /= value_[static_cast<std::size_t>(
              diagonal_[static_cast<std::size_t>(k)])];
      for (int q = diagonal_[static_cast<std::size_t>(k)] + 1; q < start_[k + 1]; ++q) {
        const int slot = position_[static_cast<std::size_t>(column_[static_cast<std::size_t>(q)])];
        if (slot >= 0) value_[static_cast<std::size_t>(slot)] -= factor * value_[static_cast<std::size_t>(q)];
      }
    }
    // A pivot that lost its sign or most of its size (the least-squares rows are not all
    // M-matrix rows, so the zero-fill elimination may cancel a diagonal) is replaced by the
    // original row's absolute sum: the factors then precondition a little worse, but exist;
    // the Krylov solver still solves the true system.
    double& pivot = value_[static_cast<std::size_t>(diagonal_[static_cast<std::size_t>(i)])];
    if (!std::isfinite(pivot)) {
      info_ = Eigen::NumericalIssue;
      return;
    }
    double row_sum = 0.0;
    for (int m = row_start[i]; m < row_start[i + 1]; ++m) row_sum += std::abs(value[m]);
    if (!(pivot > least_pivot_share * row_sum)) {
      pivot = row_sum > 0.0 ? row_sum : 1.0;
      ++replaced_pivots_;
    }
    for (int m = start_[i]; m < start_[i + 1]; ++m) {
      position_[static_cast<std::size_t>(column_[static_cast<std::size_t>(m)])] = -1;
    }
  }
}

void ZeroFillIncompleteLU::solve_in_place(double* x) const {
  const auto n = diagonal_.size();
  for (std::size_t i = 0; i < n; ++i) {  // L y = b, L unit lower
    double sum = x[i];
    for (int m = start_[i]; m < diagonal_[i]; ++m) {
      sum -= value_[static_cast<std::size_t>(m)] * x[column_[static_cast<std::size_t>(m)]];
    }
    x[i] = sum;
  }
  for (std::size_t i = n; i-- > 0;) {  // U z = y
    double sum = x[i];
    for (int m = diagonal_[i] + 1; m < start_[i + 1]; ++m) {
      sum -= value_[static_cast<std::size_t>(m)] * x[column_[static_cast<std::size_t>(m)]];
    }
    x[i] = sum / value_[static_cast<std::size_t>(diagonal_[i])];
  }
}

}  // namespace swemps::ns

#include "swemps/ns/incomplete_cholesky.hpp"

#include <cmath>

namespace swemps::ns {

void ZeroFillIncompleteCholesky::factorize_rows(int n, const int* row_start, const int* column,
                                                const double* value) {
  info_ = Eigen::Success;
  lower_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  lower_column_.clear();
  lower_value_.clear();
  diagonal_.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    // Row i of L, left to right: L_ik = (A_ik - sum_{j<k} L_ij L_kj) / L_kk, where the sum
    // runs over the columns rows i and k share (both sorted: a merge).
    const int first = static_cast<int>(lower_column_.size());
    double a_ii = 0.0;
    for (int m = row_start[i]; m < row_start[i + 1]; ++m) {
      const int k = column[m];
      if (k == i) a_ii = value[m];
      if (k >= i) continue;
      double sum = value[m];
      int p = first, q = lower_start_[static_cast<std::size_t>(k)];
      const int p_end = static_cast<int>(lower_column_.size());
      const int q_end = lower_start_[static_cast<std::size_t>(k) + 1];
      while (p < p_end && q < q_end) {
        const int cp = lower_column_[static_cast<std::size_t>(p)];
        const int cq = lower_column_[static_cast<std::size_t>(q)];
        if (cp == cq) {
          sum -=
              lower_value_[static_cast<std::size_t>(p)] * lower_value_[static_cast<std::size_t>(q)];
          ++p;
          ++q;
        } else if (cp < cq) {
          ++p;
        } else {
          ++q;
        }
      }
      lower_column_.push_back(k);
      lower_value_.push_back(sum / diagonal_[static_cast<std::size_t>(k)]);
    }
    double pivot = a_ii;
    for (std::size_t p = static_cast<std::size_t>(first); p < lower_value_.size(); ++p) {
      pivot -= lower_value_[p] * lower_value_[p];
    }
    if (!(pivot > 0.0)) {
      info_ = Eigen::NumericalIssue;
      pivot = a_ii > 0.0 ? a_ii : 1.0;  // keep going; the caller sees info()
    }
    diagonal_[static_cast<std::size_t>(i)] = std::sqrt(pivot);
    lower_start_[static_cast<std::size_t>(i) + 1] = static_cast<int>(lower_column_.size());
  }
}

void ZeroFillIncompleteCholesky::solve_in_place(double* x) const {
  const auto n = diagonal_.size();
  // L y = b, by rows.
  for (std::size_t i = 0; i < n; ++i) {
    double sum = x[i];
    for (int p = lower_start_[i]; p < lower_start_[i + 1]; ++p) {
      sum -=
          lower_value_[static_cast<std::size_t>(p)] * x[lower_column_[static_cast<std::size_t>(p)]];
    }
    x[i] = sum / diagonal_[i];
  }
  // L^T z = y: row i of L is column i of L^T, so each solved z_i is scattered back.
  for (std::size_t i = n; i-- > 0;) {
    x[i] /= diagonal_[i];
    const double z = x[i];
    for (int p = lower_start_[i]; p < lower_start_[i + 1]; ++p) {
      x[lower_column_[static_cast<std::size_t>(p)]] -=
          lower_value_[static_cast<std::size_t>(p)] * z;
    }
  }
}

}  // namespace swemps::ns

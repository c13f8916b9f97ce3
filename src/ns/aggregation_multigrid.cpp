#include "swemps/ns/aggregation_multigrid.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace swemps::ns {

namespace {

// Coarsening stops at a level this small, which is factorised densely (an LU of 100
// unknowns is about 0.7 million operations, below a fine-level sweep of the 20,000-particle
// dam break).
constexpr int kCoarsestUnknowns = 100;
// A level that coarsening left larger than this (aggregation stalled) is not factorised but
// smoothed by a few sweeps, which keeps the cycle's cost linear.
constexpr int kDenseLimit = 600;
constexpr int kCoarsestSweeps = 4;
// Vanek, Mandel & Brezina's strength threshold, halved on each coarser level (their
// eq. 3.5: coarse operators are denser, their weak entries relatively larger).
constexpr double kStrengthFinest = 0.08;
// Aggregation has stalled when it keeps more than this share of a level's unknowns.
constexpr double kStalledShare = 0.8;

template <class Rows>
void set_inverse_diagonal(const Rows& a, std::vector<double>& inverse) {
  inverse.assign(static_cast<std::size_t>(a.n), 0.0);
  for (int i = 0; i < a.n; ++i) {
    for (int m = a.start[static_cast<std::size_t>(i)]; m < a.start[static_cast<std::size_t>(i) + 1];
         ++m) {
      if (a.column[static_cast<std::size_t>(m)] == i &&
          a.value[static_cast<std::size_t>(m)] != 0.0) {
        inverse[static_cast<std::size_t>(i)] = 1.0 / a.value[static_cast<std::size_t>(m)];
      }
    }
  }
}

// Vanek's three passes. Returns each unknown's aggregate (-1: no strong neighbour, left to
// the smoother) and sets `count`.
template <class Rows>
std::vector<int> aggregate(const Rows& a, const std::vector<double>& inverse_diagonal, double theta,
                           int& count) {
  const auto n = static_cast<std::size_t>(a.n);
  const double theta2 = theta * theta;
  // Strong off-diagonal entries, as a mask over the matrix's entries.
  std::vector<char> strong(a.column.size(), 0);
  std::vector<char> has_strong(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double d_i = inverse_diagonal[i];
    if (d_i == 0.0) continue;
    for (int m = a.start[i]; m < a.start[i + 1]; ++m) {
      const auto j = static_cast<std::size_t>(a.column[static_cast<std::size_t>(m)]);
      if (j == i || inverse_diagonal[j] == 0.0) continue;
      const double v = a.value[static_cast<std::size_t>(m)];
      // a_ij^2 >= theta^2 |a_ii a_jj|
      if (v * v * std::abs(d_i * inverse_diagonal[j]) >= theta2) {
        strong[static_cast<std::size_t>(m)] = 1;
        has_strong[i] = 1;
      }
    }
  }
  std::vector<int> group(n, -1);
  count = 0;
  // 1: an unknown whose strong neighbours are all free roots an aggregate of them all.
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_strong[i] || group[i] >= 0) continue;
    bool free = true;
    for (int m = a.start[i]; m < a.start[i + 1] && free; ++m) {
      if (strong[static_cast<std::size_t>(m)] &&
          group[static_cast<std::size_t>(a.column[static_cast<std::size_t>(m)])] >= 0) {
        free = false;
      }
    }
    if (!free) continue;
    group[i] = count;
    for (int m = a.start[i]; m < a.start[i + 1]; ++m) {
      if (strong[static_cast<std::size_t>(m)]) {
        group[static_cast<std::size_t>(a.column[static_cast<std::size_t>(m)])] = count;
      }
    }
    ++count;
  }
  // 2: a free unknown joins the first-pass aggregate it is most strongly connected to.
  const std::vector<int> first_pass = group;
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_strong[i] || group[i] >= 0) continue;
    double best = 0.0;
    for (int m = a.start[i]; m < a.start[i + 1]; ++m) {
      if (!strong[static_cast<std::size_t>(m)]) continue;
      const int g = first_pass[static_cast<std::size_t>(a.column[static_cast<std::size_t>(m)])];
      const double v = std::abs(a.value[static_cast<std::size_t>(m)]);
      if (g >= 0 && v > best) {
        best = v;
        group[i] = g;
      }
    }
  }
  // 3: what is left groups with its free strong neighbours.
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_strong[i] || group[i] >= 0) continue;
    group[i] = count;
    for (int m = a.start[i]; m < a.start[i + 1]; ++m) {
      const auto j = static_cast<std::size_t>(a.column[static_cast<std::size_t>(m)]);
      if (strong[static_cast<std::size_t>(m)] && group[j] < 0) group[j] = count;
    }
    ++count;
  }
  return group;
}

// P = (I - omega D^-1 A) P0, P0 the aggregates' indicators.
template <class Rows>
Rows smoothed_prolongation(const Rows& a, const std::vector<double>& inverse_diagonal,
                           const std::vector<int>& group, double omega) {
  Rows p;
  p.n = a.n;
  p.start.assign(1, 0);
  std::vector<std::pair<int, double>> row;
  for (int i = 0; i < a.n; ++i) {
    row.clear();
    auto add = [&row](int column, double value) {
      for (auto& entry : row) {
        if (entry.first == column) {
          entry.second += value;
          return;
        }
      }
      row.emplace_back(column, value);
    };
    const auto si = static_cast<std::size_t>(i);
    if (group[si] >= 0) add(group[si], 1.0);
    const double scale = -omega * inverse_diagonal[si];
    for (int m = a.start[si]; m < a.start[si + 1]; ++m) {
      const int g = group[static_cast<std::size_t>(a.column[static_cast<std::size_t>(m)])];
      if (g >= 0) add(g, scale * a.value[static_cast<std::size_t>(m)]);
    }
    std::sort(row.begin(), row.end());
    for (const auto& [column, value] : row) {
      if (value == 0.0) continue;
      p.column.push_back(column);
      p.value.push_back(value);
    }
    p.start.push_back(static_cast<int>(p.column.size()));
  }
  return p;
}

template <class Rows>
Rows transpose(const Rows& p, int columns) {
  Rows t;
  t.n = columns;
  t.start.assign(static_cast<std::size_t>(columns) + 1, 0);
  for (const int c : p.column) ++t.start[static_cast<std::size_t>(c) + 1];
  for (int c = 0; c < columns; ++c) {
    t.start[static_cast<std::size_t>(c) + 1] += t.start[static_cast<std::size_t>(c)];
  }
  t.column.resize(p.column.size());
  t.value.resize(p.value.size());
  std::vector<int> next(t.start.begin(), t.start.end() - 1);
  for (int i = 0; i < p.n; ++i) {  // rows in order: each transposed row comes out sorted
    for (int m = p.start[static_cast<std::size_t>(i)]; m < p.start[static_cast<std::size_t>(i) + 1];
         ++m) {
      const int slot = next[static_cast<std::size_t>(p.column[static_cast<std::size_t>(m)])]++;
      t.column[static_cast<std::size_t>(slot)] = i;
      t.value[static_cast<std::size_t>(slot)] = p.value[static_cast<std::size_t>(m)];
    }
  }
  return t;
}

// left * right, both compressed rows, `columns` the product's column count; each row's
// columns come out sorted.
template <class Rows>
Rows multiply(const Rows& left, const Rows& right, int columns) {
  Rows out;
  out.n = left.n;
  out.start.assign(1, 0);
  std::vector<double> sum(static_cast<std::size_t>(columns), 0.0);
  std::vector<int> seen(static_cast<std::size_t>(columns), -1);
  std::vector<int> touched;
  for (int i = 0; i < left.n; ++i) {
    touched.clear();
    for (int m = left.start[static_cast<std::size_t>(i)];
         m < left.start[static_cast<std::size_t>(i) + 1]; ++m) {
      const auto k = static_cast<std::size_t>(left.column[static_cast<std::size_t>(m)]);
      const double v = left.value[static_cast<std::size_t>(m)];
      for (int q = right.start[k]; q < right.start[k + 1]; ++q) {
        const auto c = static_cast<std::size_t>(right.column[static_cast<std::size_t>(q)]);
        if (seen[c] != i) {
          seen[c] = i;
          sum[c] = 0.0;
          touched.push_back(static_cast<int>(c));
        }
        sum[c] += v * right.value[static_cast<std::size_t>(q)];
      }
    }
    std::sort(touched.begin(), touched.end());
    for (const int c : touched) {
      out.column.push_back(c);
      out.value.push_back(sum[static_cast<std::size_t>(c)]);
    }
    out.start.push_back(static_cast<int>(out.column.size()));
  }
  return out;
}

// x += D^-1 (b - A x) row by row, in the given direction (Gauss-Seidel).
template <class Rows>
void sweep(const Rows& a, const std::vector<double>& inverse_diagonal, const double* b, double* x,
           bool forward) {
  const int* start = a.start.data();
  const int* column = a.column.data();
  const double* value = a.value.data();
  auto relax = [&](int i) {
    double s = b[i];
    for (int m = start[i]; m < start[i + 1]; ++m) s -= value[m] * x[column[m]];
    x[i] += s * inverse_diagonal[static_cast<std::size_t>(i)];
  };
  if (forward) {
    for (int i = 0; i < a.n; ++i) relax(i);
  } else {
    for (int i = a.n; i-- > 0;) relax(i);
  }
}

}  // namespace

void AggregationMultigrid::factorize_rows(int n, const int* row_start, const int* column,
                                          const double* value) {
  const bool keep =
      keep_next_ && levels_.size() > 1 && setup_row_.size() == static_cast<std::size_t>(n);
  keep_next_ = false;
  kept_ = keep;
  if (keep) {
    take_finest(n, row_start, column, value);
  } else {
    set_up(n, row_start, column, value);
  }
}

void AggregationMultigrid::take_finest(int n, const int* row_start, const int* column,
                                       const double* value) {
  info_ = Eigen::Success;
  fine_size_ = n;
  Level& finest = levels_.front();
  finest.matrix.n = n;
  finest.matrix.start.assign(row_start, row_start + n + 1);
  finest.matrix.column.assign(column, column + row_start[n]);
  finest.matrix.value.assign(value, value + row_start[n]);
  set_inverse_diagonal(finest.matrix, finest.inverse_diagonal);
  finest.rhs.assign(static_cast<std::size_t>(n), 0.0);
  finest.solution.assign(finest.rhs.size(), 0.0);
  finest.residual.assign(finest.rhs.size(), 0.0);
  Rows& p = finest.prolongation;
  p.n = n;
  p.start.assign(1, 0);
  p.column.clear();
  p.value.clear();
  const Rows& old = setup_prolongation_;
  auto kept_row = [&](int k) {
    const std::int32_t r = setup_row_[static_cast<std::size_t>(k)];
    return r >= 0 && r < old.n ? r : -1;
  };
  std::vector<std::pair<int, double>> row;
  for (int k = 0; k < n; ++k) {
    const std::int32_t r = kept_row(k);
    if (r >= 0) {
      p.column.insert(p.column.end(), old.column.begin() + old.start[static_cast<std::size_t>(r)],
                      old.column.begin() + old.start[static_cast<std::size_t>(r) + 1]);
      p.value.insert(p.value.end(), old.value.begin() + old.start[static_cast<std::size_t>(r)],
                     old.value.begin() + old.start[static_cast<std::size_t>(r) + 1]);
    } else {
      // An unknown the setup did not have (a particle that has just left the free surface):
      // the mean of its neighbours' rows, weighted by their couplings, as a smoothed
      // prolongation would interpolate it. Without a row, its error is left to the smoother
      // alone, and in the dam break's splash the coarse levels kept over 50 solves (or over
      // 20 for the least-squares system) let the splash run away (docs/performance.md).
      row.clear();
      double total = 0.0;
      for (int m = row_start[k]; m < row_start[k + 1]; ++m) {
        const int j = column[m];
        const std::int32_t rj = j == k ? -1 : kept_row(j);
        if (rj < 0) continue;
        const double w = std::abs(value[m]);
        total += w;
        for (int q = old.start[static_cast<std::size_t>(rj)];
             q < old.start[static_cast<std::size_t>(rj) + 1]; ++q) {
          const int c = old.column[static_cast<std::size_t>(q)];
          const double v = w * old.value[static_cast<std::size_t>(q)];
          auto entry =
              std::find_if(row.begin(), row.end(), [c](const auto& e) { return e.first == c; });
          if (entry == row.end()) {
            row.emplace_back(c, v);
          } else {
            entry->second += v;
          }
        }
      }
      if (total > 0.0) {
        std::sort(row.begin(), row.end());
        for (const auto& [c, v] : row) {
          p.column.push_back(c);
          p.value.push_back(v / total);
        }
      }
    }
    p.start.push_back(static_cast<int>(p.column.size()));
  }
  finest.restriction = transpose(p, levels_[1].matrix.n);
  level_sizes_.front() = {n, row_start[n]};
}

void AggregationMultigrid::set_up(int n, const int* row_start, const int* column,
                                  const double* value) {
  info_ = Eigen::Success;
  fine_size_ = n;
  levels_.clear();
  level_sizes_.clear();
  levels_.emplace_back();
  {
    Rows& a = levels_.back().matrix;
    a.n = n;
    a.start.assign(row_start, row_start + n + 1);
    a.column.assign(column, column + row_start[n]);
    a.value.assign(value, value + row_start[n]);
  }
  double theta = kStrengthFinest;
  for (;;) {
    Level& fine = levels_.back();
    set_inverse_diagonal(fine.matrix, fine.inverse_diagonal);
    fine.rhs.assign(static_cast<std::size_t>(fine.matrix.n), 0.0);
    fine.solution.assign(fine.rhs.size(), 0.0);
    fine.residual.assign(fine.rhs.size(), 0.0);
    level_sizes_.push_back({fine.matrix.n, static_cast<int>(fine.matrix.column.size())});
    if (fine.matrix.n <= kCoarsestUnknowns) break;
    int count = 0;
    const std::vector<int> group = aggregate(fine.matrix, fine.inverse_diagonal, theta, count);
    if (count == 0 || count > kStalledShare * fine.matrix.n) break;
    // Gershgorin's bound on the spectral radius of D^-1 A.
    double radius = 0.0;
    for (int i = 0; i < fine.matrix.n; ++i) {
      double row_sum = 0.0;
      for (int m = fine.matrix.start[static_cast<std::size_t>(i)];
           m < fine.matrix.start[static_cast<std::size_t>(i) + 1]; ++m) {
        row_sum += std::abs(fine.matrix.value[static_cast<std::size_t>(m)]);
      }
      radius =
          std::max(radius, row_sum * std::abs(fine.inverse_diagonal[static_cast<std::size_t>(i)]));
    }
    const double omega = radius > 0.0 ? (4.0 / 3.0) / radius : 0.0;
    fine.prolongation = smoothed_prolongation(fine.matrix, fine.inverse_diagonal, group, omega);
    fine.restriction = transpose(fine.prolongation, count);
    Rows coarse =
        multiply(fine.restriction, multiply(fine.matrix, fine.prolongation, count), count);
    levels_.emplace_back();
    levels_.back().matrix = std::move(coarse);
    theta *= 0.5;
  }
  if (levels_.size() > 1) setup_prolongation_ = levels_.front().prolongation;
  const Rows& last = levels_.back().matrix;
  if (last.n <= kDenseLimit) {
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(last.n, last.n);
    for (int i = 0; i < last.n; ++i) {
      for (int m = last.start[static_cast<std::size_t>(i)];
           m < last.start[static_cast<std::size_t>(i) + 1]; ++m) {
        dense(i, last.column[static_cast<std::size_t>(m)]) =
            last.value[static_cast<std::size_t>(m)];
      }
    }
    coarsest_.compute(dense);
    if (last.n > 0 && !std::isfinite(coarsest_.rcond())) info_ = Eigen::NumericalIssue;
  }
}

void AggregationMultigrid::cycle(std::size_t l) const {
  const Level& level = levels_[l];
  const auto n = static_cast<std::size_t>(level.matrix.n);
  if (l + 1 == levels_.size()) {
    if (level.matrix.n <= kDenseLimit) {
      Eigen::Map<Eigen::VectorXd>(level.solution.data(), level.matrix.n) =
          coarsest_.solve(Eigen::Map<const Eigen::VectorXd>(level.rhs.data(), level.matrix.n));
    } else {
      std::fill(level.solution.begin(), level.solution.end(), 0.0);
      for (int s = 0; s < kCoarsestSweeps; ++s) {
        sweep(level.matrix, level.inverse_diagonal, level.rhs.data(), level.solution.data(), true);
        sweep(level.matrix, level.inverse_diagonal, level.rhs.data(), level.solution.data(), false);
      }
    }
    return;
  }
  double* x = level.solution.data();
  std::fill(level.solution.begin(), level.solution.end(), 0.0);
  sweep(level.matrix, level.inverse_diagonal, level.rhs.data(), x, true);
  // The residual, restricted.
  const Rows& a = level.matrix;
  for (std::size_t i = 0; i < n; ++i) {
    double s = level.rhs[i];
    for (int m = a.start[i]; m < a.start[i + 1]; ++m) {
      s -= a.value[static_cast<std::size_t>(m)] * x[a.column[static_cast<std::size_t>(m)]];
    }
    level.residual[i] = s;
  }
  const Level& coarse = levels_[l + 1];
  const Rows& r = level.restriction;
  for (int c = 0; c < r.n; ++c) {
    double s = 0.0;
    for (int m = r.start[static_cast<std::size_t>(c)]; m < r.start[static_cast<std::size_t>(c) + 1];
         ++m) {
      s += r.value[static_cast<std::size_t>(m)] *
           level.residual[static_cast<std::size_t>(r.column[static_cast<std::size_t>(m)])];
    }
    coarse.rhs[static_cast<std::size_t>(c)] = s;
  }
  cycle(l + 1);
  // The coarse correction, prolonged.
  const Rows& p = level.prolongation;
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (int m = p.start[i]; m < p.start[i + 1]; ++m) {
      s += p.value[static_cast<std::size_t>(m)] *
           coarse.solution[static_cast<std::size_t>(p.column[static_cast<std::size_t>(m)])];
    }
    x[i] += s;
  }
  sweep(level.matrix, level.inverse_diagonal, level.rhs.data(), x, false);
}

void AggregationMultigrid::solve_in_place(double* x) const {
  if (levels_.empty() || fine_size_ == 0) return;
  const Level& finest = levels_.front();
  std::copy(x, x + fine_size_, finest.rhs.begin());
  cycle(0);
  std::copy(finest.solution.begin(), finest.solution.end(), x);
}

}  // namespace swemps::ns

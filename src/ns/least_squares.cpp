#include "swemps/ns/least_squares.hpp"

#include <Eigen/Core>
#include <stdexcept>

namespace swemps::ns {

namespace {

template <int Dim>
using Basis = Eigen::Matrix<double, quadratic_terms<Dim>, 1>;

// q(x / r_s) in the order of least_squares.hpp: the Dim linear terms, then the products
// x_a x_b for a <= b in lexicographic order.
template <int Dim>
Basis<Dim> quadratic_basis(const std::array<double, Dim>& offset, double inverse_scale) {
  Basis<Dim> q;
  std::array<double, Dim> s{};
  for (int d = 0; d < Dim; ++d) s[d] = offset[d] * inverse_scale;
  int k = 0;
  for (int d = 0; d < Dim; ++d) q[k++] = s[d];
  for (int a = 0; a < Dim; ++a) {
    for (int b = a; b < Dim; ++b) q[k++] = s[a] * s[b];
  }
  return q;
}

// The sum e_xx + e_yy (+ e_zz): the basis entries that hold f_dd r_s^2 / 2.
template <int Dim>
Basis<Dim> laplacian_selector() {
  Basis<Dim> e = Basis<Dim>::Zero();
  int k = Dim;
  for (int a = 0; a < Dim; ++a) {
    for (int b = a; b < Dim; ++b, ++k) {
      if (a == b) e[k] = 1.0;
    }
  }
  return e;
}

void check_sizes(std::size_t neighbours, std::size_t out) {
  if (neighbours != out) {
    throw std::invalid_argument("least squares: one output per neighbour");
  }
}

}  // namespace

// Factors the symmetric moment matrix in place as L D L^T (no pivoting: M is a sum of w q q^T,
// positive semi-definite) and refuses it when a pivot is not above least_squares_min_pivot
// of its own diagonal entry, i.e. when one basis term is all but a combination of the
// earlier ones over these neighbours (independent of how each term is scaled). Written out
// for the fixed sizes here: Eigen's general rank update and pivoted LDLT took two thirds of
// the fit's time.
template <int N>
bool factor_moment(std::array<std::array<double, N>, N>& m) {
  for (int k = 0; k < N; ++k) {
    const double diagonal = m[k][k];
    double pivot = diagonal;
    for (int c = 0; c < k; ++c) pivot -= m[k][c] * m[k][c] * m[c][c];
    if (!(diagonal > 0.0) || !(pivot > least_squares_min_pivot * diagonal)) return false;
    m[k][k] = pivot;
    for (int r = k + 1; r < N; ++r) {
      double value = m[r][k];
      for (int c = 0; c < k; ++c) value -= m[r][c] * m[k][c] * m[c][c];
      m[r][k] = value / pivot;
    }
  }
  return true;
}

// Solves L D L^T x = b in place with the factor of factor_moment().
template <int N>
void solve_moment(const std::array<std::array<double, N>, N>& f, std::array<double, N>& x) {
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c < r; ++c) x[r] -= f[r][c] * x[c];
  }
  for (int r = 0; r < N; ++r) x[r] /= f[r][r];
  for (int r = N; r-- > 0;) {
    for (int c = r + 1; c < N; ++c) x[r] -= f[c][r] * x[c];
  }
}

template <int Dim>
bool fit_quadratic(std::span<const FitNeighbour<Dim>> neighbours, double scale_m,
                   std::span<FitWeights<Dim>> out) {
  check_sizes(neighbours.size(), out.size());
  constexpr int n = quadratic_terms<Dim>;
  if (neighbours.size() < static_cast<std::size_t>(n)) return false;
  const double inverse_scale = 1.0 / scale_m;
  std::array<std::array<double, n>, n> moment{};  // lower triangle used
  for (const auto& j : neighbours) {
    if (!(j.weight > 0.0)) continue;
    const Basis<Dim> q = quadratic_basis<Dim>(j.offset, inverse_scale);
    for (int r = 0; r < n; ++r) {
      const double wq = j.weight * q[r];
      for (int c = 0; c <= r; ++c) moment[r][c] += wq * q[c];
    }
  }
  if (!factor_moment<n>(moment)) return false;
  // M is symmetric, so e^T M^-1 q = (M^-1 e)^T q: Dim + 1 solves give every neighbour's
  // weights as dot products.
  std::array<std::array<double, n>, Dim + 1> rows{};
  for (int d = 0; d < Dim; ++d) {
    rows[d][d] = 1.0;
    solve_moment<n>(moment, rows[d]);
    for (double& v : rows[d]) v *= inverse_scale;
  }
  const Basis<Dim> selector = laplacian_selector<Dim>();
  for (int k = 0; k < n; ++k) rows[Dim][k] = selector[k];
  solve_moment<n>(moment, rows[Dim]);
  for (double& v : rows[Dim]) v *= 2.0 * inverse_scale * inverse_scale;
  for (std::size_t m = 0; m < neighbours.size(); ++m) {
    const auto& j = neighbours[m];
    if (!(j.weight > 0.0)) {
      out[m] = FitWeights<Dim>{};
      continue;
    }
    const Basis<Dim> q = quadratic_basis<Dim>(j.offset, inverse_scale) * j.weight;
    for (int d = 0; d < Dim; ++d) {
      double g = 0.0;
      for (int k = 0; k < n; ++k) g += rows[d][k] * q[k];
      out[m].gradient[d] = g;
    }
    double l = 0.0;
    for (int k = 0; k < n; ++k) l += rows[Dim][k] * q[k];
    out[m].laplacian = l;
  }
  return true;
}

template bool fit_quadratic<2>(std::span<const FitNeighbour<2>>, double, std::span<FitWeights<2>>);
template bool fit_quadratic<3>(std::span<const FitNeighbour<3>>, double, std::span<FitWeights<3>>);

}  // namespace swemps::ns

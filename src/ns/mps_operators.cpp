#include "swemps/ns/mps_operators.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::ns {

namespace {

// Unmarks the unknowns of every group of rows that no strictly diagonally dominant row
// reaches through the matrix's couplings (a group without a Dirichlet neighbour); returns
// how many.
std::size_t drop_ungrounded(const PoissonSystem& system, std::vector<char>& unknown) {
  const auto& a = system.matrix;
  const Eigen::Index n = a.rows();
  std::vector<char> reached(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Index> queue;
  for (Eigen::Index r = 0; r < n; ++r) {
    double diagonal = 0.0, off = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator it(a, r); it; ++it) {
      if (it.col() == r) {
        diagonal += it.value();
      } else {
        off += std::abs(it.value());
      }
    }
    if (diagonal - off > 1e-9 * diagonal) {
      reached[static_cast<std::size_t>(r)] = 1;
      queue.push_back(r);
    }
  }
  while (!queue.empty()) {
    const Eigen::Index r = queue.back();
    queue.pop_back();
    for (Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator it(a, r); it; ++it) {
      if (!reached[static_cast<std::size_t>(it.col())]) {
        reached[static_cast<std::size_t>(it.col())] = 1;
        queue.push_back(it.col());
      }
    }
  }
  std::size_t dropped = 0;
  for (Eigen::Index r = 0; r < n; ++r) {
    if (reached[static_cast<std::size_t>(r)]) continue;
    unknown[system.particle_of_unknown[static_cast<std::size_t>(r)]] = 0;
    ++dropped;
  }
  return dropped;
}

}  // namespace

template <int Dim>
bool solve_symmetric(const std::array<std::array<double, Dim>, Dim>& c,
                     const std::array<double, Dim>& b, std::array<double, Dim>& g) {
  Eigen::Matrix<double, Dim, Dim> matrix;
  double scale = 1.0;
  for (int r = 0; r < Dim; ++r) {
    for (int k = 0; k < Dim; ++k) matrix(r, k) = c[r][k];
    scale *= c[r][r];
  }
  if (!(scale > 0.0) || !(matrix.determinant() > 0.05 * scale)) return false;
  const Eigen::Matrix<double, Dim, 1> solved =
      matrix.inverse() * Eigen::Map<const Eigen::Matrix<double, Dim, 1>>(b.data());
  for (int d = 0; d < Dim; ++d) g[d] = solved[d];
  return true;
}

template <int Dim>
void MpsOperators<Dim>::assemble(const StepGeometry<Dim>& g, std::vector<char>& unknown,
                                 std::span<const double> source,
                                 const BoundaryExtrapolation* boundary, PoissonSystem& out) {
  const double laplacian_factor = 2.0 * Dim / (g.lattice.lambda_m2 * g.lattice.number_density);
  out.symmetric = true;
  out.residual_to_compression = laplacian_factor;  // the simulation scales by dt^2 / rho
  if (boundary) {
    assemble_poisson_extrapolated(g.pairs, g.pair_weight, unknown, source, *boundary,
                                  laplacian_factor, out);
    // A few fluid particles held only by walls (a drop in a corner) have no free surface in
    // reach: their pressure is undetermined and the matrix singular. They are set to p = 0
    // like the surface, and the system is formed again without them.
    if (drop_ungrounded(out, unknown) > 0) {
      assemble_poisson_extrapolated(g.pairs, g.pair_weight, unknown, source, *boundary,
                                    laplacian_factor, out);
    }
  } else {
    assemble_poisson(g.pairs, g.pair_weight, unknown, source,
                     g.particles.fluid + g.particles.wall, laplacian_factor, out);
  }
}

template <int Dim>
void MpsOperators<Dim>::velocity_change(const StepGeometry<Dim>& g, double dt,
                                        std::array<std::vector<double>, Dim>& change) {
  const auto& p = g.particles;
  const auto& s = g.settings;
  const auto& pairs = g.pairs;
  const auto pair_weight = g.pair_weight;
  const std::size_t fluid = p.fluid;
  const std::size_t candidates = fluid + p.wall;
  const double factor = -dt * Dim / (s.density_kg_m3 * g.lattice.number_density);
  const bool corrected = s.gradient != PressureGradient::minimum_pressure;
  const bool repulsive = s.gradient != PressureGradient::corrected;
  // Extrapolated boundary pressures take part in the gradient, dummies too; the smallest
  // pressure is the fluid's (a wall above the water extrapolates below zero, and would make
  // the surface particle beside it repel everything).
  const bool extrapolated = s.boundary == BoundaryPressure::extrapolated;
  const std::size_t sources = extrapolated ? p.size() : candidates;
  const std::size_t lowest_of = extrapolated ? fluid : candidates;
  const double reach = s.repulsion_distance_spacings * s.spacing_m;
  const double repulsion_reach2 = reach * reach;
  for (int d = 0; d < Dim; ++d) change[d].resize(fluid);
  parallel_for(fluid, [&](std::size_t i) {
    const std::size_t first = pairs.offsets[i];
    const auto row = pairs.row(i);
    double lowest = p.pressure[i];
    for (std::size_t m = 0; m < row.size() && repulsive; ++m) {
      if (row[m] < lowest_of && pair_weight[first + m] > 0.0) {
        lowest = std::min(lowest, p.pressure[row[m]]);
      }
    }
    std::array<double, Dim> gradient{};
    std::array<std::array<double, Dim>, Dim> moment{};
    for (std::size_t m = 0; m < row.size(); ++m) {
      const std::uint32_t j = row[m];
      const double w = pair_weight[first + m];
      if (j >= sources || w == 0.0) continue;
      const double r2 = squared_distance(p, i, j);
      if (r2 == 0.0) continue;
      std::array<double, Dim> x{};
      for (int d = 0; d < Dim; ++d) x[d] = p.position[d][j] - p.position[d][i];
      // p_j - p_min = (p_j - p_i) + (p_i - p_min): with the correction matrix the second
      // part, the repulsion, acts only between pairs closer than the repulsion distance.
      const double coefficient =
          (corrected ? p.pressure[j] - p.pressure[i] +
                           (r2 < repulsion_reach2 ? p.pressure[i] - lowest : 0.0)
                     : p.pressure[j] - lowest) *
          w / r2;
      for (int d = 0; d < Dim; ++d) gradient[d] += coefficient * x[d];
      if (corrected) {
        for (int a = 0; a < Dim; ++a) {
          for (int b = 0; b < Dim; ++b) moment[a][b] += x[a] * x[b] * w / r2;
        }
      }
    }
    std::array<double, Dim> solved{};
    if (corrected && solve_symmetric<Dim>(moment, gradient, solved)) {
      // C_i^-1 b is the gradient itself; the standard form's d/n0 is its lattice value.
      for (int d = 0; d < Dim; ++d) change[d][i] = -dt * solved[d] / s.density_kg_m3;
      return;
    }
    for (int d = 0; d < Dim; ++d) change[d][i] = factor * gradient[d];
  });
}

template bool solve_symmetric<2>(const std::array<std::array<double, 2>, 2>&,
                                 const std::array<double, 2>&, std::array<double, 2>&);
template bool solve_symmetric<3>(const std::array<std::array<double, 3>, 3>&,
                                 const std::array<double, 3>&, std::array<double, 3>&);
template class MpsOperators<2>;
template class MpsOperators<3>;

}  // namespace swemps::ns

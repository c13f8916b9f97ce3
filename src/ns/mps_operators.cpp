#include "swemps/ns/mps_operators.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

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
MpsOperators<Dim>::MpsOperators(const Settings& settings) {
  if (settings.gradient_weights == GradientWeights::kernel_slope) {
    slope_kernel_ = kernels::make_kernel<Dim>(
        settings.pressure_kernel.spec,
        settings.pressure_kernel.support_spacings * settings.spacing_m);
  }
}

namespace {

// The pair weight omega = -w'(r) / r of GradientWeights::kernel_slope, and a stand-in for the
// MPS weights, whose loop does not read it.
template <class Kernel>
struct SlopeWeight {
  const Kernel& kernel;
  double operator()(double r2) const {
    const double r = std::sqrt(r2);
    return -kernel.dw_dr(r) / r;
  }
};
struct NoSlopeWeight {
  double operator()(double) const { return 0.0; }
};

}  // namespace

template <int Dim>
void MpsOperators<Dim>::velocity_change(const StepGeometry<Dim>& g, double dt,
                                        std::array<std::vector<double>, Dim>& change) {
  for (int d = 0; d < Dim; ++d) change[d].resize(g.particles.fluid);
  const bool corrected = g.settings.gradient != PressureGradient::minimum_pressure;
  if (corrected && slope_kernel_) {
    std::visit(
        [&](const auto& kernel) {
          gradient_loop(g, dt, SlopeWeight<std::decay_t<decltype(kernel)>>{kernel}, change);
        },
        *slope_kernel_);
  } else {
    gradient_loop(g, dt, NoSlopeWeight{}, change);
  }
}

template <int Dim>
template <class Slope>
void MpsOperators<Dim>::gradient_loop(const StepGeometry<Dim>& g, double dt, Slope slope,
                                      std::array<std::vector<double>, Dim>& change) const {
  constexpr bool own_weights = !std::is_same_v<Slope, NoSlopeWeight>;
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
  parallel_for(fluid, [&](std::size_t i) {
    const std::size_t first = pairs.offsets[i];
    const auto row = pairs.row(i);
    double lowest = p.pressure[i];
    for (std::size_t m = 0; m < row.size() && repulsive; ++m) {
      if (row[m] < lowest_of && pair_weight[first + m] > 0.0) {
        lowest = std::min(lowest, p.pressure[row[m]]);
      }
    }
    // The sums on w / r^2 (the gradient with its repulsion, and their correction matrix) and,
    // with the kernel's slope, the consistent part on the slope with its own correction
    // matrix and the repulsion alone; the w / r^2 gradient is then the fallback.
    std::array<double, Dim> gradient{}, repulsion{}, sloped{};
    std::array<std::array<double, Dim>, Dim> moment{}, sloped_moment{};
    bool repels = false;
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
      const double difference = corrected ? p.pressure[j] - p.pressure[i] : p.pressure[j] - lowest;
      const double push = corrected && r2 < repulsion_reach2 ? p.pressure[i] - lowest : 0.0;
      const double coefficient = (difference + push) * w / r2;
      for (int d = 0; d < Dim; ++d) gradient[d] += coefficient * x[d];
      if (!corrected) continue;
      // The matrices are symmetric: the upper triangle here, the lower one after the loop.
      for (int a = 0; a < Dim; ++a) {
        for (int b = a; b < Dim; ++b) moment[a][b] += x[a] * x[b] * w / r2;
      }
      if constexpr (own_weights) {
        const double omega = slope(r2);
        repels = repels || push != 0.0;
        for (int d = 0; d < Dim; ++d) {
          sloped[d] += difference * omega * x[d];
          repulsion[d] += push * w / r2 * x[d];
        }
        for (int a = 0; a < Dim; ++a) {
          for (int b = a; b < Dim; ++b) sloped_moment[a][b] += x[a] * x[b] * omega;
        }
      }
    }
    for (int a = 0; a < Dim; ++a) {
      for (int b = 0; b < a; ++b) {
        moment[a][b] = moment[b][a];
        if constexpr (own_weights) sloped_moment[a][b] = sloped_moment[b][a];
      }
    }
    if (corrected) {
      // C_i^-1 b is the gradient itself; the standard form's d/n0 is its lattice value.
      std::array<double, Dim> consistent{}, repelled{};
      bool solved = false;
      if constexpr (own_weights) {
        solved = solve_symmetric<Dim>(sloped_moment, sloped, consistent) &&
                 (!repels || solve_symmetric<Dim>(moment, repulsion, repelled));
      } else {
        solved = solve_symmetric<Dim>(moment, gradient, consistent);
      }
      if (solved) {
        for (int d = 0; d < Dim; ++d) {
          change[d][i] = -dt * (consistent[d] + repelled[d]) / s.density_kg_m3;
        }
        return;
      }
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

#include "swemps/ns/least_squares_operators.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/ns/mps_operators.hpp"

namespace swemps::ns {

std::size_t drop_ungrounded_unknowns(const neighbors::NeighborList& pairs,
                                     std::span<const double> pair_weight,
                                     const BoundaryExtrapolation& boundary,
                                     std::vector<char>& unknown) {
  const std::size_t fluid = boundary.fluid_count;
  std::vector<char> reached(fluid, 0);
  std::vector<std::uint32_t> queue;
  // Calls visit(k) for every fluid particle k that row i couples to.
  const auto for_each_coupled = [&](std::size_t i, auto&& visit) {
    const std::size_t first = pairs.offsets[i];
    const auto row = pairs.row(i);
    for (std::size_t m = 0; m < row.size(); ++m) {
      if (!(pair_weight[first + m] > 0.0)) continue;
      const std::uint32_t j = row[m];
      if (j < fluid) {
        visit(j);
        continue;
      }
      const std::size_t b = j - fluid;
      for (std::size_t s = boundary.offsets[b]; s < boundary.offsets[b + 1]; ++s) {
        visit(boundary.fluid[s]);
      }
    }
  };
  for (std::size_t i = 0; i < fluid; ++i) {
    if (!unknown[i]) continue;
    bool grounded = false;
    for_each_coupled(i, [&](std::uint32_t k) { grounded = grounded || !unknown[k]; });
    if (grounded) {
      reached[i] = 1;
      queue.push_back(static_cast<std::uint32_t>(i));
    }
  }
  while (!queue.empty()) {
    const std::uint32_t i = queue.back();
    queue.pop_back();
    for_each_coupled(i, [&](std::uint32_t k) {
      if (unknown[k] && !reached[k]) {
        reached[k] = 1;
        queue.push_back(k);
      }
    });
  }
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < fluid; ++i) {
    if (unknown[i] && !reached[i]) {
      unknown[i] = 0;
      ++dropped;
    }
  }
  return dropped;
}

template <int Dim>
void LeastSquaresOperators<Dim>::fit(const StepGeometry<Dim>& g) {
  const auto& p = g.particles;
  const std::size_t fluid = p.fluid;
  weights_.resize(g.pairs.index.size());
  fitted_.assign(fluid, 0);
  const double scale = g.settings.spacing_m;
  parallel_for(fluid, [&](std::size_t i) {
    thread_local std::vector<FitNeighbour<Dim>> neighbours;
    const std::size_t first = g.pairs.offsets[i];
    const auto row = g.pairs.row(i);
    neighbours.resize(row.size());
    for (std::size_t m = 0; m < row.size(); ++m) {
      for (int d = 0; d < Dim; ++d) {
        neighbours[m].offset[d] = p.position[d][row[m]] - p.position[d][i];
      }
      neighbours[m].weight = g.pair_weight[first + m];
    }
    fitted_[i] = fit_quadratic<Dim>(neighbours, scale,
                                    std::span<FitWeights<Dim>>(weights_).subspan(first, row.size()));
  });
  fitted_count_ = static_cast<std::size_t>(std::count(fitted_.begin(), fitted_.end(), 1));
}

template <int Dim>
void LeastSquaresOperators<Dim>::assemble(const StepGeometry<Dim>& g, std::vector<char>& unknown,
                                          std::span<const double> source,
                                          const BoundaryExtrapolation* boundary,
                                          PoissonSystem& out) {
  if (!boundary) {
    throw std::invalid_argument("least-squares operators: walls must be extrapolated");
  }
  fit(g);
  const std::size_t fluid = g.particles.fluid;
  const double lattice_factor =
      2.0 * Dim / (g.lattice.lambda_m2 * g.lattice.number_density);
  coefficient_.resize(g.pairs.index.size());
  for (std::size_t i = 0; i < fluid; ++i) {
    const std::size_t begin = g.pairs.offsets[i], end = g.pairs.offsets[i + 1];
    bool own = fitted_[i];
    if (own) {
      double negative = 0.0, positive = 0.0;
      for (std::size_t k = begin; k < end; ++k) {
        const double l = weights_[k].laplacian;
        (l < 0.0 ? negative : positive) += std::abs(l);
      }
      own = negative <= least_squares_max_negative_share * positive;
    }
    for (std::size_t k = begin; k < end; ++k) {
      coefficient_[k] = own ? weights_[k].laplacian : lattice_factor * g.pair_weight[k];
    }
  }
  drop_ungrounded_unknowns(g.pairs, g.pair_weight, *boundary, unknown);
  // The fluid with p = 0 (the free surface, and any unknown left out above) takes the
  // first-order gradient.
  on_surface_.resize(fluid);
  for (std::size_t i = 0; i < fluid; ++i) on_surface_[i] = !unknown[i];
  // The coefficients are the Laplacian's own (factor 1): row i reads sum_j L_ij (p_j - p_i).
  assemble_poisson_extrapolated(g.pairs, g.pair_weight, unknown, source, *boundary, 1.0, out,
                                coefficient_);
  out.symmetric = false;
  out.residual_to_compression = 1.0;  // rows are the Laplacian's; the simulation scales by dt^2 / rho
}

template <int Dim>
void LeastSquaresOperators<Dim>::velocity_change(const StepGeometry<Dim>& g, double dt,
                                                 std::array<std::vector<double>, Dim>& change) {
  const auto& p = g.particles;
  const auto& s = g.settings;
  const std::size_t fluid = p.fluid;
  const bool repulsive = s.gradient == PressureGradient::corrected_repulsive;
  const double reach = s.repulsion_distance_spacings * s.spacing_m;
  const double reach2 = reach * reach;
  const double mps_factor = Dim / g.lattice.number_density;
  const double to_velocity = -dt / s.density_kg_m3;
  for (int d = 0; d < Dim; ++d) change[d].resize(fluid);
  parallel_for(fluid, [&](std::size_t i) {
    const std::size_t first = g.pairs.offsets[i];
    const auto row = g.pairs.row(i);
    double lowest = p.pressure[i];
    for (std::size_t m = 0; m < row.size() && repulsive; ++m) {
      if (row[m] < fluid && g.pair_weight[first + m] > 0.0) {
        lowest = std::min(lowest, p.pressure[row[m]]);
      }
    }
    const bool quadratic = fitted_[i] && !on_surface_[i];
    std::array<double, Dim> gradient{}, repulsion{}, standard{};
    std::array<std::array<double, Dim>, Dim> moment{};
    for (std::size_t m = 0; m < row.size(); ++m) {
      const std::uint32_t j = row[m];
      const double w = g.pair_weight[first + m];
      if (!(w > 0.0)) continue;
      const double difference = p.pressure[j] - p.pressure[i];
      if (quadratic) {
        for (int d = 0; d < Dim; ++d) gradient[d] += weights_[first + m].gradient[d] * difference;
      }
      std::array<double, Dim> x{};
      double r2 = 0.0;
      for (int d = 0; d < Dim; ++d) {
        x[d] = p.position[d][j] - p.position[d][i];
        r2 += x[d] * x[d];
      }
      if (r2 == 0.0) continue;
      if (repulsive && r2 < reach2) {
        for (int d = 0; d < Dim; ++d) repulsion[d] += (p.pressure[i] - lowest) * w / r2 * x[d];
      }
      if (!quadratic) {  // the first-order fit and the standard sum, as fallbacks
        for (int d = 0; d < Dim; ++d) standard[d] += difference * w / r2 * x[d];
        for (int a = 0; a < Dim; ++a) {
          for (int b = 0; b < Dim; ++b) moment[a][b] += x[a] * x[b] * w / r2;
        }
      }
    }
    if (!quadratic && !solve_symmetric<Dim>(moment, standard, gradient)) {
      for (int d = 0; d < Dim; ++d) gradient[d] = mps_factor * standard[d];
    }
    for (int d = 0; d < Dim; ++d) {
      change[d][i] = to_velocity * (gradient[d] + mps_factor * repulsion[d]);
    }
  });
}

template class LeastSquaresOperators<2>;
template class LeastSquaresOperators<3>;

}  // namespace swemps::ns

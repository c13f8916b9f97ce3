// The corrected pressure gradient of the MPS operators (mps_operators.hpp) with both pair
// weights (settings.hpp GradientWeights): each balances gravity exactly in a jittered tank,
// and only the kernel's slope makes the gradient the adjoint of the number density's rate of
// change on the lattice, the property that keeps the 3D tank at rest (docs/method.md
// "Gradient weights").

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/ns/lattice.hpp"
#include "swemps/ns/mps_operators.hpp"
#include "swemps/ns/tank.hpp"
#include "../support/ns_fluid_pairs.hpp"

namespace {

using namespace swemps;

constexpr double kSpacing = 0.01, kRho = 1000.0, kG = 9.81;

template <int Dim>
struct Water {
  ns::Particles<Dim> particles;
  neighbors::NeighborList pairs;
  std::vector<double> weight;
  ns::Settings settings;
  ns::LatticeConstants lattice;
  double top = 0.0;  // the top fluid row's height

  ns::StepGeometry<Dim> geometry() const { return {particles, pairs, weight, settings, lattice}; }
};

// A tank `cells` spacings wide along each axis, full of water; the well-balanced scheme's
// settings with the corrected gradient (no repulsion) on the given weights; every fluid
// particle but the top row moved by up to `jitter` l0 along each axis.
template <int Dim>
Water<Dim> make_water(int cells, double jitter, ns::GradientWeights weights) {
  ns::TankSpec<Dim> spec;
  spec.spacing_m = kSpacing;
  for (int d = 0; d < Dim; ++d) spec.interior.upper[d] = cells * kSpacing;
  spec.water.push_back(spec.interior);
  Water<Dim> w;
  w.particles = ns::fill_tank<Dim>(spec);
  for (std::size_t i = 0; i < w.particles.fluid; ++i) {
    w.top = std::max(w.top, w.particles.position[Dim - 1][i]);
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> shift(-jitter * kSpacing, jitter * kSpacing);
  for (std::size_t i = 0; i < w.particles.fluid && jitter > 0.0; ++i) {
    if (w.particles.position[Dim - 1][i] > w.top - 0.5 * kSpacing) continue;
    for (int d = 0; d < Dim; ++d) w.particles.position[d][i] += shift(rng);
  }
  w.settings = ns::scheme_settings(ns::Scheme::well_balanced, Dim);
  w.settings.spacing_m = kSpacing;
  w.settings.gradient = ns::PressureGradient::corrected;
  w.settings.gradient_weights = weights;
  const double support = w.settings.pressure_kernel.support_spacings * kSpacing;
  const auto kernel = kernels::make_kernel<Dim>(w.settings.pressure_kernel.spec, support);
  w.lattice = ns::lattice_constants<Dim>(kernel, kSpacing);
  test::fluid_pairs<Dim>(w.particles, kernel, w.pairs, w.weight);
  return w;
}

// The largest |change - g dt e_z| over the fluid when every particle, boundary included,
// holds the hydrostatic pressure under the top row.
template <int Dim>
double gravity_imbalance(ns::GradientWeights weights) {
  Water<Dim> w = make_water<Dim>(8, 0.2, weights);
  for (std::size_t i = 0; i < w.particles.size(); ++i) {
    w.particles.pressure[i] = kRho * kG * (w.top - w.particles.position[Dim - 1][i]);
  }
  ns::MpsOperators<Dim> operators(w.settings);
  std::array<std::vector<double>, Dim> change;
  const double dt = 1e-3;
  operators.velocity_change(w.geometry(), dt, change);
  double worst = 0.0;
  for (std::size_t i = 0; i < w.particles.fluid; ++i) {
    for (int d = 0; d < Dim; ++d) {
      worst = std::max(worst, std::abs(change[d][i] - (d == Dim - 1 ? kG * dt : 0.0)));
    }
  }
  return worst / (kG * dt);
}

// On the 3D lattice, sum_j p_j dn_j/dt for particles moving with u, against c sum_i u_i . G_i
// (the gradient's pairing with the same fields; c the correction matrix's lattice diagonal),
// for random p and u that vanish wherever a neighbourhood reaches the surface or the walls.
// Returns |left - right| / |left|: zero when the gradient is the density rate's adjoint.
double adjoint_mismatch(ns::GradientWeights weights) {
  constexpr int Dim = 3;
  Water<Dim> w = make_water<Dim>(12, 0.0, weights);
  const auto& p = w.particles;
  const double margin = 4.5 * kSpacing;  // two supports of 2.1 l0
  auto inside = [&](std::size_t i) {
    for (int d = 0; d < Dim; ++d) {
      const double x = p.position[d][i];
      if (x < margin || x > w.top - margin) return false;
    }
    return true;
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::array<std::vector<double>, Dim> u;
  for (auto& component : u) component.assign(p.size(), 0.0);
  w.particles.pressure.assign(p.size(), 0.0);
  for (std::size_t i = 0; i < p.fluid; ++i) {
    if (!inside(i)) continue;
    w.particles.pressure[i] = value(rng);
    for (int d = 0; d < Dim; ++d) u[d][i] = value(rng);
  }
  // The number densities' rate of change, by central differences of the sums themselves.
  const double support = w.settings.pressure_kernel.support_spacings * kSpacing;
  const auto kernel = kernels::make_kernel<Dim>(w.settings.pressure_kernel.spec, support);
  const double step = 1e-7 * kSpacing;
  auto density_at = [&](std::size_t j, double sign) {
    double n = 0.0;
    for (std::uint32_t k : w.pairs.row(j)) {
      double r2 = 0.0;
      for (int d = 0; d < Dim; ++d) {
        const double x = p.position[d][k] + sign * step * u[d][k] -
                         (p.position[d][j] + sign * step * u[d][j]);
        r2 += x * x;
      }
      n += kernels::weight<Dim>(kernel, std::sqrt(r2));
    }
    return n;
  };
  double left = 0.0;
  for (std::size_t j = 0; j < p.fluid; ++j) {
    if (w.particles.pressure[j] == 0.0) continue;
    left += w.particles.pressure[j] * (density_at(j, 1.0) - density_at(j, -1.0)) / (2.0 * step);
  }
  // c: the correction matrix's diagonal on the lattice, from one interior particle's row.
  std::size_t centre = 0;
  while (!inside(centre)) ++centre;
  double c = 0.0;
  const auto row = w.pairs.row(centre);
  for (std::size_t m = 0; m < row.size(); ++m) {
    const double x = p.position[0][row[m]] - p.position[0][centre];
    double r2 = 0.0;
    for (int d = 0; d < Dim; ++d) {
      const double e = p.position[d][row[m]] - p.position[d][centre];
      r2 += e * e;
    }
    if (r2 == 0.0) continue;
    const double r = std::sqrt(r2);
    const double omega =
        weights == ns::GradientWeights::kernel_slope
            ? -std::visit([&](const auto& k) { return k.dw_dr(r); }, kernel) / r
            : w.weight[w.pairs.offsets[centre] + m] / r2;
    c += omega * x * x;
  }
  ns::MpsOperators<Dim> operators(w.settings);
  std::array<std::vector<double>, Dim> change;
  const double dt = 1e-3;
  operators.velocity_change(w.geometry(), dt, change);
  double right = 0.0;
  for (std::size_t i = 0; i < p.fluid; ++i) {
    for (int d = 0; d < Dim; ++d) right += c * u[d][i] * (-kRho * change[d][i] / dt);
  }
  return std::abs(left - right) / std::abs(left);
}

}  // namespace

TEST_CASE("mps operators: either gradient weight balances gravity in a jittered tank",
          "[ns]") {
  for (const auto weights : {ns::GradientWeights::mps, ns::GradientWeights::kernel_slope}) {
    CAPTURE(ns::gradient_weights_name(weights));
    CHECK(gravity_imbalance<2>(weights) <= 1e-10);
    CHECK(gravity_imbalance<3>(weights) <= 1e-10);
  }
}

TEST_CASE("mps operators: the kernel-slope gradient is the number density rate's adjoint",
          "[ns]") {
  // Exact to the central difference's rounding with the kernel's slope; with w / r^2 the two
  // weigh the neighbour shells differently.
  CHECK(adjoint_mismatch(ns::GradientWeights::kernel_slope) <= 1e-6);
  CHECK(adjoint_mismatch(ns::GradientWeights::mps) >= 0.05);
}

// Wall and dummy pressures extrapolated from the fluid, and the Poisson system with them
// eliminated (boundary_pressure.hpp): a hydrostatic field is carried to every boundary
// particle exactly, and the eliminated system is symmetric and holds hydrostatic pressure
// beside the walls with no source at all.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/boundary_pressure.hpp"
#include "swemps/ns/tank.hpp"
#include "../support/ns_fluid_pairs.hpp"

namespace {

using namespace swemps;

constexpr double kSpacing = 0.01, kDepth = 0.1, kRhoG = 1000.0 * 9.81;

struct Tank {
  ns::Particles<2> particles;
  neighbors::NeighborList pairs;
  std::vector<double> weight;
  ns::BoundaryExtrapolation boundary;
};

// A tank 0.1 m long with 0.1 m of water; fluid positions jittered by up to `jitter` l0.
Tank make_tank(double jitter) {
  ns::TankSpec<2> spec;
  spec.spacing_m = kSpacing;
  spec.interior.upper = {0.1, 0.15};
  spec.water.push_back({{0.0, 0.0}, {0.1, kDepth}});
  Tank t;
  t.particles = ns::fill_tank<2>(spec);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> shift(-jitter * kSpacing, jitter * kSpacing);
  for (std::size_t i = 0; i < t.particles.fluid; ++i) {
    for (int d = 0; d < 2; ++d) t.particles.position[d][i] += shift(rng);
  }
  test::fluid_pairs(t.particles, kernels::make_kernel<2>(kernels::KernelSpec{}, 2.1 * kSpacing),
                    t.pairs, t.weight);
  ns::build_boundary_extrapolation(t.pairs, t.weight, t.particles.fluid, t.particles.size(),
                                   t.particles.position[1], kRhoG, t.boundary);
  return t;
}

double hydrostatic(double z) { return kRhoG * (kDepth - z); }

}  // namespace

TEST_CASE("boundary pressure: a hydrostatic field reaches every wall and dummy exactly",
          "[ns][boundary]") {
  const Tank t = make_tank(0.2);
  const auto& p = t.particles;
  const ns::BoundaryExtrapolation& boundary = t.boundary;
  std::vector<double> pressure(p.size(), -1.0);
  for (std::size_t i = 0; i < p.fluid; ++i) pressure[i] = hydrostatic(p.position[1][i]);
  ns::extrapolate_boundary_pressure(boundary, pressure);
  std::size_t reached = 0;
  for (std::size_t b = p.fluid; b < p.size(); ++b) {
    const std::size_t m = b - p.fluid;
    if (boundary.offsets[m + 1] == boundary.offsets[m]) {
      CHECK(pressure[b] == 0.0);  // no water in reach
      continue;
    }
    ++reached;
    double total = 0.0;
    for (std::size_t s = boundary.offsets[m]; s < boundary.offsets[m + 1]; ++s) {
      total += boundary.alpha[s];
    }
    CHECK(total == Approx(1.0).epsilon(1e-12));
    // Side walls beside the surface, the floor and the corners alike; the field spans
    // rho g H ~ 1 kPa, so 1e-9 Pa is rounding.
    CHECK(pressure[b] == Approx(hydrostatic(p.position[1][b])).margin(1e-9));
  }
  // The floor's wall row and first dummy row (10 each) and the two side walls' (two
  // columns of 10 each): 60 particles with water in reach.
  CHECK(reached >= 60);
}

TEST_CASE("boundary pressure: the eliminated system is symmetric and balances hydrostatics",
          "[ns][boundary]") {
  const Tank t = make_tank(0.0);
  const auto& p = t.particles;
  const ns::BoundaryExtrapolation& boundary = t.boundary;
  // The top row is the free surface (Dirichlet, p = 0 = hydrostatic at its centre, taken as
  // the level H' of the field below); no source: at rest nothing is compressed.
  const double top = kDepth - 0.5 * kSpacing;
  std::vector<char> unknown(p.fluid, 0);
  for (std::size_t i = 0; i < p.fluid; ++i) unknown[i] = p.position[1][i] < top - 1e-9;
  const std::vector<double> source(p.fluid, 0.0);
  ns::PoissonSystem system;
  ns::assemble_poisson_extrapolated(t.pairs, t.weight, unknown, source, boundary, 1.0, system);
  const Eigen::SparseMatrix<double> a = system.matrix;
  CHECK((a - Eigen::SparseMatrix<double>(a.transpose())).norm() <= 1e-12 * a.norm());
  Eigen::VectorXd field(a.rows());
  for (Eigen::Index k = 0; k < a.rows(); ++k) {
    field[k] = kRhoG * (top - p.position[1][system.particle_of_unknown[k]]);
  }
  const Eigen::VectorXd residual = a * field - system.rhs;
  // Every row whose stencil lies below the surface's reach (2.1 l0): rows beside the floor
  // and the walls, where the wall particles' pressure had to come from somewhere, included.
  std::size_t checked = 0, beside_wall = 0;
  for (Eigen::Index k = 0; k < a.rows(); ++k) {
    const std::size_t i = system.particle_of_unknown[k];
    if (p.position[1][i] > top - 2.1 * kSpacing) continue;
    ++checked;
    const double x = p.position[0][i], z = p.position[1][i];
    beside_wall += z < 2 * kSpacing || x < 2 * kSpacing || x > 0.1 - 2 * kSpacing;
    // The row's entries are weights ~1 times pressures ~1 kPa.
    CHECK(residual[k] == Approx(0.0).margin(1e-8));
  }
  CHECK(checked > 50);
  CHECK(beside_wall > 20);
}

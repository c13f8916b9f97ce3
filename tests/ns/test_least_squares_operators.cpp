// The least-squares pressure operators (least_squares_operators.hpp) on a tank of jittered
// water: with no source their Poisson system holds the hydrostatic pressure beside the walls
// and under the surface, their gradient balances gravity exactly, and a group of unknowns no
// surface reaches is left out.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/boundary_pressure.hpp"
#include "swemps/ns/lattice.hpp"
#include "swemps/ns/incomplete_lu.hpp"
#include "swemps/ns/least_squares_operators.hpp"
#include "swemps/ns/tank.hpp"
#include "../support/ns_fluid_pairs.hpp"

namespace {

using namespace swemps;

constexpr double kSpacing = 0.01, kRhoG = 1000.0 * 9.81;

struct Tank {
  ns::Particles<2> particles;
  neighbors::NeighborList pairs;
  std::vector<double> weight;
  ns::BoundaryExtrapolation boundary;
  ns::Settings settings;
  ns::LatticeConstants lattice;
  double surface_z = 0.0;  // the top row's height: p = 0 there
};

// A tank 0.1 m long with 0.1 m of water (10 x 10 particles), Sheu's quartic kernel at 2.1 l0;
// every fluid particle but the top row moved by up to 0.2 l0 along each axis.
Tank make_tank() {
  ns::TankSpec<2> spec;
  spec.spacing_m = kSpacing;
  spec.interior.upper = {0.1, 0.15};
  spec.water.push_back({{0.0, 0.0}, {0.1, 0.1}});
  Tank t;
  t.particles = ns::fill_tank<2>(spec);
  for (std::size_t i = 0; i < t.particles.fluid; ++i) {
    t.surface_z = std::max(t.surface_z, t.particles.position[1][i]);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> shift(-0.2 * kSpacing, 0.2 * kSpacing);
  for (std::size_t i = 0; i < t.particles.fluid; ++i) {
    if (t.particles.position[1][i] > t.surface_z - 0.5 * kSpacing) continue;
    for (int d = 0; d < 2; ++d) t.particles.position[d][i] += shift(rng);
  }
  t.settings = ns::scheme_settings(ns::Scheme::least_squares, 2);
  t.settings.spacing_m = kSpacing;
  t.settings.gradient = ns::PressureGradient::corrected;  // no repulsion between close pairs
  const auto kernel =
      kernels::make_kernel<2>(t.settings.pressure_kernel.spec, 2.1 * kSpacing);
  t.lattice = ns::lattice_constants<2>(kernel, kSpacing);
  test::fluid_pairs(t.particles, kernel, t.pairs, t.weight);
  ns::build_boundary_extrapolation(t.pairs, t.weight, t.particles.fluid, t.particles.size(),
                                   t.particles.position[1], kRhoG, t.boundary);
  return t;
}

ns::StepGeometry<2> geometry(const Tank& t) {
  return {t.particles, t.pairs, t.weight, t.settings, t.lattice};
}

// Every particle below the top row is an unknown.
std::vector<char> below_surface(const Tank& t) {
  std::vector<char> unknown(t.particles.fluid, 0);
  for (std::size_t i = 0; i < t.particles.fluid; ++i) {
    unknown[i] = t.particles.position[1][i] < t.surface_z - 0.5 * kSpacing;
  }
  return unknown;
}

double hydrostatic(const Tank& t, double z) { return kRhoG * (t.surface_z - z); }

}  // namespace

TEST_CASE("least-squares operators: no source holds hydrostatic pressure in a jittered tank",
          "[ns][least-squares]") {
  Tank t = make_tank();
  ns::LeastSquaresOperators<2> operators;
  std::vector<char> unknown = below_surface(t);
  const std::vector<double> source(t.particles.fluid, 0.0);
  ns::PoissonSystem system;
  operators.assemble(geometry(t), unknown, source, &t.boundary, system);
  REQUIRE(system.matrix.rows() == 90);
  CHECK(operators.fitted() == t.particles.fluid);
  CHECK_FALSE(system.symmetric);
  // Not symmetric indeed: the fit's weights of i on j and of j on i differ.
  const Eigen::SparseMatrix<double> transpose = system.matrix.transpose();
  CHECK((Eigen::SparseMatrix<double>(system.matrix) - transpose).norm() >
        1e-3 * system.matrix.norm());

  // The hydrostatic field satisfies every row (the walls' part of it moves to the
  // right-hand side through their extrapolation): the Laplacian of a linear field is 0.
  Eigen::VectorXd exact(system.matrix.rows());
  for (Eigen::Index k = 0; k < exact.size(); ++k) {
    exact[k] = hydrostatic(t, t.particles.position[1][system.particle_of_unknown[k]]);
  }
  CHECK((system.matrix * exact - system.rhs).norm() <= 1e-10 * system.rhs.norm());

  // BiCGSTAB with the incomplete LU finds it from nothing.
  ns::PoissonSettings settings;
  settings.relative_tolerance = 1e-12;
  ns::PoissonSolver solver(settings);
  Eigen::VectorXd pressure = Eigen::VectorXd::Zero(exact.size());
  const auto report = solver.solve(system, pressure);
  CHECK(report.converged);
  CHECK((pressure - exact).norm() <= 1e-8 * exact.norm());

  // Its gradient lifts every fluid particle by exactly g dt: at rest gravity is balanced,
  // in the jittered interior (the quadratic fit) and on and under the surface (the linear one).
  for (std::size_t i = 0; i < t.particles.fluid; ++i) {
    t.particles.pressure[i] = unknown[i] ? hydrostatic(t, t.particles.position[1][i]) : 0.0;
  }
  ns::extrapolate_boundary_pressure(t.boundary, t.particles.pressure);
  std::array<std::vector<double>, 2> change;
  const double dt = 1e-3;
  operators.velocity_change(geometry(t), dt, change);
  double worst = 0.0;
  for (std::size_t i = 0; i < t.particles.fluid; ++i) {
    worst = std::max(worst, std::abs(change[0][i]));
    worst = std::max(worst, std::abs(change[1][i] - 9.81 * dt));
  }
  CHECK(worst <= 1e-12);
}

TEST_CASE("least-squares operators: unknowns no free surface reaches are left out",
          "[ns][least-squares]") {
  Tank t = make_tank();
  // Every fluid particle an unknown: nothing fixes the pressure's level.
  std::vector<char> unknown(t.particles.fluid, 1);
  CHECK(ns::drop_ungrounded_unknowns(t.pairs, t.weight, t.boundary, unknown) ==
        t.particles.fluid);
  CHECK(std::count(unknown.begin(), unknown.end(), 1) == 0);
  // With the top row on the surface every unknown is reached.
  unknown = below_surface(t);
  CHECK(ns::drop_ungrounded_unknowns(t.pairs, t.weight, t.boundary, unknown) == 0);
}

TEST_CASE("zero-fill incomplete LU is exact on a tridiagonal matrix and drives BiCGSTAB",
          "[ns][poisson][least-squares]") {
  // Tridiagonal, not symmetric: no fill, so the zero-fill factors are the exact LU.
  const int n = 40;
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> a(n, n);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 3.0 + 0.02 * i);
    if (i > 0) entries.emplace_back(i, i - 1, -1.3);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -0.6);
  }
  a.setFromTriplets(entries.begin(), entries.end());
  ns::ZeroFillIncompleteLU factor;
  factor.compute(a);
  REQUIRE(factor.info() == Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -2.0, 1.0);
  const Eigen::VectorXd x = factor.solve(b);
  CHECK((a * x - b).norm() <= 1e-12 * b.norm());

  ns::PoissonSystem system;
  system.matrix = a;
  system.rhs = b;
  system.particle_of_unknown.resize(n);
  system.symmetric = false;
  ns::PoissonSettings settings;
  settings.relative_tolerance = 1e-12;
  ns::PoissonSolver solver(settings);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  const auto report = solver.solve(system, y);
  CHECK(report.converged);
  CHECK(report.iterations <= 1);
  CHECK((a * y - b).norm() <= 1e-11 * b.norm());

  // A zero pivot is replaced (the factors still exist), a value that is not finite reported.
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> singular(2, 2);
  std::vector<Eigen::Triplet<double>> s{{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 1.0}, {1, 1, 2.0}};
  singular.setFromTriplets(s.begin(), s.end());
  factor.compute(singular);
  CHECK(factor.info() == Eigen::Success);
  CHECK(factor.replaced_pivots() == 1);
  singular.coeffRef(1, 1) = std::nan("");
  factor.compute(singular);
  CHECK(factor.info() == Eigen::NumericalIssue);
}

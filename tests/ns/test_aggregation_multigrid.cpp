// The smoothed-aggregation multigrid preconditioner (aggregation_multigrid.hpp): exact on a
// system small enough to factorise, symmetric for a symmetric matrix (conjugate gradients
// needs it), and an iteration count that stays about flat as the grid is refined, where the
// zero-fill incomplete Cholesky's grows.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "swemps/ns/aggregation_multigrid.hpp"
#include "swemps/ns/poisson.hpp"

namespace {

using namespace swemps;
using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

// The 5-point Laplacian on an n x n grid with p = 0 beyond its edges (the MPS matrix's
// structure: an M-matrix, weakly diagonally dominant, strictly at the Dirichlet edges), with
// an optional first-order upwind drift that makes it non-symmetric.
Matrix grid_laplacian(int n, double drift = 0.0) {
  Matrix a(n * n, n * n);
  std::vector<Eigen::Triplet<double>> entries;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int i = y * n + x;
      entries.emplace_back(i, i, 4.0 + drift);
      if (x > 0) entries.emplace_back(i, i - 1, -1.0 - drift);
      if (x + 1 < n) entries.emplace_back(i, i + 1, -1.0);
      if (y > 0) entries.emplace_back(i, i - n, -1.0);
      if (y + 1 < n) entries.emplace_back(i, i + n, -1.0);
    }
  }
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

int iterations(const Matrix& a, ns::Preconditioner preconditioner, bool symmetric,
               double tolerance) {
  ns::PoissonSystem system;
  system.matrix = a;
  system.rhs = Eigen::VectorXd::Ones(a.rows());
  system.particle_of_unknown.resize(static_cast<std::size_t>(a.rows()));
  system.symmetric = symmetric;
  ns::PoissonSettings settings;
  settings.preconditioner = preconditioner;
  settings.relative_tolerance = tolerance;
  ns::PoissonSolver solver(settings);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(a.rows());
  const auto report = solver.solve(system, p);
  REQUIRE(report.converged);
  CHECK((system.rhs - a * p).norm() <= 2.0 * tolerance * system.rhs.norm());
  return report.iterations;
}

}  // namespace

TEST_CASE("aggregation multigrid is exact on a system it factorises whole", "[ns][poisson]") {
  const Matrix a = grid_laplacian(9);  // 81 unknowns: one level, the dense LU
  ns::AggregationMultigrid mg;
  mg.compute(a);
  REQUIRE(mg.info() == Eigen::Success);
  CHECK(mg.level_sizes().size() == 1);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = mg.solve(b);
  CHECK((a * x - b).norm() <= 1e-12 * b.norm());
}

TEST_CASE("aggregation multigrid coarsens and is a symmetric preconditioner", "[ns][poisson]") {
  const Matrix a = grid_laplacian(64);
  ns::AggregationMultigrid mg;
  mg.compute(a);
  REQUIRE(mg.info() == Eigen::Success);
  const auto& levels = mg.level_sizes();
  REQUIRE(levels.size() >= 3);
  CHECK(levels.front().unknowns == 64 * 64);
  for (std::size_t l = 1; l < levels.size(); ++l) {
    CHECK(levels[l].unknowns * 3 < levels[l - 1].unknowns);  // aggregates of several unknowns
  }
  CHECK(levels.back().unknowns <= 100);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd u(a.rows()), v(a.rows());
  for (Eigen::Index k = 0; k < a.rows(); ++k) {
    u[k] = value(random);
    v[k] = value(random);
  }
  const Eigen::VectorXd mu = mg.solve(u), mv = mg.solve(v);
  CHECK(std::abs(u.dot(mv) - v.dot(mu)) <= 1e-12 * std::abs(u.dot(mv)));
  CHECK(u.dot(mu) > 0.0);  // positive on these vectors
}

TEST_CASE("aggregation multigrid keeps the iteration count flat under refinement",
          "[ns][poisson]") {
  const int coarse_mg = iterations(grid_laplacian(48), ns::Preconditioner::multigrid, true, 1e-8);
  const int fine_mg = iterations(grid_laplacian(192), ns::Preconditioner::multigrid, true, 1e-8);
  const int coarse_ic =
      iterations(grid_laplacian(48), ns::Preconditioner::incomplete_cholesky, true, 1e-8);
  const int fine_ic =
      iterations(grid_laplacian(192), ns::Preconditioner::incomplete_cholesky, true, 1e-8);
  // Four times the resolution: IC(0) needs about four times the iterations (they grow like
  // 1/h), multigrid fewer than twice (V-cycles of smoothed aggregation grow slowly with the
  // number of levels).
  CHECK(fine_ic >= 3 * coarse_ic);
  CHECK(fine_mg < 2 * coarse_mg);
  CHECK(fine_mg * 3 < fine_ic);
}

TEST_CASE("aggregation multigrid preconditions BiCGSTAB on a non-symmetric matrix",
          "[ns][poisson]") {
  const int n = iterations(grid_laplacian(96, 0.5), ns::Preconditioner::multigrid, false, 1e-8);
  CHECK(n < iterations(grid_laplacian(96, 0.5), ns::Preconditioner::diagonal, false, 1e-8) / 4);
}

TEST_CASE("the Poisson solver keeps a multigrid setup across solves and renumberings",
          "[ns][poisson]") {
  // Unknown k is particle k at first; the second system is the same grid with every
  // coefficient changed by a few per cent, and the particles renumbered at random.
  const int side = 40, n = side * side;
  ns::PoissonSettings settings;
  settings.preconditioner = ns::Preconditioner::multigrid;
  settings.relative_tolerance = 1e-8;
  settings.multigrid_setup_solves = 3;
  ns::PoissonSolver solver(settings);
  ns::PoissonSystem system;
  system.matrix = grid_laplacian(side);
  system.rhs = Eigen::VectorXd::Ones(n);
  for (int k = 0; k < n; ++k) system.particle_of_unknown.push_back(static_cast<std::uint32_t>(k));
  Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
  const auto first = solver.solve(system, p);
  REQUIRE(first.converged);
  CHECK_FALSE(first.setup_kept);

  std::vector<std::uint32_t> old_of_new(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    old_of_new[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(k);
  std::mt19937 random(3);
  std::shuffle(old_of_new.begin(), old_of_new.end(), random);
  solver.follow_renumbering(old_of_new);
  // The unknowns stay in their order (the same grid); their particles have new labels. A
  // solver that did not follow them would take its prolongation's rows for the wrong
  // unknowns, and need many more iterations.
  for (int k = 0; k < n; ++k) {
    system.particle_of_unknown[old_of_new[static_cast<std::size_t>(k)]] =
        static_cast<std::uint32_t>(k);
  }
  // Weaker couplings by up to 3 %, symmetric and still diagonally dominant.
  for (int i = 0; i < n; ++i) {
    for (Matrix::InnerIterator it(system.matrix, i); it; ++it) {
      if (it.col() != i) it.valueRef() *= 1.0 - 0.015 * (1.0 + std::sin(i + it.col()));
    }
  }
  p.setZero();
  const auto kept = solver.solve(system, p);
  REQUIRE(kept.converged);
  CHECK(kept.setup_kept);
  CHECK(kept.iterations <= first.iterations + 3);  // the kept levels still fit
  CHECK((system.rhs - system.matrix * p).norm() <= 2e-8 * system.rhs.norm());

  // The labels now mean other particles: what the setup kept would not fit.
  solver.forget_kept_setup();
  p.setZero();
  CHECK_FALSE(solver.solve(system, p).setup_kept);
  // Three solves at most on one setup.
  p.setZero();
  CHECK(solver.solve(system, p).setup_kept);
  p.setZero();
  CHECK(solver.solve(system, p).setup_kept);
  p.setZero();
  CHECK_FALSE(solver.solve(system, p).setup_kept);
}

// The pressure Poisson system of the Navier-Stokes mode: its assembly against a direct,
// independent evaluation of the MPS Laplacian, and its solution against a pressure field
// chosen in advance (a known problem solved exactly).

#include <Eigen/IterativeLinearSolvers>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/ns/incomplete_cholesky.hpp"
#include "swemps/ns/poisson.hpp"

namespace {

using swemps::neighbors::NeighborList;
using namespace swemps::ns;

// A jittered square patch of particles; the outer two rings are free surface (Dirichlet,
// p = 0), the rest are unknowns.
struct Patch {
  std::array<std::vector<double>, 2> x;
  std::vector<char> unknown;
  NeighborList pairs;
  std::vector<double> weight;  // per pair
  double support = 0.0;
};

Patch make_patch(int n, double jitter, const swemps::kernels::AnyKernel<2>& kernel) {
  Patch p;
  p.support = swemps::kernels::support<2>(kernel);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-jitter, jitter);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      p.x[0].push_back(i + shift(rng));
      p.x[1].push_back(j + shift(rng));
      const bool ring = i < 2 || j < 2 || i >= n - 2 || j >= n - 2;
      p.unknown.push_back(ring ? 0 : 1);
    }
  }
  swemps::neighbors::Coordinates<2> coords{p.x[0], p.x[1]};
  swemps::neighbors::CellList<2> cells;
  cells.build(coords, p.support);
  swemps::neighbors::build_neighbor_list<2>(cells, coords, p.x[0].size(), p.support, p.pairs);
  for (std::size_t i = 0; i < p.pairs.row_count(); ++i) {
    for (std::uint32_t j : p.pairs.row(i)) {
      p.weight.push_back(swemps::kernels::weight<2>(
          kernel, std::hypot(p.x[0][j] - p.x[0][i], p.x[1][j] - p.x[1][i])));
    }
  }
  return p;
}

// The MPS Laplacian (2d/(lambda n0)) sum_j (p_j - p_i) w_ij, summed straight from the
// positions with an O(N^2) loop: the reference the assembled matrix must reproduce.
std::vector<double> direct_laplacian(const Patch& patch,
                                     const swemps::kernels::AnyKernel<2>& kernel,
                                     const std::vector<double>& pressure, double factor) {
  const std::size_t n = patch.x[0].size();
  std::vector<double> out(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const double r = std::hypot(patch.x[0][j] - patch.x[0][i], patch.x[1][j] - patch.x[1][i]);
      out[i] += (pressure[j] - pressure[i]) * swemps::kernels::weight<2>(kernel, r);
    }
    out[i] *= factor;
  }
  return out;
}

}  // namespace

TEST_CASE("poisson: a two-unknown system has the entries of the MPS Laplacian", "[ns][poisson]") {
  // Particles 0 and 1 are unknowns, 2 is free surface, 3 is a dummy (candidate_count = 3).
  NeighborList pairs;
  pairs.offsets = {0, 3, 5, 7, 8};
  pairs.index = {1, 2, 3, 0, 2, 0, 1, 0};
  const std::vector<double> weight{2.0, 0.5, 9.0, 2.0, 1.5, 0.5, 1.5, 9.0};
  const std::vector<char> unknown{1, 1, 0, 0};
  const std::vector<double> source{4.0, -2.0, 0.0, 0.0};
  PoissonSystem system;
  assemble_poisson(pairs, weight, unknown, source, 3, 2.0, system);
  REQUIRE(system.matrix.rows() == 2);
  // Row 0: diagonal w01 + w02 (the dummy is left out), off-diagonal -w01.
  CHECK(system.matrix.coeff(0, 0) == 2.5);
  CHECK(system.matrix.coeff(0, 1) == -2.0);
  CHECK(system.matrix.coeff(1, 0) == -2.0);
  CHECK(system.matrix.coeff(1, 1) == 3.5);
  // rhs = -b / factor.
  CHECK(system.rhs[0] == -2.0);
  CHECK(system.rhs[1] == 1.0);
  CHECK(system.particle_of_unknown == std::vector<std::uint32_t>{0, 1});
}

TEST_CASE(
    "poisson: assembly reproduces the direct Laplacian and the solve recovers a chosen "
    "pressure",
    "[ns][poisson]") {
  const auto [name, support] = GENERATE(std::pair{"standard", 2.1}, std::pair{"sheu-quartic", 2.0},
                                        std::pair{"hyperbolic", 4.0});
  const auto preconditioner = GENERATE(Preconditioner::incomplete_cholesky,
                                       Preconditioner::diagonal, Preconditioner::multigrid);
  CAPTURE(name, support, static_cast<int>(preconditioner));
  swemps::kernels::KernelSpec spec{*swemps::kernels::kernel_type_from_name(name), 4.0, 1.0};
  const auto kernel = swemps::kernels::make_kernel<2>(spec, support);
  const Patch patch = make_patch(14, 0.2, kernel);
  const std::size_t n = patch.x[0].size();

  // Any pressure on the unknowns, zero on the surface ring.
  std::vector<double> chosen(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (patch.unknown[i]) chosen[i] = 100.0 + 30.0 * std::sin(patch.x[0][i]) * patch.x[1][i];
  }
  const double factor = 0.37;
  const auto source = direct_laplacian(patch, kernel, chosen, factor);

  PoissonSystem system;
  assemble_poisson(patch.pairs, patch.weight, patch.unknown, source, n, factor, system);
  // The matrix applied to the chosen pressure gives the right-hand side: the assembly is
  // the Laplacian (up to the factor -1/factor), row by row.
  Eigen::VectorXd p(system.matrix.rows());
  for (Eigen::Index k = 0; k < p.size(); ++k) p[k] = chosen[system.particle_of_unknown[k]];
  const Eigen::VectorXd applied = system.matrix * p;
  CHECK((applied - system.rhs).norm() <= 1e-12 * system.rhs.norm());
  // Symmetric, as conjugate gradients require.
  const Eigen::SparseMatrix<double> transpose = system.matrix.transpose();
  CHECK((Eigen::SparseMatrix<double>(system.matrix) - transpose).norm() == 0.0);

  PoissonSettings settings;
  settings.preconditioner = preconditioner;
  settings.relative_tolerance = 1e-13;
  PoissonSolver solver(settings);
  Eigen::VectorXd guess = Eigen::VectorXd::Zero(p.size());
  const auto report = solver.solve(system, guess);
  CHECK(report.converged);
  if (preconditioner == Preconditioner::multigrid) {
    // A patch this small is one level, factorised whole: the first update is exact (Eigen's
    // conjugate gradients count an update that converges as no iteration).
    CHECK(report.iterations <= 1);
  } else {
    CHECK(report.iterations > 0);
  }
  // Relative residual 1e-13 and a condition number of order 1e2-1e3 for this patch: the
  // pressure is recovered to well under 1e-9 of its size.
  CHECK((guess - p).norm() <= 1e-9 * p.norm());
}

TEST_CASE("poisson: a zero right-hand side gives zero pressure without iterating",
          "[ns][poisson]") {
  NeighborList pairs;
  pairs.offsets = {0, 1, 2};
  pairs.index = {1, 0};
  PoissonSystem system;
  assemble_poisson(pairs, std::vector<double>{1.0, 1.0}, std::vector<char>{1, 0},
                   std::vector<double>{0.0, 0.0}, 2, 1.0, system);
  PoissonSolver solver(PoissonSettings{});
  Eigen::VectorXd guess = Eigen::VectorXd::Constant(1, 5.0);
  const auto report = solver.solve(system, guess);
  CHECK(report.iterations == 0);
  CHECK(guess[0] == 0.0);
}

TEST_CASE("zero-fill incomplete Cholesky is exact on a tridiagonal M-matrix", "[ns][poisson]") {
  // A tridiagonal matrix has no fill, so the zero-fill factor is the exact Cholesky factor and
  // preconditioned conjugate gradients must converge in one iteration.
  const int n = 50;
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> a(n, n);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0 + 0.01 * i);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0);
  }
  a.setFromTriplets(entries.begin(), entries.end());
  ZeroFillIncompleteCholesky factor;
  factor.compute(a);
  REQUIRE(factor.info() == Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 3.0);
  const Eigen::VectorXd x = factor.solve(b);
  CHECK((a * x - b).norm() <= 1e-12 * b.norm());

  Eigen::ConjugateGradient<decltype(a), Eigen::Lower | Eigen::Upper, ZeroFillIncompleteCholesky> cg;
  cg.setTolerance(1e-12);
  cg.compute(a);
  const Eigen::VectorXd y = cg.solve(b);
  CHECK(cg.iterations() <= 1);
  CHECK((a * y - b).norm() <= 1e-11 * b.norm());
}

TEST_CASE("zero-fill incomplete Cholesky reports a matrix that is not positive definite",
          "[ns][poisson]") {
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> a(2, 2);
  std::vector<Eigen::Triplet<double>> entries{{0, 0, 1.0}, {0, 1, -2.0}, {1, 0, -2.0}, {1, 1, 1.0}};
  a.setFromTriplets(entries.begin(), entries.end());
  ZeroFillIncompleteCholesky factor;
  factor.compute(a);
  CHECK(factor.info() == Eigen::NumericalIssue);
}

TEST_CASE("poisson: the compression rule stops at the compression left asked for",
          "[ns][poisson]") {
  // A 1D Laplacian's rows (Dirichlet at both ends), each residual entry worth 1e-3 of
  // compression: asking for 1e-9 root mean square stops there, and no earlier than the
  // relative rule alone would for the same |r|.
  const int n = 200;
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> a(n, n);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0);
  }
  a.setFromTriplets(entries.begin(), entries.end());
  PoissonSystem system;
  system.matrix = a;
  system.rhs = Eigen::VectorXd::Ones(n);
  system.particle_of_unknown.resize(n);
  system.residual_to_compression = 1e-3;
  for (const double wanted : {1e-6, 1e-9}) {
    PoissonSettings settings;
    settings.preconditioner = Preconditioner::diagonal;
    settings.compression_tolerance = wanted;
    PoissonSolver solver(settings);
    Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
    const auto report = solver.solve(system, p);
    CAPTURE(wanted, report.iterations);
    CHECK(report.converged);
    const double left =
        (system.rhs - a * p).norm() * system.residual_to_compression / std::sqrt(double(n));
    CHECK(left <= 1.01 * wanted);
    CHECK(report.compression_left == Approx(left).epsilon(0.01));
  }
  PoissonSettings bad;
  bad.compression_tolerance = -1.0;
  CHECK_THROWS_AS(PoissonSolver(bad), std::invalid_argument);
}

#include "swemps/ns/poisson.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "swemps/ns/aggregation_multigrid.hpp"
#include "swemps/ns/incomplete_cholesky.hpp"
#include "swemps/ns/incomplete_lu.hpp"

namespace swemps::ns {

namespace {

// Sorts a row's (column, value) entries by column. Insertion sort: the neighbour list visits
// cells in order and the fluid is sorted by cell, so rows arrive nearly sorted and this is
// close to one pass (measured: a tenth less assembly time than std::sort on the 20,000
// particle dam break).
void sort_row(std::vector<std::pair<int, double>>& row) {
  for (std::size_t a = 1; a < row.size(); ++a) {
    const auto entry = row[a];
    std::size_t b = a;
    for (; b > 0 && row[b - 1].first > entry.first; --b) row[b] = row[b - 1];
    row[b] = entry;
  }
}

}  // namespace

std::vector<std::int32_t> number_unknowns(std::span<const char> unknown, std::size_t count,
                                          PoissonSystem& out) {
  std::vector<std::int32_t> unknown_of_particle(count, -1);
  out.particle_of_unknown.clear();
  for (std::size_t i = 0; i < count; ++i) {
    if (unknown[i]) {
      unknown_of_particle[i] = static_cast<std::int32_t>(out.particle_of_unknown.size());
      out.particle_of_unknown.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return unknown_of_particle;
}

void assemble_poisson(const neighbors::NeighborList& pairs, std::span<const double> pair_weight,
                      std::span<const char> unknown, std::span<const double> source,
                      std::size_t candidate_count, double laplacian_factor, PoissonSystem& out) {
  if (pair_weight.size() != pairs.index.size() || unknown.size() < candidate_count ||
      source.size() < candidate_count || pairs.row_count() < candidate_count) {
    throw std::invalid_argument("poisson: inputs do not match the neighbour list");
  }
  if (!(laplacian_factor > 0.0)) throw std::invalid_argument("poisson: laplacian factor <= 0");
  const std::vector<std::int32_t> unknown_of_particle =
      number_unknowns(unknown, candidate_count, out);
  const auto n = static_cast<int>(out.particle_of_unknown.size());

  // Rows in compressed form, written straight into the matrix's own arrays: one pass counts
  // the entries, the next fills them with columns in ascending order (the incomplete
  // Cholesky factorisation needs sorted rows).
  std::vector<int> row_start(static_cast<std::size_t>(n) + 1, 0);
  for (int k = 0; k < n; ++k) {
    int count = 1;  // the diagonal
    for (std::uint32_t j : pairs.row(out.particle_of_unknown[static_cast<std::size_t>(k)])) {
      if (j < candidate_count && unknown_of_particle[j] >= 0) ++count;
    }
    row_start[static_cast<std::size_t>(k) + 1] = row_start[static_cast<std::size_t>(k)] + count;
  }
  auto& a = out.matrix;
  a.resize(n, n);
  a.resizeNonZeros(row_start.back());
  std::copy(row_start.begin(), row_start.end(), a.outerIndexPtr());
  out.rhs.resize(n);
  const double to_system = -1.0 / laplacian_factor;
  std::vector<std::pair<int, double>> row;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = out.particle_of_unknown[static_cast<std::size_t>(k)];
    row.clear();
    double diagonal = 0.0;
    const std::size_t first = pairs.offsets[i];
    const auto neighbours = pairs.row(i);
    for (std::size_t m = 0; m < neighbours.size(); ++m) {
      const std::uint32_t j = neighbours[m];
      if (j >= candidate_count) continue;  // a dummy
      const double w = pair_weight[first + m];
      diagonal += w;
      if (unknown_of_particle[j] >= 0) row.emplace_back(unknown_of_particle[j], -w);
    }
    row.emplace_back(k, diagonal);
    sort_row(row);
    int slot = row_start[static_cast<std::size_t>(k)];
    for (const auto& [column, value] : row) {
      a.innerIndexPtr()[slot] = column;
      a.valuePtr()[slot] = value;
      ++slot;
    }
    out.rhs[k] = to_system * source[i];
  }
}

struct PoissonSolver::Impl {
  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  PoissonSettings settings;
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper,
                           Eigen::DiagonalPreconditioner<double>>
      diagonal;
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, ZeroFillIncompleteCholesky>
      cholesky;
  Eigen::BiCGSTAB<Matrix, Eigen::DiagonalPreconditioner<double>> general_diagonal;
  Eigen::BiCGSTAB<Matrix, ZeroFillIncompleteLU> general_lu;
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, AggregationMultigrid> multigrid;
  Eigen::BiCGSTAB<Matrix, AggregationMultigrid> general_multigrid;

  // The multigrid setup kept across solves (PoissonSettings::multigrid_setup_solves): the
  // unknown each particle was at the last full setup, and what that solve took.
  struct KeptSetup {
    bool valid = false;
    bool symmetric = true;
    std::vector<std::int32_t> unknown_of_particle;
    int iterations = 0;  // of the solve that set up
    int solves = 0;      // since then, that one included
  } kept;

  // Asks `preconditioner` to keep its setup for `system` when the rule allows it.
  void offer_kept_setup(const PoissonSystem& system, AggregationMultigrid& preconditioner,
                        int last_iterations) {
    if (!kept.valid || kept.symmetric != system.symmetric ||
        kept.solves >= settings.multigrid_setup_solves ||
        last_iterations > 2 * kept.iterations + 2) {
      return;
    }
    std::vector<std::int32_t> setup_row(system.particle_of_unknown.size(), -1);
    for (std::size_t k = 0; k < setup_row.size(); ++k) {
      const std::uint32_t i = system.particle_of_unknown[k];
      if (i < kept.unknown_of_particle.size()) setup_row[k] = kept.unknown_of_particle[i];
    }
    preconditioner.keep_setup_for_next(std::move(setup_row));
  }
  void note_setup(const PoissonSystem& system, const AggregationMultigrid& preconditioner,
                  int iterations) {
    if (preconditioner.kept_setup()) {
      ++kept.solves;
      return;
    }
    kept.valid = true;
    kept.symmetric = system.symmetric;
    kept.iterations = iterations;
    kept.solves = 1;
    std::uint32_t highest = 0;
    for (const std::uint32_t i : system.particle_of_unknown) highest = std::max(highest, i);
    kept.unknown_of_particle.assign(system.particle_of_unknown.empty() ? 0 : highest + 1u, -1);
    for (std::size_t k = 0; k < system.particle_of_unknown.size(); ++k) {
      kept.unknown_of_particle[system.particle_of_unknown[k]] = static_cast<std::int32_t>(k);
    }
  }
  int last_iterations = 0;
};

PoissonSolver::PoissonSolver(const PoissonSettings& settings) : impl_(std::make_unique<Impl>()) {
  if (!(settings.relative_tolerance > 0.0) || settings.max_iterations < 1 ||
      !(settings.compression_tolerance >= 0.0) || settings.multigrid_setup_solves < 1) {
    throw std::invalid_argument(
        "poisson solver: tolerances must be > 0 (compression >= 0), iterations >= 1, "
        "multigrid setup solves >= 1");
  }
  impl_->settings = settings;
}
PoissonSolver::~PoissonSolver() = default;
PoissonSolver::PoissonSolver(PoissonSolver&&) noexcept = default;
PoissonSolver& PoissonSolver::operator=(PoissonSolver&&) noexcept = default;

void PoissonSolver::follow_renumbering(std::span<const std::uint32_t> old_of_new) {
  auto& kept = impl_->kept;
  if (!kept.valid) return;
  std::vector<std::int32_t> renumbered(std::max(kept.unknown_of_particle.size(), old_of_new.size()),
                                       -1);
  for (std::size_t k = 0; k < renumbered.size(); ++k) {
    const std::size_t old = k < old_of_new.size() ? old_of_new[k] : k;
    if (old < kept.unknown_of_particle.size()) renumbered[k] = kept.unknown_of_particle[old];
  }
  kept.unknown_of_particle = std::move(renumbered);
}

void PoissonSolver::forget_kept_setup() { impl_->kept.valid = false; }

PoissonReport PoissonSolver::solve(const PoissonSystem& system, Eigen::VectorXd& guess) {
  PoissonReport report;
  if (guess.size() != system.rhs.size()) {
    throw std::invalid_argument("poisson solver: one starting value per unknown");
  }
  if (system.rhs.size() == 0 || system.rhs.squaredNorm() == 0.0) {
    guess.setZero();
    report.converged = true;
    return report;
  }
  // |r| / |b| that leaves the compression tolerance's root mean square.
  const double rhs_norm = system.rhs.norm();
  const double root_n = std::sqrt(static_cast<double>(system.rhs.size()));
  const bool by_compression =
      impl_->settings.compression_tolerance > 0.0 && system.residual_to_compression > 0.0;
  const double tolerance = by_compression
                               ? std::clamp(impl_->settings.compression_tolerance * root_n /
                                                (system.residual_to_compression * rhs_norm),
                                            1e-14, 0.5)
                               : impl_->settings.relative_tolerance;
  auto run = [&](auto& cg) {
    cg.setTolerance(tolerance);
    cg.setMaxIterations(impl_->settings.max_iterations);
    cg.compute(system.matrix);
    if (cg.info() != Eigen::Success) {
      throw std::runtime_error("poisson solver: the preconditioner could not be computed");
    }
    guess = cg.solveWithGuess(system.rhs, guess);
    report.iterations = static_cast<int>(cg.iterations());
    report.relative_residual = cg.error();
    report.compression_left = cg.error() * rhs_norm * system.residual_to_compression / root_n;
    report.converged = cg.info() == Eigen::Success;
  };
  switch (impl_->settings.preconditioner) {
    case Preconditioner::diagonal:
      system.symmetric ? run(impl_->diagonal) : run(impl_->general_diagonal);
      break;
    case Preconditioner::incomplete_cholesky:
      system.symmetric ? run(impl_->cholesky) : run(impl_->general_lu);
      break;
    case Preconditioner::multigrid: {
      auto multigrid = [&](auto& krylov) {
        const Eigen::VectorXd start = guess;
        impl_->offer_kept_setup(system, krylov.preconditioner(), impl_->last_iterations);
        run(krylov);
        if (!report.converged && krylov.preconditioner().kept_setup()) {
          // The kept coarse levels no longer fit: set up anew and solve again.
          guess = start;
          run(krylov);
        }
        report.setup_kept = krylov.preconditioner().kept_setup();
        impl_->note_setup(system, krylov.preconditioner(), report.iterations);
        impl_->last_iterations = report.iterations;
      };
      system.symmetric ? multigrid(impl_->multigrid) : multigrid(impl_->general_multigrid);
      break;
    }
  }
  return report;
}

}  // namespace swemps::ns

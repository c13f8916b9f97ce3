// The pressure Poisson solve of the 2D dam break with 20,000 fluid particles (the scene of
// swemps-ns-speed), solved by the project's conjugate gradients with the zero-fill
// incomplete Cholesky and with the alternatives issue 20 names: conjugate gradients
// preconditioned by algebraic multigrid (the project's smoothed aggregation, its setup timed
// apart, and hypre's BoomerAMG) and a sparse Cholesky factorisation (CHOLMOD). The systems are the
// run's own, taken at several times, each with the starting guess the run gives it (the pressure of
// the step before). Every method is timed as one step would use it: the matrix changes every step,
// so each builds its preconditioner or factor anew. Prints numbers; asserts nothing
// (docs/performance.md).
//
//   OMP_NUM_THREADS=1 swemps-ns-solvers [key=value ...]   (keys of ns_options.hpp)
//
// hypre and CHOLMOD are optional: built in where CMake finds them (Debian's libhypre-dev and
// libsuitesparse-dev), otherwise their rows say so.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "ns_options.hpp"
#include "swemps/ns/aggregation_multigrid.hpp"
#include "swemps/ns/poisson.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/ns/tank.hpp"

#ifdef SWEMPS_HAVE_HYPRE
#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>
#endif
#ifdef SWEMPS_HAVE_CHOLMOD
#include <cholmod.h>
#endif

namespace {

using namespace swemps;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The fastest of `repeats` timings of `run` (the machine is shared; the minimum is the
// least disturbed).
template <class Run>
double fastest(int repeats, Run&& run) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    run();
    best = std::min(best, seconds_since(start));
  }
  return best;
}

double relative_residual(const ns::PoissonSystem& system, const Eigen::VectorXd& x) {
  return (system.rhs - system.matrix * x).norm() / system.rhs.norm();
}

struct Row {
  std::string method;
  int iterations = 0;
  double setup_ms = 0.0, solve_ms = 0.0, residual = 0.0, difference = 0.0;
};

void print(const Row& row) {
  std::printf("  %-40s %6d %10.2f %10.2f %10.2f %10.1e %10.1e\n", row.method.c_str(),
              row.iterations, row.setup_ms, row.solve_ms, row.setup_ms + row.solve_ms, row.residual,
              row.difference);
}

constexpr int kRepeats = 3;

Row conjugate_gradients(const ns::PoissonSystem& system, const Eigen::VectorXd& guess,
                        ns::PoissonSettings settings, ns::Preconditioner preconditioner,
                        Eigen::VectorXd& solution) {
  settings.preconditioner = preconditioner;
  ns::PoissonSolver solver(settings);
  Row row;
  const char* krylov = system.symmetric ? "CG" : "BiCGSTAB";
  row.method =
      std::string(krylov) +
      (preconditioner == ns::Preconditioner::incomplete_cholesky
           ? (system.symmetric ? " + incomplete Cholesky IC(0)" : " + incomplete LU ILU(0)")
       : preconditioner == ns::Preconditioner::diagonal ? " + diagonal"
                                                        : " + aggregation multigrid");
  row.solve_ms = 1e3 * fastest(kRepeats, [&] {
                   solution = guess;
                   row.iterations = solver.solve(system, solution).iterations;
                 });
  row.residual = relative_residual(system, solution);
  return row;
}

#ifdef SWEMPS_HAVE_HYPRE
// hypre's parallel CSR matrix from the system's rows (one process owns them all).
Row boomer_amg(const ns::PoissonSystem& system, const Eigen::VectorXd& guess, double tolerance,
               Eigen::VectorXd& solution) {
  const auto& a = system.matrix;
  const auto n = static_cast<HYPRE_BigInt>(a.rows());
  std::vector<HYPRE_BigInt> rows(static_cast<std::size_t>(n));
  std::vector<HYPRE_Int> sizes(static_cast<std::size_t>(n));
  for (HYPRE_BigInt r = 0; r < n; ++r) {
    rows[static_cast<std::size_t>(r)] = r;
    sizes[static_cast<std::size_t>(r)] = a.outerIndexPtr()[r + 1] - a.outerIndexPtr()[r];
  }
  std::vector<HYPRE_BigInt> columns(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  Row row;
  row.method = "CG + BoomerAMG (hypre, one V-cycle)";
  double setup = 1e300, solve = 1e300;
  for (int r = 0; r < kRepeats; ++r) {
    auto start = Clock::now();
    HYPRE_IJMatrix matrix;
    HYPRE_IJMatrixCreate(MPI_COMM_WORLD, 0, n - 1, 0, n - 1, &matrix);
    HYPRE_IJMatrixSetObjectType(matrix, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(matrix, sizes.data());
    HYPRE_IJMatrixInitialize(matrix);
    HYPRE_IJMatrixSetValues(matrix, static_cast<HYPRE_Int>(n), sizes.data(), rows.data(),
                            columns.data(), a.valuePtr());
    HYPRE_IJMatrixAssemble(matrix);
    HYPRE_ParCSRMatrix par_matrix;
    HYPRE_IJMatrixGetObject(matrix, reinterpret_cast<void**>(&par_matrix));
    HYPRE_IJVector rhs, x;
    HYPRE_ParVector par_rhs, par_x;
    HYPRE_IJVectorCreate(MPI_COMM_WORLD, 0, n - 1, &rhs);
    HYPRE_IJVectorCreate(MPI_COMM_WORLD, 0, n - 1, &x);
    for (auto* v : {&rhs, &x}) {
      HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR);
      HYPRE_IJVectorInitialize(*v);
    }
    HYPRE_IJVectorSetValues(rhs, static_cast<HYPRE_Int>(n), rows.data(), system.rhs.data());
    HYPRE_IJVectorSetValues(x, static_cast<HYPRE_Int>(n), rows.data(), guess.data());
    HYPRE_IJVectorAssemble(rhs);
    HYPRE_IJVectorAssemble(x);
    HYPRE_IJVectorGetObject(rhs, reinterpret_cast<void**>(&par_rhs));
    HYPRE_IJVectorGetObject(x, reinterpret_cast<void**>(&par_x));

    HYPRE_Solver pcg, amg;
    HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD, &pcg);
    HYPRE_PCGSetMaxIter(pcg, 1000);
    HYPRE_PCGSetTol(pcg, tolerance);
    HYPRE_PCGSetTwoNorm(pcg, 1);  // |b - A x| / |b|, the criterion of the project's solver
    HYPRE_BoomerAMGCreate(&amg);
    HYPRE_BoomerAMGSetCoarsenType(amg, 10);  // HMIS
    HYPRE_BoomerAMGSetInterpType(amg, 6);    // extended+i
    HYPRE_BoomerAMGSetPMaxElmts(amg, 4);
    HYPRE_BoomerAMGSetStrongThreshold(amg, 0.25);  // the value for 2D problems
    HYPRE_BoomerAMGSetRelaxType(amg, 6);           // symmetric Gauss-Seidel: CG needs symmetry
    HYPRE_BoomerAMGSetNumSweeps(amg, 1);
    HYPRE_BoomerAMGSetMaxIter(amg, 1);
    HYPRE_BoomerAMGSetTol(amg, 0.0);
    HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
    HYPRE_ParCSRPCGSetup(pcg, par_matrix, par_rhs, par_x);
    setup = std::min(setup, seconds_since(start));
    start = Clock::now();
    HYPRE_ParCSRPCGSolve(pcg, par_matrix, par_rhs, par_x);
    solve = std::min(solve, seconds_since(start));
    HYPRE_PCGGetNumIterations(pcg, &row.iterations);
    solution.resize(a.rows());
    HYPRE_IJVectorGetValues(x, static_cast<HYPRE_Int>(n), rows.data(), solution.data());
    HYPRE_BoomerAMGDestroy(amg);
    HYPRE_ParCSRPCGDestroy(pcg);
    HYPRE_IJVectorDestroy(rhs);
    HYPRE_IJVectorDestroy(x);
    HYPRE_IJMatrixDestroy(matrix);
  }
  row.setup_ms = 1e3 * setup;
  row.solve_ms = 1e3 * solve;
  row.residual = relative_residual(system, solution);
  return row;
}
#endif

#ifdef SWEMPS_HAVE_CHOLMOD
// A direct solve: fill-reducing ordering and symbolic analysis (setup), then the numeric
// factorisation and the two triangular solves. The row-major symmetric matrix read as
// column-major is itself; CHOLMOD reads its upper triangle.
Row sparse_cholesky(const ns::PoissonSystem& system, Eigen::VectorXd& solution) {
  const auto& a = system.matrix;
  const auto n = static_cast<std::size_t>(a.rows());
  cholmod_common common;
  cholmod_start(&common);
  cholmod_sparse* matrix = cholmod_allocate_sparse(n, n, static_cast<std::size_t>(a.nonZeros()), 1,
                                                   1, 1, CHOLMOD_REAL, &common);
  std::copy(a.outerIndexPtr(), a.outerIndexPtr() + n + 1, static_cast<int*>(matrix->p));
  std::copy(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), static_cast<int*>(matrix->i));
  std::copy(a.valuePtr(), a.valuePtr() + a.nonZeros(), static_cast<double*>(matrix->x));
  cholmod_dense* rhs = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  std::copy(system.rhs.data(), system.rhs.data() + n, static_cast<double*>(rhs->x));
  Row row;
  row.method = "sparse Cholesky (CHOLMOD)";
  double setup = 1e300, solve = 1e300;
  for (int r = 0; r < kRepeats; ++r) {
    auto start = Clock::now();
    cholmod_factor* factor = cholmod_analyze(matrix, &common);
    setup = std::min(setup, seconds_since(start));
    start = Clock::now();
    cholmod_factorize(matrix, factor, &common);
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, factor, rhs, &common);
    solve = std::min(solve, seconds_since(start));
    solution = Eigen::Map<const Eigen::VectorXd>(static_cast<double*>(x->x), a.rows());
    cholmod_free_dense(&x, &common);
    cholmod_free_factor(&factor, &common);
  }
  cholmod_free_dense(&rhs, &common);
  cholmod_free_sparse(&matrix, &common);
  cholmod_finish(&common);
  row.setup_ms = 1e3 * setup;
  row.solve_ms = 1e3 * solve;
  row.residual = relative_residual(system, solution);
  return row;
}
#endif

}  // namespace

int main(int argc, char** argv) {
#ifdef SWEMPS_HAVE_HYPRE
  MPI_Init(&argc, &argv);
  HYPRE_Init();
#endif
  ns::Settings s;
  s.spacing_m = 0.006;
  for (int a = 1; a < argc; ++a) {
    if (!benchmarks::apply_ns_option(argv[a], s, 2)) {
      std::fprintf(stderr, "swemps-ns-solvers: unknown option '%s'\n", argv[a]);
      return 2;
    }
  }
  ns::TankSpec<2> tank;
  tank.interior.upper = {3.216, 1.2};
  tank.water.push_back({{0.0, 0.0}, {1.2, 0.6}});
  tank.spacing_m = s.spacing_m;
  tank.solid_layers = static_cast<int>(std::ceil(s.pressure_kernel.support_spacings));
  const double solid = tank.solid_layers * s.spacing_m;
  ns::Simulation<2> sim(ns::fill_tank<2>(tank), s, {-solid, -solid}, {3.216 + solid, 1.2 + solid});
  std::printf("tolerance %g (|b - A p| / |b|), fastest of %d timings\n",
              s.solver.relative_tolerance, kRepeats);
  for (const double t : {0.1, 0.4, 0.8}) {
    sim.advance_to(t);
    // The next step's starting guess is today's pressure, unless the step re-sorts the fluid
    // first: step on until it does not.
    while (sim.steps() % s.sort_interval == 0) sim.advance(sim.stable_time_step());
    const std::vector<double> before = sim.particles().pressure;
    sim.advance(sim.stable_time_step());
    const ns::PoissonSystem& system = sim.poisson_system();
    Eigen::VectorXd guess(system.rhs.size());
    for (Eigen::Index k = 0; k < guess.size(); ++k) {
      guess[k] = before[system.particle_of_unknown[static_cast<std::size_t>(k)]];
    }
    std::printf("\nt = %.3f s: %ld unknowns, %ld entries; starting guess |b - A p0| / |b| = %.1e\n",
                sim.time(), static_cast<long>(system.matrix.rows()),
                static_cast<long>(system.matrix.nonZeros()), relative_residual(system, guess));
    std::printf("  %-40s %6s %10s %10s %10s %10s %10s\n", "method", "iter", "setup ms", "solve ms",
                "total ms", "residual", "max dp/pmax");
    // The reference is today's solver's answer: the others are compared with it.
    Eigen::VectorXd solution, reference;
    Row today = conjugate_gradients(system, guess, s.solver,
                                    ns::Preconditioner::incomplete_cholesky, reference);
    const double scale = reference.cwiseAbs().maxCoeff();
    print(today);
    auto report = [&](Row row) {
      row.difference = (solution - reference).cwiseAbs().maxCoeff() / scale;
      print(row);
    };
    report(conjugate_gradients(system, guess, s.solver, ns::Preconditioner::diagonal, solution));
    {
      // The multigrid's setup alone, and its levels.
      ns::AggregationMultigrid multigrid;
      Row row =
          conjugate_gradients(system, guess, s.solver, ns::Preconditioner::multigrid, solution);
      row.setup_ms = 1e3 * fastest(kRepeats, [&] { multigrid.compute(system.matrix); });
      row.solve_ms -= row.setup_ms;
      report(row);
      std::printf("    levels (unknowns / entries):");
      for (const auto& level : multigrid.level_sizes()) {
        std::printf(" %d / %d", level.unknowns, level.entries);
      }
      std::printf("\n");
    }
#ifdef SWEMPS_HAVE_HYPRE
    report(boomer_amg(system, guess, s.solver.relative_tolerance, solution));
#else
    std::printf("  CG + BoomerAMG: not built (hypre not found)\n");
#endif
#ifdef SWEMPS_HAVE_CHOLMOD
    report(sparse_cholesky(system, solution));
#else
    std::printf("  sparse Cholesky: not built (CHOLMOD not found)\n");
#endif
  }
#ifdef SWEMPS_HAVE_HYPRE
  HYPRE_Finalize();
  MPI_Finalize();
#endif
}

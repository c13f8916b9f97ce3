#pragma once
// Settings of the incompressible Navier-Stokes MPS mode (method.md section 3). Plain values;
// scenario fills them from the scene's "ns" block and checks their ranges.

#include <cstddef>
#include <optional>
#include <string_view>

#include "swemps/kernels/any_kernel.hpp"

namespace swemps::ns {

// A weight function and its cut-off distance, given in particle spacings (r_c / l_0).
struct KernelChoice {
  kernels::KernelSpec spec;
  double support_spacings = 2.1;
};

// How the right-hand side of the pressure Poisson equation is formed.
enum class SourceTerm {
  // method.md section 3: -(rho/dt^2) (n*_i - n0)/n0, the deviation of the predicted number
  // density from the lattice's.
  number_density,
  // Kondo & Koshizuka's stabilised (mixed) source: -(rho/dt^2) [(n*_i - n^k_i)/n0 +
  // gamma (n^k_i - n0)/n0]. The first term asks the step to create no new compression (a
  // velocity-divergence condition, smooth in time); the second relaxes the compression
  // already there by the fraction gamma per step, so it cannot accumulate.
  mixed,
};

// How the pressure gradient of step 6 is formed.
enum class PressureGradient {
  // Koshizuka & Oka: (d/n0) sum_j (p_j - p_min,i) x_ij w_ij / r_ij^2. Every pair repels, which
  // keeps particles apart, but the sum is exact for a linear pressure only where the
  // neighbourhood is symmetric: beside a wall or the surface it pushes with a spurious force
  // (about g/2 of lift on a surface particle).
  minimum_pressure,
  // First-order corrected (Khayyer & Gotoh's CMPS correction matrix; Tamai & Koshizuka's
  // LSMPS of order one): C_i^-1 sum_j (p_j - p_i) x_ij w_ij / r_ij^2, C_i = sum_j x_ij
  // x_ij^T w_ij / r_ij^2. Exact for any linear pressure whatever the neighbourhood, so with
  // extrapolated walls the lattice at rest is a discrete equilibrium. No pairwise repulsion:
  // with the standard kernel at 2.1 l0 particles cluster (the dam break breaks down); with
  // Sheu's quartic kernel or a wide support it runs (docs/ns-dam-break.md, "Water at rest").
  corrected,
  // The corrected gradient plus the minimum-pressure repulsion between close pairs only:
  // C_i^-1 sum_j [(p_j - p_i) + (p_i - p_min,i) [r_ij < r_rep]] x_ij w_ij / r_ij^2, r_rep =
  // repulsion_distance_spacings l_0. On a lattice (every pair at least l_0 apart) it is the
  // corrected gradient, exact for a linear pressure, so water at rest stays at rest; where
  // particles crowd closer than r_rep the repulsion pushes them apart, as the standard sum
  // does, so a dam break stays stable with any kernel. With the repulsion between all pairs
  // (r_rep at the support) a fluid particle facing a wall particle is pushed along the wall
  // by the fixed wall lattice, and at rest that grows (e-fold in about 0.05 s).
  corrected_repulsive,
};

// The pair weights of a corrected pressure gradient, C_i^-1 sum_j (p_j - p_i) x_ij omega_ij
// with C_i = sum_j x_ij x_ij^T omega_ij: exact for a linear pressure with either. The
// close-range repulsion of corrected_repulsive keeps w_ij / r_ij^2.
enum class GradientWeights {
  // omega = w(r) / r^2, Khayyer & Gotoh's correction of the MPS gradient.
  mps,
  // omega = -w'(r) / r, the slope of the kernel that measures the number density: the
  // gradient is then, on a lattice, the adjoint of the number density's rate of change
  // (docs/method.md "Gradient weights"), so the pressure the Poisson equation sets from a
  // compression can only undo it. With w / r^2 the two disagree at short wavelengths: in 3D
  // at 2.1 l0 with Sheu's quartic kernel the step's projection amplifies a wave near the
  // lattice's shortest (k l0 = (0.54, 1, 1) pi, by 0.25 % a step), which the mixed source's
  // relaxation grows into the mode that breaks the tank at rest after a second or two. Not
  // the default: where the 20,000-particle dam break's surge hits the far wall, its splash
  // ran faster, and in one run of four two particles went through the wall (docs/ns-dam-break.md
  // "Gradient weights").
  kernel_slope,
};

// Where wall and dummy particles get their pressure.
enum class BoundaryPressure {
  // method.md section 3: wall particles are unknowns of the Poisson equation (their rows
  // sum over fluid and wall neighbours), dummies only pad the number density. The wall
  // row's one-sided Laplacian fixes the pressure slope the water feels beside it, and not at
  // the hydrostatic value: at rest the water settles only by compressing, with noise.
  poisson,
  // Extrapolated from the fluid along the hydrostatic gradient (boundary_pressure.hpp),
  // walls and dummies alike, and eliminated from the Poisson equation. Gravity's part of the
  // predicted motion is then carried by the extrapolation alone, so the number density
  // against the boundary is measured without it (else it would be counted twice); every
  // other approach to a wall still compresses and is pushed back.
  extrapolated,
};

// How the Poisson equation's Laplacian and the pressure gradient are discretised
// (pressure_operators.hpp).
enum class Operators {
  // The standard MPS operators with the kernel's lattice constants (method.md section 3),
  // and the gradient `gradient` names.
  mps,
  // Least-squares MPS (Tamai & Koshizuka 2014; least_squares.hpp): each particle's quadratic
  // fit gives both, exact for quadratics whatever the arrangement. Needs extrapolated walls
  // and a corrected gradient (the repulsion of corrected-repulsive is kept).
  least_squares,
};

// The preconditioner of the Poisson solve: Jacobi, the zero-fill incomplete factorisation
// (Cholesky for the symmetric MPS system, LU for the least-squares one), or one V-cycle of
// smoothed-aggregation multigrid (aggregation_multigrid.hpp).
enum class Preconditioner { diagonal, incomplete_cholesky, multigrid };

// The pressure Poisson solve: conjugate gradients for the symmetric positive definite MPS
// system, BiCGSTAB for the least-squares one (poisson.hpp), warm-started from the previous
// step's pressure.
struct PoissonSettings {
  Preconditioner preconditioner = Preconditioner::incomplete_cholesky;
  double relative_tolerance = 1e-6;  // |b - A p| / |b|
  // When > 0, the solve stops instead when the compression the pressure leaves undone is
  // below this, as a root mean square over the unknowns of |r_i| dt^2 / rho (the residual of
  // the Laplacian's row in units of the number density's relative change per step: what the
  // step's divergence condition leaves). 0: the relative rule above.
  double compression_tolerance = 0.0;
  int max_iterations = 1000;
  // The multigrid preconditioner's coarse levels serve at most this many solves, the one
  // that built them included (1: set up for every solve), and are rebuilt sooner when
  // particles are removed or a solve takes more than twice the iterations (and two more) of
  // the one that built them. 5: kept over 20, they let the 3D tank at rest at 2.1 l0 go
  // unstable by 4 s (19.9 % against 3.8 %), for 13 % less run time on the 20,000-particle dam
  // break (docs/performance.md).
  int multigrid_setup_solves = 5;
};

// The scene's name of each gradient (docs/scenario.md), for reading scenes and for logs.
constexpr const char* pressure_gradient_name(PressureGradient g) {
  return g == PressureGradient::corrected             ? "corrected"
         : g == PressureGradient::corrected_repulsive ? "corrected-repulsive"
                                                      : "minimum-pressure";
}

// The scene's name of each choice of gradient weights (docs/scenario.md).
constexpr const char* gradient_weights_name(GradientWeights w) {
  return w == GradientWeights::mps ? "mps" : "kernel-slope";
}

// The gradient weights a scene's name stands for; none for a name that is not one.
constexpr std::optional<GradientWeights> gradient_weights_from_name(std::string_view name) {
  for (const auto w : {GradientWeights::mps, GradientWeights::kernel_slope}) {
    if (name == gradient_weights_name(w)) return w;
  }
  return std::nullopt;
}

// The scene's name of each preconditioner (docs/scenario.md), for reading scenes and for logs.
constexpr const char* preconditioner_name(Preconditioner p) {
  return p == Preconditioner::diagonal              ? "diagonal"
         : p == Preconditioner::incomplete_cholesky ? "incomplete-cholesky"
                                                    : "multigrid";
}

// The preconditioner a scene's name stands for; none for a name that is not one.
constexpr std::optional<Preconditioner> preconditioner_from_name(std::string_view name) {
  for (const auto p :
       {Preconditioner::diagonal, Preconditioner::incomplete_cholesky, Preconditioner::multigrid}) {
    if (name == preconditioner_name(p)) return p;
  }
  return std::nullopt;
}

// Koshizuka's particle collision: two fluid particles closer than distance_spacings l_0 and
// approaching each other exchange the approaching part of their relative velocity, keeping
// (1 + restitution)/2 of it. It keeps the standard kernel's clustering from blowing up.
struct Collision {
  double distance_spacings = 0.5;
  double restitution = 0.2;
};

// The member defaults below are the standard semi-implicit MPS of the seed papers
// (method.md section 3); scenes get the well-balanced scheme unless they ask for the standard
// one (scheme_settings).
struct Settings {
  double spacing_m = 0.0;                  // l_0, the initial lattice spacing
  double density_kg_m3 = 1000.0;           // rho
  double kinematic_viscosity_m2_s = 1e-6;  // nu
  double gravity_m_s2 = 9.81;              // along -z (the last axis)
  double courant = 0.2;                    // u_max dt / l_0 <= courant
  double max_time_step_s = 1e-3;           // also bounds the very first steps, taken at rest
  // Kakuda's choice: one kernel for the pressure side (number density, Poisson Laplacian,
  // pressure gradient) and another for the velocity side (viscosity Laplacian).
  KernelChoice pressure_kernel;
  KernelChoice velocity_kernel;
  double free_surface_beta = 0.97;  // n*_i < beta n0: free surface, p = 0
  // Khayyer, Gotoh & Shao's second test: a particle below beta n0 is on the surface only when
  // its neighbours' weighted mean offset |sum x_ij w_ij / sum w_ij| exceeds this many l_0 (its
  // neighbourhood is one-sided). 0 turns the test off (number density alone). The row just
  // under a flat surface lacks only a few far neighbours, so its number density sits within a
  // few per cent of beta n0 and would flip on and off the surface (a pressure jump of rho g l_0
  // per flip); its mean offset is ~0.02 l_0 against ~0.5 l_0 on the surface itself.
  double free_surface_asymmetry = 0.0;
  SourceTerm source = SourceTerm::number_density;
  double source_gamma = 0.05;  // mixed source only
  PressureGradient gradient = PressureGradient::minimum_pressure;
  GradientWeights gradient_weights = GradientWeights::mps;  // corrected gradients only
  double repulsion_distance_spacings = 0.9;                 // corrected_repulsive only
  BoundaryPressure boundary = BoundaryPressure::poisson;
  Operators operators = Operators::mps;
  PoissonSettings solver;
  std::optional<Collision> collision = Collision{};
  // Fluid particles are re-sorted by cell every this many steps (memory locality only).
  std::size_t sort_interval = 20;
};

// The two sets of numerical choices a scene picks with "scheme" (docs/scenario.md).
enum class Scheme {
  // The standard MPS: Settings' member defaults. Kept for the kernel study and comparison;
  // at rest its pressure swings by several times rho g H from step to step.
  standard,
  // Quiet at rest, and stable at twice the step (docs/ns-dam-break.md "Water at rest",
  // docs/performance.md): Sheu's quartic kernel at 2.1 l0, the mixed source, the corrected
  // gradient with close-range repulsion, the surface asymmetry test, extrapolated walls,
  // Courant 0.4 and a solver tolerance of 1e-3 (measured: the Martin & Moyce front moves by
  // 0.01 a against 1e-6, the water at rest stays within 1.5 % of rho g H), and the multigrid
  // preconditioner with its setup kept over 5 solves (its smooth pressure is what multigrid
  // is for: 4 iterations a step against 33, the 20,000-particle dam break 1.3-1.5 times
  // faster; docs/performance.md). In 3D its gradient weighs pairs by the kernel's slope and
  // the multigrid's setup serves 20 solves (scheme_settings).
  well_balanced,
  // The well-balanced scheme's choices on least-squares operators (Operators::least_squares):
  // the Laplacian and gradient consistent on any arrangement (docs/ns-dam-break.md), but
  // with the incomplete LU: under the multigrid its dam break's splash ran away (measured,
  // docs/performance.md).
  least_squares,
};

// Settings with every numerical choice of `scheme` in `dimensions` (2 or 3); the physical
// constants, the spacing and the largest step keep Settings' defaults, for the caller to set.
inline Settings scheme_settings(Scheme scheme, int dimensions) {
  Settings s;
  if (scheme == Scheme::standard) return s;
  s.pressure_kernel.spec.type = kernels::KernelType::sheu_quartic;
  s.velocity_kernel = s.pressure_kernel;
  s.free_surface_asymmetry = 0.2;
  s.source = SourceTerm::mixed;
  s.gradient = PressureGradient::corrected_repulsive;
  s.boundary = BoundaryPressure::extrapolated;
  s.courant = 0.4;
  s.solver.relative_tolerance = 1e-3;
  s.solver.preconditioner = Preconditioner::multigrid;
  if (scheme == Scheme::well_balanced && dimensions == 3) {
    // In 3D at 2.1 l0 the step amplifies a lattice wave when the gradient weighs its pairs by
    // w / r^2, and water at rest leaves its rest within seconds; weighed by the kernel's slope
    // the gradient is the adjoint of the number density's rate of change and amplifies none
    // (method.md "Gradient weights"; docs/ns-dam-break.md). In 2D nothing is amplified on
    // w / r^2, and there its 20,000-particle splash held in more runs (measured), so 2D keeps
    // it. A 3D multigrid setup costs more against solves of two iterations, and on the slope
    // the 3D tank holds 10 s with it kept over 20 (docs/performance.md).
    s.gradient_weights = GradientWeights::kernel_slope;
    s.solver.multigrid_setup_solves = 20;
  }
  if (scheme == Scheme::least_squares) {
    s.operators = Operators::least_squares;
    s.solver.preconditioner = Preconditioner::incomplete_cholesky;
  }
  return s;
}

}  // namespace swemps::ns

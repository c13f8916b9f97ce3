#pragma once
// Settings of the incompressible Navier-Stokes MPS mode (method.md section 3). Plain values;
// scenario fills them from the scene's "ns" block and checks their ranges.

#include <cstddef>
#include <optional>

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

enum class Preconditioner { diagonal, incomplete_cholesky };

// The pressure Poisson solve: conjugate gradients (the matrix is symmetric positive definite,
// see poisson.hpp), warm-started from the previous step's pressure.
struct PoissonSettings {
  Preconditioner preconditioner = Preconditioner::incomplete_cholesky;
  double relative_tolerance = 1e-6;  // |b - A p| / |b|
  int max_iterations = 1000;
};

// Koshizuka's particle collision: two fluid particles closer than distance_spacings l_0 and
// approaching each other exchange the approaching part of their relative velocity, keeping
// (1 + restitution)/2 of it. It keeps the standard kernel's clustering from blowing up.
struct Collision {
  double distance_spacings = 0.5;
  double restitution = 0.2;
};

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
  SourceTerm source = SourceTerm::number_density;
  double source_gamma = 0.05;  // mixed source only
  PoissonSettings solver;
  std::optional<Collision> collision = Collision{};
  // Fluid particles are re-sorted by cell every this many steps (memory locality only).
  std::size_t sort_interval = 20;
};

}  // namespace swemps::ns

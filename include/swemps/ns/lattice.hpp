#pragma once
// The MPS reference constants of a kernel on the initial lattice (method.md section 3): the
// number density n0 = sum_j w(|x_j - x_i|) and the Laplacian's
// lambda = sum_j r_ij^2 w_ij / sum_j w_ij, both for a particle whose support is full.
// Both are sums over the lattice offsets within the support, so they are exact for the
// lattice the particles start on, whatever the kernel.

#include "swemps/kernels/any_kernel.hpp"

namespace swemps::ns {

struct LatticeConstants {
  double number_density = 0.0;  // n0
  double lambda_m2 = 0.0;       // lambda
  int neighbours = 0;           // lattice points within the support
};

// Square (2D) or cubic (3D) lattice of spacing l0.
template <int Dim>
LatticeConstants lattice_constants(const kernels::AnyKernel<Dim>& kernel, double spacing_m);

}  // namespace swemps::ns

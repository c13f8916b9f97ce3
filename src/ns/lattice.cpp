#include "swemps/ns/lattice.hpp"

#include <cmath>
#include <stdexcept>
#include <variant>

namespace swemps::ns {

template <int Dim>
LatticeConstants lattice_constants(const kernels::AnyKernel<Dim>& kernel, double spacing_m) {
  if (!(spacing_m > 0.0)) throw std::invalid_argument("lattice constants: spacing <= 0");
  const double support = kernels::support<Dim>(kernel);
  const int reach = static_cast<int>(std::ceil(support / spacing_m));
  LatticeConstants c;
  double weighted_r2 = 0.0;
  const int kz_reach = Dim == 3 ? reach : 0;
  for (int kz = -kz_reach; kz <= kz_reach; ++kz)
    for (int ky = -reach; ky <= reach; ++ky)
      for (int kx = -reach; kx <= reach; ++kx) {
        if (kx == 0 && ky == 0 && kz == 0) continue;
        const double r2 = spacing_m * spacing_m * (kx * kx + ky * ky + kz * kz);
        const double r = std::sqrt(r2);
        if (r >= support) continue;
        const double w = kernels::weight<Dim>(kernel, r);
        c.number_density += w;
        weighted_r2 += r2 * w;
        ++c.neighbours;
      }
  if (!(c.number_density > 0.0)) {
    throw std::invalid_argument("lattice constants: no lattice neighbour inside the support");
  }
  c.lambda_m2 = weighted_r2 / c.number_density;
  return c;
}

template LatticeConstants lattice_constants<2>(const kernels::AnyKernel<2>&, double);
template LatticeConstants lattice_constants<3>(const kernels::AnyKernel<3>&, double);

}  // namespace swemps::ns

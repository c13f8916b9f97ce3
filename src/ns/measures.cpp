#include "swemps/ns/measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "swemps/neighbors/cell_list.hpp"

namespace swemps::ns {

template <int Dim>
double front_position(const Particles<Dim>& particles, double spacing_m) {
  const std::size_t fluid = particles.fluid;
  if (fluid == 0) return std::numeric_limits<double>::quiet_NaN();
  neighbors::Coordinates<Dim> coords;
  for (int d = 0; d < Dim; ++d)
    coords[d] = std::span<const double>(particles.position[d]).first(fluid);
  const double radius = 1.5 * spacing_m;
  neighbors::CellList<Dim> cells;
  cells.build(coords, radius);
  double front = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fluid; ++i) {
    std::array<double, Dim> x{};
    for (int d = 0; d < Dim; ++d) x[d] = coords[d][i];
    if (!(x[0] > front)) continue;
    bool has_company = false;
    cells.for_each_candidate(x, [&](std::uint32_t j) {
      if (j == i || has_company) return;
      double r2 = 0.0;
      for (int d = 0; d < Dim; ++d) r2 += (coords[d][j] - x[d]) * (coords[d][j] - x[d]);
      has_company = r2 < radius * radius;
    });
    if (has_company) front = x[0];
  }
  return front + 0.5 * spacing_m;
}

template <int Dim>
std::vector<double> column_depth(const Particles<Dim>& particles, double spacing_m,
                                 const PlanGrid& grid) {
  if (!(grid.dx > 0.0) || !(grid.dy > 0.0) || grid.nx == 0 || grid.ny == 0) {
    throw std::invalid_argument("column depth: empty grid");
  }
  std::vector<double> depth(grid.nx * grid.ny, 0.0);
  const double volume = std::pow(spacing_m, Dim);  // per unit width in 2D
  const double cell = Dim == 3 ? grid.dx * grid.dy : grid.dx;
  auto index_of = [](double x, double x0, double dx, std::size_t n) -> long {
    const double c = std::floor((x - (x0 - 0.5 * dx)) / dx);
    return (c >= 0.0 && c < static_cast<double>(n)) ? static_cast<long>(c) : -1;
  };
  for (std::size_t p = 0; p < particles.fluid; ++p) {
    const long i = index_of(particles.position[0][p], grid.x0, grid.dx, grid.nx);
    if (i < 0) continue;
    if constexpr (Dim == 3) {
      const long k = index_of(particles.position[1][p], grid.y0, grid.dy, grid.ny);
      if (k < 0) continue;
      depth[static_cast<std::size_t>(k) * grid.nx + static_cast<std::size_t>(i)] += volume / cell;
    } else {
      depth[static_cast<std::size_t>(i)] += volume / cell;
    }
  }
  if constexpr (Dim == 2) {
    for (std::size_t k = 1; k < grid.ny; ++k) {
      std::copy_n(depth.begin(), grid.nx, depth.begin() + static_cast<long>(k * grid.nx));
    }
  }
  return depth;
}

template <int Dim>
double pressure_at(const Particles<Dim>& particles, const kernels::AnyKernel<Dim>& kernel,
                   const std::array<double, Dim>& point) {
  double weighted = 0.0, total = 0.0;
  std::visit(
      [&](const auto& k) {
        const double support = k.support();
        for (std::size_t i = 0; i < particles.fluid + particles.wall; ++i) {
          double r2 = 0.0;
          for (int d = 0; d < Dim; ++d) {
            const double delta = particles.position[d][i] - point[d];
            r2 += delta * delta;
          }
          if (r2 >= support * support) continue;
          // A particle exactly at the point would give a singular weight infinite: take it
          // alone.
          const double r = std::max(std::sqrt(r2), 1e-6 * support);
          const double w = k.w(r);
          weighted += w * particles.pressure[i];
          total += w;
        }
      },
      kernel);
  return total > 0.0 ? weighted / total : 0.0;
}

template double front_position<2>(const Particles<2>&, double);
template double front_position<3>(const Particles<3>&, double);
template std::vector<double> column_depth<2>(const Particles<2>&, double, const PlanGrid&);
template std::vector<double> column_depth<3>(const Particles<3>&, double, const PlanGrid&);
template double pressure_at<2>(const Particles<2>&, const kernels::AnyKernel<2>&,
                               const std::array<double, 2>&);
template double pressure_at<3>(const Particles<3>&, const kernels::AnyKernel<3>&,
                               const std::array<double, 3>&);

}  // namespace swemps::ns

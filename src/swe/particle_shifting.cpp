#include "swemps/swe/particle_shifting.hpp"

#include <cmath>
#include <vector>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/swe/particle_kernel.hpp"

namespace swemps::swe {

namespace {

// One row's offsets, radii, areas and (second pass) concentration gradients, gathered so that
// the kernel sums run in tight, vectorised loops over contiguous values.
struct ShiftRow {
  std::vector<double> dx, dy, h, area, gx, gy;
  void gather(const particles::SweParticles& p, std::span<const std::uint32_t> row,
              std::size_t i) {
    for (auto* v : {&dx, &dy, &h, &area}) v->resize(row.size());
    for (std::size_t k = 0; k < row.size(); ++k) {
      const std::uint32_t j = row[k];
      dx[k] = p.x[i] - p.x[j];
      dy[k] = p.y[i] - p.y[j];
      h[k] = p.smoothing_length[j];
      area[k] = p.area[j];
    }
  }
  // The second pass's row: offsets, and the areas and grad C of fluid neighbours (ghosts,
  // whose gradient would be a mirror image, get weight 0).
  void gather_fluid_gradients(const particles::SweParticles& p,
                              std::span<const std::uint32_t> row, std::size_t i,
                              const std::vector<double>& grad_x,
                              const std::vector<double>& grad_y) {
    for (auto* v : {&dx, &dy, &area, &gx, &gy}) v->resize(row.size());
    const std::size_t n = p.fluid_count();
    for (std::size_t k = 0; k < row.size(); ++k) {
      const std::uint32_t j = row[k];
      dx[k] = p.x[i] - p.x[j];
      dy[k] = p.y[i] - p.y[j];
      const bool fluid = j < n;
      area[k] = fluid ? p.area[j] : 0.0;
      gx[k] = fluid ? grad_x[j] : 0.0;
      gy[k] = fluid ? grad_y[j] : 0.0;
    }
  }
};

// C_i and grad C_i of every fluid particle (see the header).
template <class K>
void concentration_gradients(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                             std::vector<double>& concentration, std::vector<double>& gx,
                             std::vector<double>& gy) {
  const std::size_t n = p.fluid_count();
  concentration.resize(n);
  gx.resize(n);
  gy.resize(n);
#pragma omp parallel if (n > static_cast<std::size_t>(parallel_threshold))
  {
    ShiftRow b;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      b.gather(p, nl.row(i), i);
      const std::size_t count = b.dx.size();
      const double inverse_hi = 1.0 / p.smoothing_length[i];
      const double w_scale_i = K::sigma() * inverse_hi * inverse_hi;  // sigma / h^2
      const double slope_scale_i = w_scale_i * inverse_hi;
      double shape_sum = 0.0, sx = 0.0, sy = 0.0;
#pragma omp simd reduction(+ : shape_sum, sx, sy)
      for (std::size_t k = 0; k < count; ++k) {
        const double r = std::sqrt(b.dx[k] * b.dx[k] + b.dy[k] * b.dy[k]);
        const double inverse_r = r > 0.0 ? 1.0 / r : 0.0;  // coincident: no direction
        const double inverse_hj = 1.0 / b.h[k];
        const double qi = r * inverse_hi;
        shape_sum += b.area[k] * K::shape(qi);
        const double slope = 0.5 * (slope_scale_i * K::shape_slope(qi) +
                                    K::sigma() * inverse_hj * inverse_hj * inverse_hj *
                                        K::shape_slope(r * inverse_hj));
        const double f = b.area[k] * slope * inverse_r;
        sx += f * b.dx[k];
        sy += f * b.dy[k];
      }
      concentration[i] = w_scale_i * (shape_sum + p.area[i] * K::shape(0.0));
      gx[i] = sx;
      gy[i] = sy;
    }
  }
}

template <class K>
void shift_with(const particles::SweParticles& p, const neighbors::NeighborList& nl, double beta,
                double dt_s, const ConcentrationField& field, std::span<const double> celerity,
                std::span<double> shift_x, std::span<double> shift_y) {
  const std::size_t n = p.fluid_count();
  const auto& concentration = field.concentration;
  const auto& gx = field.gradient_x;
  const auto& gy = field.gradient_y;
#pragma omp parallel if (n > static_cast<std::size_t>(parallel_threshold))
  {
    ShiftRow b;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      shift_x[i] = 0.0;
      shift_y[i] = 0.0;
      // Plain sqrt, not std::hypot: speeds and shifts are far from overflow, and hypot's guards
      // cost more than the rest of a particle's arithmetic here.
      const double speed = std::sqrt(p.u[i] * p.u[i] + p.v[i] * p.v[i]);
      // At rest no shift, so still water stays still; at the edge none (see the header).
      if (speed == 0.0 || concentration[i] < kEdgeConcentration) continue;
      // The kernel average of grad C over the particle and its fluid neighbours (ghosts,
      // whose gradient would be a mirror image, are left out of it: weight 0).
      const auto row = nl.row(i);
      b.gather_fluid_gradients(p, row, i, gx, gy);
      const std::size_t count = row.size();
      const double inverse_hi = 1.0 / p.smoothing_length[i];
      const double self = p.area[i] * K::shape(0.0);
      double weight = self, mx = self * gx[i], my = self * gy[i];
#pragma omp simd reduction(+ : weight, mx, my)
      for (std::size_t k = 0; k < count; ++k) {
        const double r = std::sqrt(b.dx[k] * b.dx[k] + b.dy[k] * b.dy[k]);
        const double w = b.area[k] * K::shape(r * inverse_hi);
        weight += w;
        mx += w * b.gx[k];
        my += w * b.gy[k];
      }
      // Only the particle-scale part of grad C moves the particle (see the header), and slow
      // water less than in proportion to its speed (kSlowFroude).
      const double froude = speed / celerity[i];
      const double slowing = froude < kSlowFroude ? froude / kSlowFroude : 1.0;
      const double diffusion = beta * p.smoothing_length[i] * speed * dt_s * slowing;
      double sx = -diffusion * (gx[i] - mx / weight), sy = -diffusion * (gy[i] - my / weight);
      const double largest = kLargestShift * std::sqrt(p.area[i]);
      const double length = std::sqrt(sx * sx + sy * sy);
      if (length > largest) {
        sx *= largest / length;
        sy *= largest / length;
      }
      shift_x[i] = sx;
      shift_y[i] = sy;
    }
  }
}

}  // namespace

void concentration_field(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                         KernelShape shape, ConcentrationField& field) {
  with_kernel_shape(shape, [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    concentration_gradients<K>(p, nl, field.concentration, field.gradient_x, field.gradient_y);
  });
}

void particle_shift(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                    KernelShape shape, double beta, double dt_s, const ConcentrationField& field,
                    std::span<const double> celerity, std::span<double> shift_x,
                    std::span<double> shift_y) {
  with_kernel_shape(shape, [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    shift_with<K>(p, nl, beta, dt_s, field, celerity, shift_x, shift_y);
  });
}

}  // namespace swemps::swe

#include "swemps/swe/operators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

using particles::SweParticles;

namespace {

// Plain sqrt, not std::hypot: the inner loops run over distances of order metres, where
// hypot's overflow guards cost several times the arithmetic and buy nothing.
inline double distance(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }

}  // namespace

double influence_radius(const SweParticles& p, double alpha_e) {
  double largest_area = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i)
    largest_area = std::max(largest_area, p.area[i]);
  return alpha_e * std::sqrt(largest_area);
}

void sum_depth(SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w) {
  const double self = w.w(0.0);
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    double h = p.volume[i] * self;  // eq 7 includes j = i
    for (std::uint32_t j : nl.row(i)) {
      const double r = distance(p.x[j] - p.x[i], p.y[j] - p.y[i]);
      h += p.volume[j] * w.w(r);
    }
    p.depth[i] = h;
    p.area[i] = p.volume[i] / h;
  });
}

double number_density_at(const SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w,
                         std::size_t i) {
  double sum = 0.0;
  for (std::uint32_t j : nl.row(i)) {
    const double r = distance(p.x[j] - p.x[i], p.y[j] - p.y[i]);
    sum += p.area[j] * w.w(r);
  }
  return sum / p.area[i];
}

void sum_number_density(SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w) {
  parallel_for(p.fluid_count(),
               [&](std::size_t i) { p.number_density[i] = number_density_at(p, nl, w, i); });
}

namespace {

// Smallest separation treated as distinct: coincident points have no direction.
constexpr double coincident_m = 1e-12;

}  // namespace

std::array<double, 2> mps_gradient_at(const SweParticles& p, const neighbors::NeighborList& nl,
                                      const Kernel& w, std::size_t i, std::span<const double> phi,
                                      double number_density) {
  constexpr double dimension = 2.0;  // D of eq 6
  double sx = 0.0, sy = 0.0;
  for (std::uint32_t j : nl.row(i)) {
    const double dx = p.x[j] - p.x[i];
    const double dy = p.y[j] - p.y[i];
    const double r2 = dx * dx + dy * dy;
    if (r2 < coincident_m * coincident_m) continue;
    const double f = (phi[j] - phi[i]) / r2 * (p.area[j] / p.area[i]) * w.w(std::sqrt(r2));
    sx += f * dx;
    sy += f * dy;
  }
  if (!(number_density > 0.0)) return {0.0, 0.0};  // an isolated particle feels no gradient
  return {dimension / number_density * sx, dimension / number_density * sy};
}

namespace {

void summation_gradient(const SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w,
                        std::span<double> gx, std::span<double> gy) {
  // grad h_i = sum_j V_j dw/dr (x_i - x_j) / r: the exact derivative of eq 7 with respect to
  // x_i. With a common r_e (eq 9) the pair terms are antisymmetric, so -g V_i grad h_i
  // conserves momentum to round-off.
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    double sx = 0.0, sy = 0.0;
    for (std::uint32_t j : nl.row(i)) {
      const double dx = p.x[i] - p.x[j];
      const double dy = p.y[i] - p.y[j];
      const double r = distance(dx, dy);
      if (r < coincident_m) continue;
      const double f = p.volume[j] * w.dw_dr(r) / r;
      sx += f * dx;
      sy += f * dy;
    }
    gx[i] = sx;
    gy[i] = sy;
  });
}

void mps_gradient(const SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w,
                  std::span<double> gx, std::span<double> gy) {
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    const auto g = mps_gradient_at(p, nl, w, i, p.depth, p.number_density[i]);
    gx[i] = g[0];
    gy[i] = g[1];
  });
}

}  // namespace

void depth_gradient(GradientVariant variant, const SweParticles& p,
                    const neighbors::NeighborList& nl, const Kernel& w, std::span<double> gx,
                    std::span<double> gy) {
  switch (variant) {
    case GradientVariant::summation: summation_gradient(p, nl, w, gx, gy); return;
    case GradientVariant::mps: mps_gradient(p, nl, w, gx, gy); return;
  }
}

TimeStepLimit stable_time_step(const SweParticles& p, double gravity_m_s2, double cfl) {
  TimeStepLimit limit{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double speed = std::sqrt(gravity_m_s2 * p.depth[i]) + std::hypot(p.u[i], p.v[i]);
    const double dt = cfl * std::sqrt(p.area[i]) / speed;
    // A NaN anywhere must surface as the limiting particle, not be skipped by '<'.
    if (!(dt >= limit.dt_s) || std::isnan(dt)) {
      limit = {dt, i};
      if (std::isnan(dt)) break;
    }
  }
  return limit;
}

std::vector<double> depth_on_grid(const SweParticles& p, const Kernel& w, const RegularGrid& grid) {
  std::vector<double> depth(grid.nx * grid.ny, 0.0);
  const std::size_t n = p.fluid_count();
  if (n == 0) return depth;
  neighbors::CellList<2> cells;
  cells.build({std::span<const double>(p.x.data(), n), std::span<const double>(p.y.data(), n)},
              w.support());
  const double support = w.support();
  parallel_for(grid.nx * grid.ny, [&](std::size_t cell) {
    const double gx = grid.x0 + static_cast<double>(cell % grid.nx) * grid.dx;
    const double gy = grid.y0 + static_cast<double>(cell / grid.nx) * grid.dy;
    double h = 0.0;
    cells.for_each_candidate({gx, gy}, [&](std::uint32_t j) {
      const double r = distance(p.x[j] - gx, p.y[j] - gy);
      if (r < support) h += p.volume[j] * w.w(r);
    });
    depth[cell] = h;
  });
  return depth;
}

}  // namespace swemps::swe

#include "swemps/swe/operators.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

using particles::SweParticles;

namespace {

// Plain sqrt, not std::hypot: the inner loops run over distances of order metres, where
// hypot's overflow guards cost several times the arithmetic and buy nothing.
inline double distance(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }

// Smallest separation treated as distinct: coincident points have no direction.
constexpr double coincident_m = 1e-12;

// A block of particle i's neighbour row, ready for a sum: the offsets x_j - x_i, r^2, and up to
// two weights per pair. Rows are 20 to 80 long, so one block nearly always.
struct PairBlock {
  static constexpr std::size_t capacity = 64;
  std::span<const std::uint32_t> index;  // the neighbours j of this block
  std::array<double, capacity> dx, dy, r2, weight, second_weight;
};

// Calls visit(block) for row i block by block. Each block is made in two steps: a loop gathers
// the neighbours' offsets, then weigh(block) computes the weights from r^2 in loops without a
// gather, which the compiler vectorises. The square roots and divisions that kernel weights
// need then cost a fraction of what they did inside the gathering loop, where they stalled it.
template <class Weigh, class Visit>
void for_each_pair_block(const SweParticles& p, const neighbors::NeighborList& nl, std::size_t i,
                         Weigh&& weigh, Visit&& visit) {
  PairBlock block;
  const auto row = nl.row(i);
  for (std::size_t first = 0; first < row.size(); first += PairBlock::capacity) {
    block.index = row.subspan(first, std::min(PairBlock::capacity, row.size() - first));
    const std::size_t count = block.index.size();
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t j = block.index[k];
      block.dx[k] = p.x[j] - p.x[i];
      block.dy[k] = p.y[j] - p.y[i];
    }
    for (std::size_t k = 0; k < count; ++k)
      block.r2[k] = block.dx[k] * block.dx[k] + block.dy[k] * block.dy[k];
    weigh(block);
    visit(block);
  }
}

// weight = w(r): the weight of eqs 5 and 7.
auto kernel_weights(const Kernel& w) {
  return [&w](PairBlock& b) {
    for (std::size_t k = 0; k < b.index.size(); ++k) b.weight[k] = w.w(std::sqrt(b.r2[k]));
  };
}

// weight = w(r) and second_weight = w(r) / r^2, the direction weight of eq 6, which is 0 for
// coincident points: they have no direction.
auto kernel_and_gradient_weights(const Kernel& w) {
  return [&w](PairBlock& b) {
    for (std::size_t k = 0; k < b.index.size(); ++k) {
      const double r2 = b.r2[k];
      b.weight[k] = w.w(std::sqrt(r2));
      // Selects, then one division for every pair: branch-free, so the loop vectorises.
      const bool distinct = r2 >= coincident_m * coincident_m;
      b.second_weight[k] = (distinct ? b.weight[k] : 0.0) / (distinct ? r2 : 1.0);
    }
  };
}

}  // namespace

double influence_radius(const SweParticles& p, double alpha_e, double max_area_ratio,
                        double isolated_area) {
  // eq 7 gives an isolated particle exactly A = 1 / w(0); a relative margin absorbs the
  // rounding of V / (V w(0)).
  const double isolated_from = isolated_area * (1.0 - 1e-9);
  // Maxima per chunk in parallel; a maximum does not depend on the order it is taken in.
  std::array<double, reduction_chunks> connected{}, any{};
  parallel_chunks(p.fluid_count(), [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double bounded = std::min(p.area[i], max_area_ratio * p.initial_area[i]);
      any[chunk] = std::max(any[chunk], bounded);
      if (p.area[i] < isolated_from) connected[chunk] = std::max(connected[chunk], bounded);
    }
  });
  const double largest_connected = *std::max_element(connected.begin(), connected.end());
  const double largest_any = *std::max_element(any.begin(), any.end());
  return alpha_e * std::sqrt(largest_connected > 0.0 ? largest_connected : largest_any);
}

void sum_depth(SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w) {
  const double self = w.w(0.0);
  const auto kernel_weight = kernel_weights(w);
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    double h = p.volume[i] * self;  // eq 7 includes j = i
    for_each_pair_block(p, nl, i, kernel_weight, [&](const PairBlock& b) {
      for (std::size_t k = 0; k < b.index.size(); ++k) h += p.volume[b.index[k]] * b.weight[k];
    });
    p.depth[i] = h;
    p.area[i] = p.volume[i] / h;
  });
}

double number_density_at(const SweParticles& p, const neighbors::NeighborList& nl,
                         const ParticleKernel& w, std::size_t i) {
  double sum = 0.0;
  for (const std::uint32_t j : nl.row(i)) {
    const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i];
    sum += p.area[j] * w.pair_w(p, i, j, distance(dx, dy));
  }
  return sum / p.area[i];
}

void sum_number_density(SweParticles& p, const neighbors::NeighborList& nl,
                        const ParticleKernel& w) {
  parallel_for(p.fluid_count(),
               [&](std::size_t i) { p.number_density[i] = number_density_at(p, nl, w, i); });
}

std::array<double, 2> mps_gradient_at(const SweParticles& p, const neighbors::NeighborList& nl,
                                      const ParticleKernel& w, std::size_t i,
                                      std::span<const double> phi, double number_density) {
  constexpr double dimension = 2.0;  // D of eq 6
  double sx = 0.0, sy = 0.0;
  for (const std::uint32_t j : nl.row(i)) {
    const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i];
    const double r2 = dx * dx + dy * dy;
    if (r2 < coincident_m * coincident_m) continue;  // no direction
    const double f =
        (phi[j] - phi[i]) * (p.area[j] / p.area[i]) * w.pair_w(p, i, j, std::sqrt(r2)) / r2;
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
  // weight = (dw/dr) / r, 0 for coincident points.
  const auto derivative_over_r = [&w](PairBlock& b) {
    for (std::size_t k = 0; k < b.index.size(); ++k) {
      const double r = std::sqrt(b.r2[k]);
      const double derivative = w.dw_dr(r);
      const bool distinct = r >= coincident_m;  // selects, not a branch: see above
      b.weight[k] = (distinct ? derivative : 0.0) / (distinct ? r : 1.0);
    }
  };
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    double sx = 0.0, sy = 0.0;
    for_each_pair_block(p, nl, i, derivative_over_r, [&](const PairBlock& b) {
      for (std::size_t k = 0; k < b.index.size(); ++k) {
        const double f = p.volume[b.index[k]] * b.weight[k];
        sx -= f * b.dx[k];  // dx = x_j - x_i: the derivative takes x_i - x_j
        sy -= f * b.dy[k];
      }
    });
    gx[i] = sx;
    gy[i] = sy;
  });
}

// eq 6 for phi = h with eq 5's n_i from the same pass: both weigh neighbour j by A_j w_ij, so
// n_i = sum A_j w_ij / A_i and grad h_i = D / n_i sum (h_j - h_i) / r^2 (A_j / A_i) w_ij x_ij
// = D sum (h_j - h_i) A_j w_ij / r^2 x_ij / sum A_j w_ij: one walk over the row, not two.
void mps_depth_gradient(SweParticles& p, const neighbors::NeighborList& nl, const Kernel& w,
                        std::span<double> gx, std::span<double> gy) {
  constexpr double dimension = 2.0;  // D of eq 6
  const auto pair_weights = kernel_and_gradient_weights(w);
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    double weight_sum = 0.0, sx = 0.0, sy = 0.0;
    for_each_pair_block(p, nl, i, pair_weights, [&](const PairBlock& b) {
      for (std::size_t k = 0; k < b.index.size(); ++k) {
        const std::uint32_t j = b.index[k];
        weight_sum += p.area[j] * b.weight[k];
        const double f = (p.depth[j] - p.depth[i]) * p.area[j] * b.second_weight[k];
        sx += f * b.dx[k];
        sy += f * b.dy[k];
      }
    });
    p.number_density[i] = weight_sum / p.area[i];
    // An isolated particle feels no gradient.
    const double scale = weight_sum > 0.0 ? dimension / weight_sum : 0.0;
    gx[i] = scale * sx;
    gy[i] = scale * sy;
  });
}

}  // namespace

void depth_gradient(GradientVariant variant, SweParticles& p, const neighbors::NeighborList& nl,
                    const Kernel& w, std::span<double> gx, std::span<double> gy) {
  switch (variant) {
    case GradientVariant::summation: summation_gradient(p, nl, w, gx, gy); return;
    case GradientVariant::mps: mps_depth_gradient(p, nl, w, gx, gy); return;
  }
}

double particle_time_step(const SweParticles& p, std::size_t i, double gravity_m_s2, double cfl) {
  const double speed = std::sqrt(gravity_m_s2 * p.depth[i]) + distance(p.u[i], p.v[i]);
  return cfl * std::sqrt(p.area[i]) / speed;
}

TimeStepLimit stable_time_step(const SweParticles& p, double gravity_m_s2, double cfl) {
  // The first particle with the smallest step, or the first whose step is NaN (it must surface
  // as the limiting particle, not be skipped by '<'). Found per chunk in parallel, then the
  // chunks' answers are taken in order by the same rule, which gives the serial scan's
  // answer for any number of threads.
  const auto take = [](TimeStepLimit& limit, double dt, std::size_t i) {
    if (std::isnan(limit.dt_s)) return;
    if (!(dt >= limit.dt_s) || std::isnan(dt)) limit = {dt, i};
  };
  std::array<TimeStepLimit, reduction_chunks> chunk_limit;
  chunk_limit.fill({std::numeric_limits<double>::infinity(), 0});
  parallel_chunks(p.fluid_count(), [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      take(chunk_limit[chunk], particle_time_step(p, i, gravity_m_s2, cfl), i);
  });
  TimeStepLimit limit{std::numeric_limits<double>::infinity(), 0};
  for (const TimeStepLimit& c : chunk_limit) take(limit, c.dt_s, c.particle);
  return limit;
}

namespace {

// Sums eq 7 and the particles' momentum at points, over the particles found through cell
// lists built once for all points, each particle with its own radius. Wall ghosts, when the
// state has them (a refreshed simulation does), count for the points on their fluid
// particle's side of the wall: a ghost mirrored across a wall is nearer to its particle than
// to itself exactly there (the wall is the perpendicular bisector of the two). Without them a
// point next to a wall would miss the half of its kernel that lies behind the wall, and read
// half the depth; with them, uniform water reads its depth up to the wall, and the field still
// integrates to the particles' volume over the fluid side. An open boundary's ghosts
// (SweParticles::mirror_end) are water beyond the line and count wherever they reach.
//
// The cells are sized for the typical support (neighbors::typical_radius), not the
// largest: the few wide particles of a thinning front would otherwise widen every cell and
// multiply the candidates of every point (gridding was an eighth of a dam-break run's time
// with cells sized for the largest). The wide particles are found through a second, coarse
// cell list of their own, as the neighbour search does (neighbors/neighbor_list.cpp).
class PointSampler {
 public:
  PointSampler(const SweParticles& p, const ParticleKernel& w) : p_(p), w_(w) {
    const std::size_t n = p.size();
    std::vector<double> supports(n), scratch;
    double largest = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      supports[j] = ParticleKernel::support(p.smoothing_length[j]);
      largest = std::max(largest, supports[j]);
    }
    cells_.build({std::span<const double>(p.x.data(), n), std::span<const double>(p.y.data(), n)},
                 neighbors::typical_radius(supports, scratch), kCellSubdivisions);
    covered_ = cells_.search_radius();
    for (std::uint32_t j = 0; j < n; ++j) {
      if (supports[j] > covered_) wide_.push_back(j);
    }
    if (wide_.empty()) return;
    wide_x_.reserve(wide_.size());
    wide_y_.reserve(wide_.size());
    for (const std::uint32_t j : wide_) {
      wide_x_.push_back(p.x[j]);
      wide_y_.push_back(p.y[j]);
    }
    wide_cells_.build({std::span<const double>(wide_x_), std::span<const double>(wide_y_)},
                      largest);
  }
  // Returns h, and (sum V u w, sum V v w) in qx, qy. The kernel shape is chosen once per
  // point, not once per particle.
  double sum(double x, double y, double& qx, double& qy) const {
    return with_kernel_shape(w_.shape(),
                             [&](const auto& kernel) { return sum_with(kernel, x, y, qx, qy); });
  }
  PointFields at(double x, double y) const {
    double qx = 0.0, qy = 0.0;
    const double h = sum(x, y, qx, qy);
    if (!(h > 0.0)) return {h, kNoValue, kNoValue};
    return {h, qx / h, qy / h};
  }

  static constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

 private:
  // Half-width cells: a 5 x 5 block fits the support's disc more tightly than 3 x 3 full
  // ones (neighbors/cell_list.hpp).
  static constexpr int kCellSubdivisions = 2;

  template <class K>
  double sum_with(const K& kernel, double x, double y, double& qx, double& qy) const {
    double h = 0.0;
    qx = 0.0;
    qy = 0.0;
    // Particle j's share at (x, y); `wide` says which of the two lists is visiting, so that
    // each particle is taken by one of them only.
    const auto add = [&](std::uint32_t j, bool wide) {
      const double hj = p_.smoothing_length[j];
      const double support = ParticleKernel::support(hj);
      if ((support > covered_) != wide) return;
      const double dx = p_.x[j] - x, dy = p_.y[j] - y;
      const double r2 = dx * dx + dy * dy;
      if (!(r2 < support * support)) return;
      if (j >= p_.fluid_count() && j < p_.mirror_end()) {
        const std::uint32_t i = p_.source[j];
        const double ix = p_.x[i] - x, iy = p_.y[i] - y;
        if (!(ix * ix + iy * iy < r2)) return;  // the point is behind the wall
      }
      const double vw = p_.volume[j] * kernel.w(std::sqrt(r2), hj);
      h += vw;
      qx += vw * p_.u[j];
      qy += vw * p_.v[j];
    };
    cells_.for_each_candidate({x, y}, [&](std::uint32_t j) { add(j, false); });
    if (!wide_.empty()) {
      wide_cells_.for_each_candidate({x, y}, [&](std::uint32_t m) { add(wide_[m], true); });
    }
    return h;
  }

  const SweParticles& p_;
  const ParticleKernel& w_;
  double covered_ = 0.0;  // every particle whose support is within this is in cells_' blocks
  neighbors::CellList<2> cells_;
  std::vector<std::uint32_t> wide_;  // the others, by index
  std::vector<double> wide_x_, wide_y_;
  neighbors::CellList<2> wide_cells_;
};

// Eq 7 and the momentum of the particles at the grid's cell centres, added up particle by
// particle: each particle adds its share to the cells within its support, with the wall
// ghosts' rule of PointSampler. A grid's points are many and regular and a young flood's
// particles few: visiting each particle's cells costs the particles' supports, where a search
// around every cell costs the whole grid (1.0 ms a step against 0.4 ms on the valley flood's
// 22,000 cells, gridded every step for the flood statistics). Bands of rows go to the
// threads, and each cell adds its particles in index order, so the maps are the same for any
// number of threads; they differ from PointSampler's sums at the same points in the order of
// the additions only.
void scatter_onto_grid(const SweParticles& p, const ParticleKernel& w, const RegularGrid& grid,
                       std::span<double> h, std::span<double> qx, std::span<double> qy) {
  const std::size_t n = p.size();
  const std::size_t fluid = p.fluid_count();
  // The cells a particle reaches, as ranges of columns and rows; empty (first > last) when
  // none.
  struct Reach {
    long i0, i1, k0, k1;
  };
  std::vector<Reach> reach(n);
  const auto cell_range = [](double centre, double support, double origin, double spacing,
                             std::size_t count) {
    const double lo = std::ceil((centre - support - origin) / spacing);
    const double hi = std::floor((centre + support - origin) / spacing);
    if (!(lo <= hi)) return std::pair<long, long>{0, -1};  // none, or NaN (nothing to cast)
    const double last = static_cast<double>(count) - 1.0;
    return std::pair<long, long>{static_cast<long>(std::clamp(lo, 0.0, last + 1.0)),
                                 static_cast<long>(std::clamp(hi, -1.0, last))};
  };
  parallel_for(n, [&](std::size_t j) {
    const double support = ParticleKernel::support(p.smoothing_length[j]);
    const auto [i0, i1] = cell_range(p.x[j], support, grid.x0, grid.dx, grid.nx);
    const auto [k0, k1] = cell_range(p.y[j], support, grid.y0, grid.dy, grid.ny);
    reach[j] = {i0, i1, k0, k1};
  });
  // One band a thread: every band visits every particle's reach, so more bands cost more.
  const std::size_t bands =
      std::min<std::size_t>(grid.ny, static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  with_kernel_shape(w.shape(), [&](const auto& kernel) {
    const auto band_count = static_cast<long>(bands);
#pragma omp parallel for schedule(static)
    for (long band = 0; band < band_count; ++band) {
      const auto b = static_cast<std::size_t>(band);
      const long band0 = static_cast<long>(b * grid.ny / bands);
      const long band1 = static_cast<long>((b + 1) * grid.ny / bands) - 1;
      for (std::size_t j = 0; j < n; ++j) {
        const Reach& r = reach[j];
        const long k0 = std::max(r.k0, band0), k1 = std::min(r.k1, band1);
        if (k0 > k1 || r.i0 > r.i1) continue;
        const double hj = p.smoothing_length[j];
        const double support = ParticleKernel::support(hj);
        const bool ghost = j >= fluid && j < p.mirror_end();
        const std::size_t source = ghost ? p.source[j] : j;
        for (long k = k0; k <= k1; ++k) {
          const double y = grid.y0 + static_cast<double>(k) * grid.dy;
          for (long i = r.i0; i <= r.i1; ++i) {
            const double x = grid.x0 + static_cast<double>(i) * grid.dx;
            const double dx = p.x[j] - x, dy = p.y[j] - y;
            const double r2 = dx * dx + dy * dy;
            if (!(r2 < support * support)) continue;
            if (ghost) {
              const double sx = p.x[source] - x, sy = p.y[source] - y;
              if (!(sx * sx + sy * sy < r2)) continue;  // the point is behind the wall
            }
            const double vw = p.volume[j] * kernel.w(std::sqrt(r2), hj);
            const std::size_t c =
                static_cast<std::size_t>(k) * grid.nx + static_cast<std::size_t>(i);
            h[c] += vw;
            qx[c] += vw * p.u[j];
            qy[c] += vw * p.v[j];
          }
        }
      }
    }
  });
}

}  // namespace

std::vector<double> depth_on_grid(const SweParticles& p, const ParticleKernel& w,
                                  const RegularGrid& grid) {
  const std::size_t cells = grid.nx * grid.ny;
  std::vector<double> depth(cells, 0.0);
  if (p.fluid_count() == 0 || cells == 0) return depth;
  std::vector<double> qx(cells, 0.0), qy(cells, 0.0);
  scatter_onto_grid(p, w, grid, depth, qx, qy);
  return depth;
}

PointFields fields_at(const SweParticles& p, const ParticleKernel& w, double x_m, double y_m) {
  if (p.fluid_count() == 0) return {0.0, PointSampler::kNoValue, PointSampler::kNoValue};
  return PointSampler(p, w).at(x_m, y_m);
}

GridFields fields_on_grid(const SweParticles& p, const ParticleKernel& w, const RegularGrid& grid) {
  const std::size_t cells = grid.nx * grid.ny;
  GridFields fields{std::vector<double>(cells, 0.0),
                    std::vector<double>(cells, PointSampler::kNoValue),
                    std::vector<double>(cells, PointSampler::kNoValue)};
  if (p.fluid_count() == 0 || cells == 0) return fields;
  std::vector<double> qx(cells, 0.0), qy(cells, 0.0);
  scatter_onto_grid(p, w, grid, fields.depth, qx, qy);
  for (std::size_t c = 0; c < cells; ++c) {
    const double h = fields.depth[c];
    if (!(h > 0.0)) continue;
    fields.u[c] = qx[c] / h;
    fields.v[c] = qy[c] / h;
  }
  return fields;
}

}  // namespace swemps::swe

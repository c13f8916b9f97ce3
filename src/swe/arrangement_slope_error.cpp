#include "swemps/swe/arrangement_slope_error.hpp"

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::swe {

namespace {

// Pairs closer than this have no direction (as in the scheme's force).
constexpr double kCoincident = 1e-12;
// The least-squares gradient needs neighbours that span the plane: at least three, and a
// second-moment matrix M whose determinant is no less than this share of trace(M)^2 / 4
// (1 for neighbours spread evenly round i, 0 for neighbours on a line: a particle in a finger
// one particle wide, or at the tip of a sheet). Below it i's error is taken as zero.
constexpr int kFewestNeighbours = 3;
constexpr double kFlattestSpread = 4e-3;

// One row's pairs, gathered: the kernels' values of every pair in one pass that vectorises,
// then the sums in the row's order, as before (so the result is the same to the bit). Why:
// pair by pair, each kernel with its divisions, this term was a tenth of Thacker's run.
struct RowScratch {
  std::vector<double> dx, dy, r, w, dw;
};

// G_i of the header: the gradient g minimising sum_j w_ij (eta_j - eta_i - g . x_ij)^2 over
// fluid neighbours with a level, x_ij = x_j - x_i, with the weights of the depth sum's own
// gradient, w_ij = A_j |W'(r_ij, h_i)| / r_ij (the corrected kernel gradient of the levels in
// difference form). False when it is not determined (above). On the way, the weight of each
// interior neighbour in <e>_i, A_j W(r_ij, h_i), goes to `average_weight` (the row's slots;
// zero for the others), so that the average needs no second distance or kernel.
//
// Why these weights: where the levels change within a kernel (a sheet's toe over a film) the
// plane's slope and G then see the change through the same weights, and e_i stays the
// arrangement's. With the kernel's values as weights, W(r_ij, h_i), e_i carried the difference
// of two smoothings of the front, and the thin film of the hard cases gained 2.1 % of its
// energy (0.6 % without the correction, 0.3 % with these weights; docs/method.md).
template <class K>
bool level_gradient(const particles::SweParticles& p, const neighbors::NeighborList& neighbors,
                    const ParticlePlanes& planes, std::size_t i, double* average_weight,
                    RowScratch& b, double& gx, double& gy) {
  const std::size_t n = p.fluid_count();
  const double hi = p.smoothing_length[i];
  const auto row = neighbors.row(i);
  const std::size_t count = row.size();
  for (auto* v : {&b.dx, &b.dy, &b.r, &b.w, &b.dw}) v->resize(count);
  double *dx = b.dx.data(), *dy = b.dy.data(), *r = b.r.data(), *w = b.w.data();
  double* dw = b.dw.data();
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t j = row[k];
    dx[k] = p.x[j] - p.x[i];
    dy[k] = p.y[j] - p.y[i];
  }
#pragma omp simd
  for (std::size_t k = 0; k < count; ++k) {
    r[k] = std::sqrt(dx[k] * dx[k] + dy[k] * dy[k]);
    w[k] = K::w(r[k], hi);
    dw[k] = K::dw_dr(r[k], hi);
  }
  double mxx = 0.0, mxy = 0.0, myy = 0.0, bx = 0.0, by = 0.0;
  int count_used = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t j = row[k];
    average_weight[k] = 0.0;
    if (j >= n || j == i || !std::isfinite(planes.level[j])) continue;
    if (!(r[k] > kCoincident)) continue;
    if (planes.interior[j]) average_weight[k] = p.area[j] * w[k];
    const double weight = -p.area[j] * dw[k] / r[k];
    if (!(weight > 0.0)) continue;
    ++count_used;
    const double rise = planes.level[j] - planes.level[i];
    mxx += weight * dx[k] * dx[k];
    mxy += weight * dx[k] * dy[k];
    myy += weight * dy[k] * dy[k];
    bx += weight * rise * dx[k];
    by += weight * rise * dy[k];
  }
  const double det = mxx * myy - mxy * mxy, trace = mxx + myy;
  if (count_used < kFewestNeighbours || !(det > 0.25 * kFlattestSpread * trace * trace))
    return false;
  gx = (myy * bx - mxy * by) / det;
  gy = (mxx * by - mxy * bx) / det;
  return true;
}

template <class K>
void remove_with(const particles::SweParticles& p, const neighbors::NeighborList& neighbors,
                 ParticlePlanes& planes, std::vector<double>& average_weight,
                 std::vector<double>& error_x, std::vector<double>& error_y) {
  const std::size_t n = p.fluid_count();
  error_x.assign(n, 0.0);
  error_y.assign(n, 0.0);
  average_weight.resize(neighbors.index.size());
  const auto takes_part = [&](std::size_t i) {
    return planes.interior[i] && std::isfinite(planes.level[i]);
  };
#pragma omp parallel if (n > static_cast <std::size_t>(parallel_threshold))
  {
    RowScratch scratch;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      if (!takes_part(i)) continue;
      double gx = 0.0, gy = 0.0;
      double* weights = average_weight.data() + neighbors.offsets[i];
      if (!level_gradient<K>(p, neighbors, planes, i, weights, scratch, gx, gy)) continue;
      error_x[i] = planes.slope_x[i] - gx;
      error_y[i] = planes.slope_y[i] - gy;
    }
  }
  // <e>_i over i itself and its interior neighbours, weighed by A_j W(r_ij, h_i), taken from
  // the slope (this pass reads only the errors, so the slopes can change as it goes).
  parallel_for(n, [&](std::size_t i) {
    if (!takes_part(i)) return;
    double weight = p.area[i] * K::w(0.0, p.smoothing_length[i]);
    double sum_x = weight * error_x[i], sum_y = weight * error_y[i];
    const auto row = neighbors.row(i);
    const double* weights = average_weight.data() + neighbors.offsets[i];
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (!(weights[k] > 0.0)) continue;
      weight += weights[k];
      sum_x += weights[k] * error_x[row[k]];
      sum_y += weights[k] * error_y[row[k]];
    }
    planes.slope_x[i] -= sum_x / weight;
    planes.slope_y[i] -= sum_y / weight;
  });
}

}  // namespace

void ArrangementSlopeError::remove(const particles::SweParticles& p,
                                   const neighbors::NeighborList& neighbors, KernelShape shape,
                                   ParticlePlanes& planes) {
  with_kernel_shape(shape, [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    remove_with<K>(p, neighbors, planes, average_weight_, error_x_, error_y_);
  });
}

}  // namespace swemps::swe

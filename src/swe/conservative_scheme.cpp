#include "swemps/swe/conservative_scheme.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/particles/resize_with_room.hpp"
#include "swemps/swe/particle_shifting.hpp"

namespace swemps::swe {

namespace {

// Newton's method on f(d) = d - S(h(d)) stops when a step changes d by less than this
// fraction: far below what any output or test resolves, and reached in two or three
// iterations from the last step's depth.
constexpr double kDepthTolerance = 1e-10;
constexpr int kMaxIterations = 50;
// A Newton step changes the depth by at most this factor either way; the cap keeps the first
// steps of a particle that has just lost or gained neighbours from overshooting.
constexpr double kLargestStep = 2.0;
// Omega below this is taken as this: Omega is about 1 in water (0.73 for a particle alone), so
// only a pathological arrangement goes lower, and Newton then degrades to a damped fixed point.
constexpr double kSmallestOmega = 0.1;
// Pairs closer than this have no direction and exert no force.
constexpr double kCoincident = 1e-12;
// v_sig = c_i + c_j - kSignalJump w_ij (Monaghan 1997 uses 4 for gas; 3 here, measured on the
// Stoker bore, docs/method.md).
constexpr double kSignalJump = 3.0;

// One row's neighbour distances and volumes, gathered once so that each Newton iteration is
// a tight loop over contiguous values (vectorised) rather than a walk through the particles.
struct RowBuffer {
  std::vector<double> r, volume;
  void gather(const particles::SweParticles& p, std::span<const std::uint32_t> row,
              std::size_t i) {
    r.resize(row.size());
    volume.resize(row.size());
    const double xi = p.x[i], yi = p.y[i];
    for (std::size_t k = 0; k < row.size(); ++k) {
      const std::uint32_t j = row[k];
      const double dx = p.x[j] - xi, dy = p.y[j] - yi;
      r[k] = std::sqrt(dx * dx + dy * dy);
      volume[k] = p.volume[j];
    }
  }
};

// The depth of particle i and its grad-h factor, by Newton's method (see the header). With
// W = sigma / h^D f(q), q = r / h, the sum and its h-derivative share the sums
// F = sum V_j f(q_j) and G = sum V_j (D f(q_j) + q_j f'(q_j)):
//   S(h) = sigma / h^D F,   dS/dh = -sigma / h^(D+1) G   (kernels/scaled_kernel.hpp).
template <class K>
std::uint32_t sum_depth_at(particles::SweParticles& p, const neighbors::NeighborList& nl,
                           std::size_t i, double kappa, double max_area_ratio, RowBuffer& row) {
  constexpr double kDim = 2.0;
  const double volume = p.volume[i];
  const double largest_area = max_area_ratio * p.initial_area[i];
  const double largest_h = kappa * std::sqrt(largest_area);
  row.gather(p, nl.row(i), i);
  const std::size_t count = row.r.size();
  const double* r = row.r.data();
  const double* v = row.volume.data();
  const double self_f = K::shape(0.0);
  double d = p.depth[i];
  if (!(d > 0.0) || !std::isfinite(d)) d = volume / p.area[i];
  double h = 0.0, sum = 0.0, omega = 1.0;
  std::uint32_t iterations = 0;
  while (iterations < kMaxIterations) {
    ++iterations;
    const double area = volume / d;
    const bool capped = area >= largest_area;
    h = capped ? largest_h : kappa * std::sqrt(area);
    const double inverse_h = 1.0 / h;
    double f_sum = volume * self_f, g_sum = volume * kDim * self_f;
#pragma omp simd reduction(+ : f_sum, g_sum)
    for (std::size_t k = 0; k < count; ++k) {
      const double q = r[k] * inverse_h;
      const double f = K::shape(q);
      f_sum += v[k] * f;
      g_sum += v[k] * (kDim * f + q * K::shape_slope(q));
    }
    const double scale = K::sigma() * inverse_h * inverse_h;  // sigma / h^2
    sum = scale * f_sum;
    const double slope = -scale * inverse_h * g_sum;
    omega = capped ? 1.0 : std::max(kSmallestOmega, 1.0 + h / (2.0 * d) * slope);
    const double next = std::clamp(d - (d - sum) / omega, d / kLargestStep, d * kLargestStep);
    const bool converged = std::abs(next - d) <= kDepthTolerance * d;
    d = next;
    if (converged) break;
  }
  // The depth is the sum at the radius it was taken with, so that depth, radius and Omega
  // belong together.
  p.depth[i] = sum;
  p.area[i] = volume / sum;
  p.smoothing_length[i] = h;
  p.omega[i] = omega;
  return iterations;
}

// One row's pair terms, gathered so that the kernel slopes and the dissipation are computed
// in a tight loop over contiguous values.
struct PairBuffer {
  std::vector<double> dx, dy, r, h, inverse_omega, volume, depth, celerity, du, dv, area;
  void resize(std::size_t n) {
    for (auto* v :
         {&dx, &dy, &r, &h, &inverse_omega, &volume, &depth, &celerity, &du, &dv, &area})
      v->resize(n);
  }
};

// With `field` (particle shifting on), the pass also sums C_i and grad C_i of
// particle_shifting.hpp: the same pairs, distances and kernel slopes.
template <class K>
void surface_acceleration_with(const particles::SweParticles& p,
                               const neighbors::NeighborList& nl, double g, double alpha,
                               std::vector<double>& celerity, std::span<double> ax,
                               std::span<double> ay, ConcentrationField* field) {
  if (field != nullptr) {
    for (auto* v : {&field->concentration, &field->gradient_x, &field->gradient_y})
      particles::resize_with_room(*v, p.fluid_count());
  }
  // c = sqrt(g d) once per particle (ghosts included), not once per pair.
  particles::resize_with_room(celerity, p.size());
  parallel_for(p.size(), [&](std::size_t k) { celerity[k] = std::sqrt(g * p.depth[k]); });
#pragma omp parallel if (p.fluid_count() > static_cast<std::size_t>(parallel_threshold))
  {
    PairBuffer b;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < p.fluid_count(); ++i) {
      const auto row = nl.row(i);
      const std::size_t count = row.size();
      b.resize(count);
      for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t j = row[k];
        b.dx[k] = p.x[i] - p.x[j];  // e = (x_i - x_j) / r: the direction j pushes i
        b.dy[k] = p.y[i] - p.y[j];
        b.h[k] = p.smoothing_length[j];
        b.inverse_omega[k] = 1.0 / p.omega[j];
        b.volume[k] = p.volume[j];
        b.depth[k] = p.depth[j];
        b.celerity[k] = celerity[j];
        b.du[k] = p.u[i] - p.u[j];
        b.dv[k] = p.v[i] - p.v[j];
        b.area[k] = p.area[j];
      }
      const double hi = p.smoothing_length[i];
      const double inverse_hi = 1.0 / hi;
      const double slope_scale_i = K::sigma() * inverse_hi * inverse_hi * inverse_hi;
      const double inverse_omega_i = 1.0 / p.omega[i];
      const double ci = celerity[i], di = p.depth[i];
      double sx = 0.0, sy = 0.0, shape_sum = 0.0, cx = 0.0, cy = 0.0;
#pragma omp simd reduction(+ : sx, sy, shape_sum, cx, cy)
      for (std::size_t k = 0; k < count; ++k) {
        const double r2 = b.dx[k] * b.dx[k] + b.dy[k] * b.dy[k];
        const double r = std::sqrt(r2);
        // Pairs closer than kCoincident have no direction and exert no force.
        const bool apart = r > kCoincident;
        const double inverse_r = apart ? 1.0 / r : 0.0;
        const double inverse_hj = 1.0 / b.h[k];
        const double slope_i = slope_scale_i * K::shape_slope(r * inverse_hi);  // dW/dr <= 0
        const double slope_j =
            K::sigma() * inverse_hj * inverse_hj * inverse_hj * K::shape_slope(r * inverse_hj);
        // -(g/2) V_j (W'_i / Omega_i + W'_j / Omega_j) along e: pressure pushes i away from j.
        double push = -0.5 * g * (slope_i * inverse_omega_i + slope_j * b.inverse_omega[k]);
        // Dissipation on approaching pairs only: w < 0; zero for w >= 0 (see the header).
        const double w = std::min(0.0, (b.du[k] * b.dx[k] + b.dv[k] * b.dy[k]) * inverse_r);
        const double signal = ci + b.celerity[k] - kSignalJump * w;
        const double pi = -alpha * signal * w / (di + b.depth[k]);  // >= 0
        push -= pi * 0.5 * (slope_i + slope_j);
        const double f = b.volume[k] * push * inverse_r;
        sx += f * b.dx[k];
        sy += f * b.dy[k];
        // C_i and grad C_i (particle_shifting.hpp); a few operations more per pair, summed
        // whether or not they are used, so that the loop has no branch.
        shape_sum += b.area[k] * K::shape(r * inverse_hi);
        const double c = b.area[k] * 0.5 * (slope_i + slope_j) * inverse_r;
        cx += c * b.dx[k];
        cy += c * b.dy[k];
      }
      ax[i] = sx;
      ay[i] = sy;
      if (field != nullptr) {
        field->concentration[i] =
            K::sigma() * inverse_hi * inverse_hi * (shape_sum + p.area[i] * K::shape(0.0));
        field->gradient_x[i] = cx;
        field->gradient_y[i] = cy;
      }
    }
  }
}

}  // namespace

ConservativeScheme::ConservativeScheme(const Settings& settings)
    : kernel_(settings.kernel),
      kappa_(settings.kappa),
      max_area_ratio_(settings.area_ratio_cap()),
      dissipation_(settings.dissipation),
      shifting_(settings.shifting) {
  if (!(kappa_ > 0.0) || !std::isfinite(kappa_))
    throw std::invalid_argument("conservative scheme: kappa must be finite and > 0");
  if (!(dissipation_ >= 0.0) || !std::isfinite(dissipation_))
    throw std::invalid_argument("conservative scheme: dissipation must be finite and >= 0");
  if (!(shifting_ >= 0.0) || !std::isfinite(shifting_))
    throw std::invalid_argument("conservative scheme: shifting must be finite and >= 0");
}

void ConservativeScheme::choose_smoothing_lengths(particles::SweParticles& p) {
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    if (p.smoothing_length[i] > 0.0) return;
    const double area = std::min(p.area[i], max_area_ratio_ * p.initial_area[i]);
    p.smoothing_length[i] = kappa_ * std::sqrt(area);
  });
}

bool ConservativeScheme::sum_depth(particles::SweParticles& p,
                                   const neighbors::NeighborList& nl) {
  return sum_depths(p, nl, {}, true);
}

bool ConservativeScheme::sum_depth_of(particles::SweParticles& p, const neighbors::NeighborList& nl,
                                      std::span<const std::uint32_t> which) {
  return sum_depths(p, nl, which, false);
}

bool ConservativeScheme::sum_depths(particles::SweParticles& p, const neighbors::NeighborList& nl,
                                    std::span<const std::uint32_t> which, bool every) {
  const std::size_t count = every ? p.fluid_count() : which.size();
  iterations_.assign(count, 0);
  grown_.assign(count, 0);
  with_kernel_shape(kernel_.shape(), [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
#pragma omp parallel if (count > static_cast <std::size_t>(parallel_threshold))
    {
      RowBuffer row;
#pragma omp for schedule(static)
      for (std::size_t m = 0; m < count; ++m) {
        const std::size_t i = every ? m : which[m];
        const double searched_h = p.smoothing_length[i];
        iterations_[m] = sum_depth_at<K>(p, nl, i, kappa_, max_area_ratio_, row);
        grown_[m] = p.smoothing_length[i] > searched_h * (1.0 + kSearchMargin);
      }
    }
  });
  last_iterations_ = 0;
  last_most_iterations_ = 0;
  for (const std::uint32_t k : iterations_) {
    last_iterations_ += k;
    last_most_iterations_ = std::max<std::size_t>(last_most_iterations_, k);
  }
  outgrown_.clear();
  for (std::size_t m = 0; m < count; ++m)
    if (grown_[m]) outgrown_.push_back(static_cast<std::uint32_t>(every ? m : which[m]));
  return outgrown_.empty();
}

void ConservativeScheme::surface_acceleration(particles::SweParticles& p,
                                              const neighbors::NeighborList& nl,
                                              double gravity_m_s2, std::span<double> accel_x,
                                              std::span<double> accel_y) {
  with_kernel_shape(kernel_.shape(), [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    surface_acceleration_with<K>(p, nl, gravity_m_s2, dissipation_, celerity_, accel_x, accel_y,
                                 shifting_ > 0.0 ? &concentration_ : nullptr);
  });
}

bool ConservativeScheme::regularising_shift(const particles::SweParticles& p,
                                            const neighbors::NeighborList& nl, double dt_s,
                                            std::span<double> shift_x,
                                            std::span<double> shift_y) {
  if (shifting_ == 0.0) return false;
  // The concentration field of this step's force pass: the same list and fields.
  particle_shift(p, nl, kernel_.shape(), shifting_, dt_s, concentration_, celerity_, shift_x,
                 shift_y);
  return true;
}

}  // namespace swemps::swe

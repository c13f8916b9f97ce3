#include "swemps/swe/conservative_scheme.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "swemps/neighbors/parallel.hpp"

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

// The depth of particle i and its grad-h factor, by Newton's method (see the header).
template <class K>
std::uint32_t sum_depth_at(particles::SweParticles& p, const neighbors::NeighborList& nl,
                           std::size_t i, double kappa, double max_area_ratio) {
  const double volume = p.volume[i];
  const double largest_area = max_area_ratio * p.initial_area[i];
  const double largest_h = kappa * std::sqrt(largest_area);
  const auto row = nl.row(i);
  double d = p.depth[i];
  if (!(d > 0.0) || !std::isfinite(d)) d = volume / p.area[i];
  double h = 0.0, sum = 0.0, omega = 1.0;
  std::uint32_t iterations = 0;
  while (iterations < kMaxIterations) {
    ++iterations;
    const double area = volume / d;
    const bool capped = area >= largest_area;
    h = capped ? largest_h : kappa * std::sqrt(area);
    sum = volume * K::w(0.0, h);
    double slope = volume * K::dw_dh(0.0, h);
    for (const std::uint32_t j : row) {
      const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i];
      const double r = std::sqrt(dx * dx + dy * dy);
      sum += p.volume[j] * K::w(r, h);
      slope += p.volume[j] * K::dw_dh(r, h);
    }
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

template <class K>
void surface_acceleration_with(const particles::SweParticles& p,
                               const neighbors::NeighborList& nl, double g, double alpha,
                               std::span<double> ax, std::span<double> ay) {
  parallel_for(p.fluid_count(), [&](std::size_t i) {
    const double hi = p.smoothing_length[i];
    const double inverse_omega_i = 1.0 / p.omega[i];
    const double ci = std::sqrt(g * p.depth[i]);
    double sx = 0.0, sy = 0.0;
    for (const std::uint32_t j : nl.row(i)) {
      // e = (x_i - x_j) / r, the direction in which j pushes i.
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      const double r = std::sqrt(dx * dx + dy * dy);
      if (!(r > kCoincident)) continue;
      const double hj = p.smoothing_length[j];
      const double slope_i = K::dw_dr(r, hi), slope_j = K::dw_dr(r, hj);  // <= 0
      // -(g/2) V_j (W'_i / Omega_i + W'_j / Omega_j) along e: pressure pushes i away from j.
      double push = -0.5 * g * (slope_i * inverse_omega_i + slope_j / p.omega[j]);
      const double approach = ((p.u[i] - p.u[j]) * dx + (p.v[i] - p.v[j]) * dy) / r;
      if (approach < 0.0) {
        const double cj = std::sqrt(g * p.depth[j]);
        const double signal = ci + cj - kSignalJump * approach;
        const double pi = -alpha * signal * approach / (p.depth[i] + p.depth[j]);  // > 0
        push -= pi * 0.5 * (slope_i + slope_j);
      }
      const double f = p.volume[j] * push / r;
      sx += f * dx;
      sy += f * dy;
    }
    ax[i] = sx;
    ay[i] = sy;
  });
}

}  // namespace

ConservativeScheme::ConservativeScheme(const Settings& settings)
    : kernel_(settings.kernel),
      kappa_(settings.kappa),
      max_area_ratio_(settings.max_area_ratio),
      dissipation_(settings.dissipation) {
  if (!(kappa_ > 0.0) || !std::isfinite(kappa_))
    throw std::invalid_argument("conservative scheme: kappa must be finite and > 0");
  if (!(dissipation_ >= 0.0) || !std::isfinite(dissipation_))
    throw std::invalid_argument("conservative scheme: dissipation must be finite and >= 0");
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
  const std::size_t n = p.fluid_count();
  iterations_.assign(n, 0);
  std::vector<std::uint8_t> outgrown(n, 0);
  with_kernel_shape(kernel_.shape(), [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    parallel_for(n, [&](std::size_t i) {
      const double searched_h = p.smoothing_length[i];
      iterations_[i] = sum_depth_at<K>(p, nl, i, kappa_, max_area_ratio_);
      outgrown[i] = p.smoothing_length[i] > searched_h * (1.0 + kSearchMargin);
    });
  });
  last_iterations_ = 0;
  last_most_iterations_ = 0;
  for (const std::uint32_t k : iterations_) {
    last_iterations_ += k;
    last_most_iterations_ = std::max<std::size_t>(last_most_iterations_, k);
  }
  return std::none_of(outgrown.begin(), outgrown.end(), [](std::uint8_t o) { return o != 0; });
}

void ConservativeScheme::surface_acceleration(particles::SweParticles& p,
                                              const neighbors::NeighborList& nl,
                                              double gravity_m_s2, std::span<double> accel_x,
                                              std::span<double> accel_y) {
  with_kernel_shape(kernel_.shape(), [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    surface_acceleration_with<K>(p, nl, gravity_m_s2, dissipation_, accel_x, accel_y);
  });
}

}  // namespace swemps::swe

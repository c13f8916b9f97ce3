#include "swemps/swe/balanced_bed_slope.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "swemps/neighbors/parallel.hpp"
#include "swemps/swe/bed_slope.hpp"

namespace swemps::swe {

namespace {

// Pairs closer than this have no direction and exert no force (as in the scheme's force).
constexpr double kCoincident = 1e-12;
// Each Newton step on (*) wets or dries at least one node; a particle's support holds a few
// hundred nodes at the widest radius, so this is never reached by a well-posed sum.
constexpr int kMaxLevelSteps = 1000;
// The level is exact once the wet set stops changing; round-off leaves an excess of about
// 1e-16 of the depth, which this stops on.
constexpr double kLevelTolerance = 1e-13;
// The smallest eigenvalue of the first moment M that the corrected gradient divides by: a full
// support has M = I, a half support (a straight shore) about 1/2 across the shore. Measured on
// Thacker's bowl: 0.25 lets a thin edge's round-off grow until the run breaks down at 10 s;
// 0.4 and 0.5 give the same error (docs/method.md).
constexpr double kSmallestMoment = 0.5;

// The nodes around one particle, gathered once so that the level's Newton steps are tight
// loops over contiguous values.
struct NodeBuffer {
  std::vector<double> z, w;
};

template <class K>
double surface_at(const BedLattice& lattice, double x, double y, double h, double depth,
                  double fallback_bed, NodeBuffer& nodes) {
  nodes.z.clear();
  nodes.w.clear();
  const double a = lattice.node_area_m2();
  lattice.for_each_node_within(x, y, 2.0 * h, [&](double r2, double z) {
    nodes.z.push_back(z);
    nodes.w.push_back(a * K::w(std::sqrt(r2), h));
  });
  const double level = level_holding(nodes.z, nodes.w, depth);
  // Beyond the lattice (never inside the domain): the bed at the particle.
  return std::isfinite(level) ? level : depth + fallback_bed;
}

// M^-1 (gx, gy) for the symmetric moment M = [[mxx, mxy], [mxy, myy]] (about the identity
// where the support is full), with M's eigenvalues taken as no less than kSmallestMoment: a
// particle whose neighbours lie almost on a line (a thin jet, a lone particle) has a moment
// near zero across the line, and dividing by it would turn round-off into force.
std::array<double, 2> corrected(double mxx, double mxy, double myy, double gx, double gy) {
  const double mean = 0.5 * (mxx + myy);
  const double spread = std::sqrt(0.25 * (mxx - myy) * (mxx - myy) + mxy * mxy);
  const double large = mean + spread, small = mean - spread;
  if (!(small >= kSmallestMoment)) {
    // Eigenvectors: (cos t, sin t) for the large eigenvalue, with tan 2t = 2 mxy / (mxx - myy).
    const double t = 0.5 * std::atan2(2.0 * mxy, mxx - myy);
    const double ex = std::cos(t), ey = std::sin(t);
    const double along = (ex * gx + ey * gy) / std::max(large, kSmallestMoment);
    const double across = (-ey * gx + ex * gy) / std::max(small, kSmallestMoment);
    return {along * ex - across * ey, along * ey + across * ex};
  }
  const double det = mxx * myy - mxy * mxy;
  return {(myy * gx - mxy * gy) / det, (mxx * gy - mxy * gx) / det};
}

template <class K>
void apply_with(const BedSource& bed, const BedLattice& lattice, StepContext& c,
                std::vector<double>& surface) {
  auto& p = c.particles;
  const std::size_t n = p.fluid_count();
  sample_bed_at_particles(bed, p);

  surface.resize(p.size());
#pragma omp parallel if (n > static_cast <std::size_t>(parallel_threshold))
  {
    NodeBuffer nodes;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      surface[i] = surface_at<K>(lattice, p.x[i], p.y[i], p.smoothing_length[i], p.depth[i],
                                 p.bed[i], nodes);
    }
  }
  // A ghost is its fluid particle's water mirrored: the same surface.
  for (std::size_t k = n; k < p.size(); ++k) surface[k] = surface[p.source[k]];

  const double g = c.settings.gravity_m_s2;
  parallel_for(n, [&](std::size_t i) {
    const double hi = p.smoothing_length[i], inverse_omega_i = 1.0 / p.omega[i];
    const double eta_i = surface[i];
    // G: the surface's difference sum; M: its first moment, which G divides by so that a
    // plane surface has its exact gradient even where the support is cut by a shore;
    // P: the scheme's own pressure sum, which the total replaces.
    double gx = 0.0, gy = 0.0, mxx = 0.0, mxy = 0.0, myy = 0.0, px = 0.0, py = 0.0;
    for (const std::uint32_t j : c.neighbors.row(i)) {
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      const double r = std::sqrt(dx * dx + dy * dy);
      if (!(r > kCoincident)) continue;
      const double hj = p.smoothing_length[j];
      const double wi = K::dw_dr(r, hi), wj = K::dw_dr(r, hj);  // <= 0
      const double plain = 0.5 * (wi + wj) / r;                 // grad W = plain (x_i - x_j)
      const double a = p.area[j] * plain;
      const double difference = a * (surface[j] - eta_i);
      gx += difference * dx;
      gy += difference * dy;
      mxx -= a * dx * dx;
      mxy -= a * dx * dy;
      myy -= a * dy * dy;
      const double pressure = p.volume[j] * 0.5 * (wi * inverse_omega_i + wj / p.omega[j]) / r;
      px += pressure * dx;
      py += pressure * dy;
    }
    const auto [cx, cy] = corrected(mxx, mxy, myy, gx, gy);
    c.accel_x[i] += -g * cx + g * px;
    c.accel_y[i] += -g * cy + g * py;
  });
}

}  // namespace

double level_holding(std::span<const double> z, std::span<const double> w, double depth) {
  double weight = 0.0, weighted_z = 0.0;
  for (std::size_t k = 0; k < z.size(); ++k) {
    weight += w[k];
    weighted_z += w[k] * z[k];
  }
  if (!(weight > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // Every node wet: sum w (eta - z) = depth. The function below is >= its all-wet line, so
  // this eta is at or above the root, and Newton's steps from there descend onto it.
  double level = (depth + weighted_z) / weight;
  for (int step = 0; step < kMaxLevelSteps; ++step) {
    double held = 0.0, wet_weight = 0.0;
    for (std::size_t k = 0; k < z.size(); ++k) {
      const bool wet = z[k] < level;
      held += wet ? w[k] * (level - z[k]) : 0.0;
      wet_weight += wet ? w[k] : 0.0;
    }
    const double excess = held - depth;
    if (!(excess > kLevelTolerance * depth) || !(wet_weight > 0.0)) break;
    const double next = level - excess / wet_weight;
    if (!(next < level)) break;  // round-off: the root is reached
    level = next;
  }
  return level;
}

void BalancedBedSlope::apply(StepContext& context) {
  with_kernel_shape(context.kernel.shape(), [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    apply_with<K>(*bed_, *lattice_, context, surface_);
  });
}

}  // namespace swemps::swe

#include "swemps/swe/bed_lattice.hpp"

#include <algorithm>
#include <stdexcept>

namespace swemps::swe {

namespace {

// v reflected into [lo, hi] across whichever edge it lies beyond (once: the margin is far
// narrower than the domain in any scene that has water).
double mirrored(double v, double lo, double hi) {
  if (v < lo) return std::min(hi, 2.0 * lo - v);
  if (v > hi) return std::max(lo, 2.0 * hi - v);
  return v;
}

}  // namespace

BedLattice::BedLattice(const BedSource& bed, const BedLatticeGeometry& geometry,
                       const DomainBox& domain, double margin_m)
    : geometry_(geometry), domain_(domain) {
  if (!(geometry.dx_m > 0.0) || !(geometry.dy_m > 0.0) || !std::isfinite(geometry.dx_m) ||
      !std::isfinite(geometry.dy_m) || !(geometry.node_area_m2 > 0.0)) {
    throw std::invalid_argument("bed lattice: the cell must have positive, finite sides and area");
  }
  if (!(margin_m >= 0.0) || !(domain.x_max > domain.x_min) || !(domain.y_max > domain.y_min)) {
    throw std::invalid_argument("bed lattice: empty domain or negative margin");
  }
  // The first and last node index within the padded domain along each axis.
  const auto first = [](double lo, double origin, double step) {
    return static_cast<long>(std::ceil((lo - origin) / step - 0.5));
  };
  const auto last = [](double hi, double origin, double step) {
    return static_cast<long>(std::floor((hi - origin) / step - 0.5));
  };
  const long i0 = first(domain.x_min - margin_m, geometry.x0_m, geometry.dx_m);
  const long i1 = last(domain.x_max + margin_m, geometry.x0_m, geometry.dx_m);
  const long k0 = first(domain.y_min - margin_m, geometry.y0_m, geometry.dy_m);
  const long k1 = last(domain.y_max + margin_m, geometry.y0_m, geometry.dy_m);
  nx_ = std::max(0L, i1 - i0 + 1);
  ny_ = std::max(0L, k1 - k0 + 1);
  first_x_ = geometry.x0_m + (static_cast<double>(i0) + 0.5) * geometry.dx_m;
  first_y_ = geometry.y0_m + (static_cast<double>(k0) + 0.5) * geometry.dy_m;
  z_.resize(static_cast<std::size_t>(nx_ * ny_));
  for (long k = 0; k < ny_; ++k) {
    const double y =
        mirrored(first_y_ + static_cast<double>(k) * geometry.dy_m, domain.y_min, domain.y_max);
    for (long i = 0; i < nx_; ++i) {
      const double x =
          mirrored(first_x_ + static_cast<double>(i) * geometry.dx_m, domain.x_min, domain.x_max);
      z_[static_cast<std::size_t>(k * nx_ + i)] = bed.elevation(x, y);
    }
  }
}

void BedLattice::raise_node_at(double x_m, double y_m, double level_m) {
  // The point and its mirror images across the domain's edges, which carry its bed.
  const std::array<double, 3> xs{x_m, 2.0 * domain_.x_min - x_m, 2.0 * domain_.x_max - x_m};
  const std::array<double, 3> ys{y_m, 2.0 * domain_.y_min - y_m, 2.0 * domain_.y_max - y_m};
  for (const double x : xs) {
    for (const double y : ys) {
      const double gx = (x - first_x_) / geometry_.dx_m, gy = (y - first_y_) / geometry_.dy_m;
      const double i = std::round(gx), k = std::round(gy);
      // A node, not a point between nodes (a coarser body's lattice): those are left alone.
      constexpr double kOnNode = 1e-6;
      if (std::abs(gx - i) > kOnNode || std::abs(gy - k) > kOnNode) continue;
      if (i < 0.0 || k < 0.0 || i >= static_cast<double>(nx_) || k >= static_cast<double>(ny_))
        continue;
      double& z = z_[static_cast<std::size_t>(k) * static_cast<std::size_t>(nx_) +
                     static_cast<std::size_t>(i)];
      z = std::max(z, level_m);
    }
  }
}

}  // namespace swemps::swe

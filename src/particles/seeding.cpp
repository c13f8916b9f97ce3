#include "swemps/particles/seeding.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swemps::particles {

double polygon_area(const std::vector<std::array<double, 2>>& polygon) {
  double twice = 0.0;  // shoelace formula
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const auto& a = polygon[k];
    const auto& b = polygon[(k + 1) % polygon.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return std::abs(twice) / 2.0;
}

bool point_in_polygon(const std::vector<std::array<double, 2>>& polygon, std::array<double, 2> p) {
  bool inside = false;  // even-odd crossing rule
  for (std::size_t k = 0, m = polygon.size() - 1; k < polygon.size(); m = k++) {
    const auto& a = polygon[k];
    const auto& b = polygon[m];
    if ((a[1] > p[1]) != (b[1] > p[1]) &&
        p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]) {
      inside = !inside;
    }
  }
  return inside;
}

namespace {

bool is_axis_aligned_rectangle(const std::vector<std::array<double, 2>>& polygon) {
  if (polygon.size() != 4) return false;
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& a = polygon[k];
    const auto& b = polygon[(k + 1) % 4];
    if (a[0] != b[0] && a[1] != b[1]) return false;
  }
  return polygon_area(polygon) > 0.0;
}

}  // namespace

Lattice fill_polygon(const std::vector<std::array<double, 2>>& polygon, double spacing_m) {
  if (polygon.size() < 3) throw std::invalid_argument("fill_polygon: fewer than 3 vertices");
  if (!(spacing_m > 0.0)) throw std::invalid_argument("fill_polygon: spacing must be > 0");
  double x_min = polygon[0][0], x_max = x_min, y_min = polygon[0][1], y_max = y_min;
  for (const auto& v : polygon) {
    x_min = std::min(x_min, v[0]);
    x_max = std::max(x_max, v[0]);
    y_min = std::min(y_min, v[1]);
    y_max = std::max(y_max, v[1]);
  }
  Lattice lattice;
  if (is_axis_aligned_rectangle(polygon)) {
    const auto nx = std::max<long>(1, std::lround((x_max - x_min) / spacing_m));
    const auto ny = std::max<long>(1, std::lround((y_max - y_min) / spacing_m));
    const double dx = (x_max - x_min) / static_cast<double>(nx);
    const double dy = (y_max - y_min) / static_cast<double>(ny);
    lattice.points.reserve(static_cast<std::size_t>(nx * ny));
    for (long k = 0; k < ny; ++k)
      for (long i = 0; i < nx; ++i)
        lattice.points.push_back({x_min + (static_cast<double>(i) + 0.5) * dx,
                                  y_min + (static_cast<double>(k) + 0.5) * dy});
    lattice.cell_area_m2 = dx * dy;
    lattice.corner = {x_min, y_min};
    lattice.dx_m = dx;
    lattice.dy_m = dy;
    return lattice;
  }
  const auto nx = static_cast<long>(std::ceil((x_max - x_min) / spacing_m));
  const auto ny = static_cast<long>(std::ceil((y_max - y_min) / spacing_m));
  for (long k = 0; k < ny; ++k)
    for (long i = 0; i < nx; ++i) {
      const std::array<double, 2> p{x_min + (static_cast<double>(i) + 0.5) * spacing_m,
                                    y_min + (static_cast<double>(k) + 0.5) * spacing_m};
      if (point_in_polygon(polygon, p)) lattice.points.push_back(p);
    }
  if (lattice.points.empty()) {
    throw std::invalid_argument("fill_polygon: the polygon is thinner than the spacing");
  }
  lattice.cell_area_m2 = polygon_area(polygon) / static_cast<double>(lattice.points.size());
  lattice.corner = {x_min, y_min};
  lattice.dx_m = spacing_m;
  lattice.dy_m = spacing_m;
  return lattice;
}

}  // namespace swemps::particles

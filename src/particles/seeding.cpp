#include "swemps/particles/seeding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

std::vector<char> connected_to(const Lattice& lattice, const std::vector<char>& wet,
                               std::array<double, 2> from) {
  const std::size_t n = lattice.points.size();
  if (wet.size() != n) throw std::invalid_argument("connected_to: one flag per lattice point");
  std::vector<char> reached(n, 0);
  if (n == 0) return reached;
  // Lattice indices (i, k) of every point; the points of a shape are a subset of the block.
  const auto index = [&](double v, double corner, double step) {
    return static_cast<long>(std::lround((v - corner) / step - 0.5));
  };
  long i_max = 0, k_max = 0;
  std::vector<std::array<long, 2>> ik(n);
  for (std::size_t m = 0; m < n; ++m) {
    ik[m] = {index(lattice.points[m][0], lattice.corner[0], lattice.dx_m),
             index(lattice.points[m][1], lattice.corner[1], lattice.dy_m)};
    i_max = std::max(i_max, ik[m][0]);
    k_max = std::max(k_max, ik[m][1]);
  }
  const std::size_t nx = static_cast<std::size_t>(i_max + 1), ny = static_cast<std::size_t>(k_max + 1);
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> at(nx * ny, kNone);
  std::size_t start = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < n; ++m) {
    at[static_cast<std::size_t>(ik[m][1]) * nx + static_cast<std::size_t>(ik[m][0])] = m;
    const double d = std::hypot(lattice.points[m][0] - from[0], lattice.points[m][1] - from[1]);
    if (d < nearest) {
      nearest = d;
      start = m;
    }
  }
  if (!wet[start]) return reached;
  std::vector<std::size_t> stack{start};
  reached[start] = 1;
  while (!stack.empty()) {
    const std::size_t m = stack.back();
    stack.pop_back();
    const long i = ik[m][0], k = ik[m][1];
    for (const auto& [di, dk] : {std::array<long, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1},
                                 {1, -1}, {-1, 1}, {-1, -1}}) {
      const long a = i + di, b = k + dk;
      if (a < 0 || b < 0 || a > i_max || b > k_max) continue;
      const std::size_t next = at[static_cast<std::size_t>(b) * nx + static_cast<std::size_t>(a)];
      if (next == kNone || reached[next] || !wet[next]) continue;
      reached[next] = 1;
      stack.push_back(next);
    }
  }
  return reached;
}

}  // namespace swemps::particles

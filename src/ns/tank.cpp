#include "swemps/ns/tank.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swemps::ns {

namespace {

template <int Dim>
bool inside(const Box<Dim>& box, const std::array<double, Dim>& x) {
  for (int d = 0; d < Dim; ++d) {
    if (x[d] < box.lower[d] || x[d] > box.upper[d]) return false;
  }
  return true;
}

// Visits every index tuple in [lo, hi) per axis, x fastest.
template <int Dim, class F>
void for_each_node(const std::array<long, Dim>& lo, const std::array<long, Dim>& hi, F&& f) {
  std::array<long, Dim> i = lo;
  for (int d = 0; d < Dim; ++d) {
    if (lo[d] >= hi[d]) return;
  }
  while (true) {
    f(i);
    int d = 0;
    while (d < Dim && ++i[d] == hi[d]) {
      i[d] = lo[d];
      ++d;
    }
    if (d == Dim) return;
  }
}

}  // namespace

template <int Dim>
Particles<Dim> fill_tank(const TankSpec<Dim>& spec) {
  const double l0 = spec.spacing_m;
  if (!(l0 > 0.0) || !std::isfinite(l0)) {
    throw std::invalid_argument("tank: spacing must be finite and > 0");
  }
  if (spec.solid_layers < 1) throw std::invalid_argument("tank: at least one solid layer");
  std::array<long, Dim> cells{};
  for (int d = 0; d < Dim; ++d) {
    const double n = (spec.interior.upper[d] - spec.interior.lower[d]) / l0;
    cells[d] = std::lround(n);
    if (!(n >= 1.0) || std::abs(n - static_cast<double>(cells[d])) > 1e-6) {
      throw std::invalid_argument("tank: side " + std::to_string(d) + " is " + std::to_string(n) +
                                  " spacings; it must be a whole number >= 1");
    }
  }
  for (const auto& box : spec.water) {
    for (int d = 0; d < Dim; ++d) {
      if (box.lower[d] < spec.interior.lower[d] - 1e-9 * l0 ||
          box.upper[d] > spec.interior.upper[d] + 1e-9 * l0 || !(box.upper[d] > box.lower[d])) {
        throw std::invalid_argument("tank: a water box is empty or not inside the tank");
      }
    }
  }
  auto node = [&](const std::array<long, Dim>& i) {
    std::array<double, Dim> x{};
    for (int d = 0; d < Dim; ++d) {
      x[d] = spec.interior.lower[d] + (static_cast<double>(i[d]) + 0.5) * l0;
    }
    return x;
  };
  // Solid layer of a node outside the interior: how many cells it lies beyond the nearest
  // wall plane, counted per axis and maximised (corners belong to the outer layer).
  auto layer = [&](const std::array<long, Dim>& i) {
    long depth = 0;
    for (int d = 0; d < Dim; ++d) {
      if (i[d] < 0) depth = std::max(depth, -i[d]);
      if (i[d] >= cells[d]) depth = std::max(depth, i[d] - cells[d] + 1);
    }
    return depth;
  };

  Particles<Dim> p;
  std::array<long, Dim> zero{};
  for_each_node<Dim>(zero, cells, [&](const std::array<long, Dim>& i) {
    const auto x = node(i);
    for (const auto& box : spec.water) {
      if (inside<Dim>(box, x)) {
        p.add(Kind::fluid, x);
        break;
      }
    }
  });
  // The solid wraps the sides and the floor; the top stays open.
  std::array<long, Dim> lo{}, hi{};
  for (int d = 0; d < Dim; ++d) {
    lo[d] = -spec.solid_layers;
    hi[d] = cells[d] + (d == Dim - 1 ? 0 : spec.solid_layers);
  }
  for (long wanted = 1; wanted <= spec.solid_layers; ++wanted) {
    for_each_node<Dim>(lo, hi, [&](const std::array<long, Dim>& i) {
      if (layer(i) == wanted) p.add(wanted == 1 ? Kind::wall : Kind::dummy, node(i));
    });
  }
  return p;
}

template Particles<2> fill_tank<2>(const TankSpec<2>&);
template Particles<3> fill_tank<3>(const TankSpec<3>&);

}  // namespace swemps::ns

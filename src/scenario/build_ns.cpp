// From a validated scene to a Navier-Stokes run: the tank and its water boxes on one lattice.

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/memory_check.hpp"

namespace swemps::scenario {

namespace {

// The tank's floor: a level plane's elevation, or z = 0 without a bed (check_ns_scene
// refuses every other bed).
double floor_elevation(const Scenario& scene) {
  const auto* plane = std::get_if<PlaneBedSpec>(&scene.bed);
  return plane ? plane->elevation_m : 0.0;
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

}  // namespace

template <int Dim>
ns::TankSpec<Dim> ns_tank(const Scenario& scene) {
  if (scene.dimension != Dim) {
    throw std::invalid_argument("ns_tank: a " + std::to_string(Dim) + "D tank for a " +
                                std::to_string(scene.dimension) + "D scene");
  }
  check_ns_scene(scene);
  const NsSpec& spec = *scene.ns;
  const double floor = floor_elevation(scene);
  ns::TankSpec<Dim> tank;
  tank.spacing_m = spec.settings.spacing_m;
  const double support = std::max(spec.settings.pressure_kernel.support_spacings,
                                  spec.settings.velocity_kernel.support_spacings);
  // A wall particle's support must be full of solid: as many layers as the support reaches.
  // The slack keeps a support of exactly 3 spacings at 3 layers despite rounding.
  tank.solid_layers = static_cast<int>(std::ceil(support - 1e-9));
  tank.interior.lower[0] = scene.domain.x_min;
  tank.interior.upper[0] = scene.domain.x_max;
  if constexpr (Dim == 3) {
    tank.interior.lower[1] = scene.domain.y_min;
    tank.interior.upper[1] = scene.domain.y_max;
  }
  tank.interior.lower[Dim - 1] = floor;
  tank.interior.upper[Dim - 1] = floor + *spec.tank_height_m;
  for (const WaterBody& w : scene.water) {
    // check_ns_scene made every body an axis-aligned rectangle of uniform depth.
    double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
    double y_min = x_min, y_max = -x_min;
    for (const Point& p : w.polygon) {
      x_min = std::min(x_min, p[0]);
      x_max = std::max(x_max, p[0]);
      y_min = std::min(y_min, p[1]);
      y_max = std::max(y_max, p[1]);
    }
    ns::Box<Dim> box;
    box.lower[0] = x_min;
    box.upper[0] = x_max;
    if constexpr (Dim == 3) {
      box.lower[1] = y_min;
      box.upper[1] = y_max;
    }
    box.lower[Dim - 1] = floor;
    box.upper[Dim - 1] = floor + std::get<UniformDepth>(w.depth).depth_m;
    tank.water.push_back(box);
  }
  return tank;
}

template <int Dim>
ns::Simulation<Dim> make_ns_simulation(const Scenario& scene) {
  const ns::TankSpec<Dim> tank = ns_tank<Dim>(scene);
  check_fits_in_memory(ns_memory_need(scene, tank), usable_memory_bytes());
  ns::Particles<Dim> particles;
  try {
    particles = ns::fill_tank<Dim>(tank);
  } catch (const std::invalid_argument& e) {
    // check_ns_scene has made the sides whole spacings already; what is left is the lattice.
    throw ScenarioError("/ns/spacing", e.what(), "a spacing the tank's lattice accepts");
  }
  if (particles.fluid == 0) {
    throw ScenarioError(
        "/water", "water boxes holding no lattice node of spacing " + fmt(tank.spacing_m) + " m",
        "water at least one spacing (ns.spacing) long, wide and deep");
  }
  std::array<double, Dim> lower{}, upper{};
  const double solid = tank.solid_layers * tank.spacing_m;
  for (int d = 0; d < Dim; ++d) {
    lower[d] = tank.interior.lower[d] - solid;
    upper[d] = tank.interior.upper[d] + solid;
  }
  try {
    return ns::Simulation<Dim>(std::move(particles), scene.ns->settings, lower, upper);
  } catch (const std::invalid_argument& e) {
    throw ScenarioError("/ns", e.what(), "settings the Navier-Stokes solver accepts");
  }
}

template ns::TankSpec<2> ns_tank<2>(const Scenario&);
template ns::TankSpec<3> ns_tank<3>(const Scenario&);
template ns::Simulation<2> make_ns_simulation<2>(const Scenario&);
template ns::Simulation<3> make_ns_simulation<3>(const Scenario&);

}  // namespace swemps::scenario

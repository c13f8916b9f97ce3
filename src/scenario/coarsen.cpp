#include "swemps/scenario/coarsen.hpp"

#include <cmath>
#include <stdexcept>

namespace swemps::scenario {

Scenario coarsened(const Scenario& scene, int factor) {
  if (factor < 1) throw std::invalid_argument("coarsened: a factor below 1");
  Scenario out = scene;
  if (factor == 1) return out;
  const double f = static_cast<double>(factor);
  for (auto& w : out.water) w.spacing_m *= f;
  for (auto& in : out.inflows) in.spacing_m *= f;
  if (out.splitting && out.splitting->max_particles > 0) {
    const auto cap = std::ceil(static_cast<double>(out.splitting->max_particles) / (f * f));
    out.splitting->max_particles = static_cast<std::size_t>(std::max(1.0, cap));
  }
  if (out.ns) {
    out.ns->settings.spacing_m *= f;
    if (out.model == Model::ns) check_ns_scene(out);
  }
  return out;
}

}  // namespace swemps::scenario

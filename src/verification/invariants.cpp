#include "swemps/verification/invariants.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "swemps/swe/simulation.hpp"

namespace swemps::verification {

namespace {

// The first non-finite field of particle i, or nullptr.
const char* non_finite_field(const particles::SweParticles& p, std::size_t i) {
  if (!std::isfinite(p.x[i])) return "x";
  if (!std::isfinite(p.y[i])) return "y";
  if (!std::isfinite(p.u[i])) return "u";
  if (!std::isfinite(p.v[i])) return "v";
  if (!std::isfinite(p.volume[i])) return "volume";
  if (!std::isfinite(p.depth[i])) return "depth";
  if (!std::isfinite(p.area[i])) return "area";
  return nullptr;
}

}  // namespace

Energy water_energy(const particles::SweParticles& p, double gravity_m_s2, double datum_m,
                    const swe::BedSource* bed) {
  Energy e;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const double z_b = bed ? bed->elevation(p.x[i], p.y[i]) : p.bed[i];
    e.kinetic += 0.5 * p.volume[i] * (p.u[i] * p.u[i] + p.v[i] * p.v[i]);
    e.potential += gravity_m_s2 * p.volume[i] * (0.5 * p.depth[i] + z_b - datum_m);
  }
  return e;
}

bool inside_or_on(const std::vector<std::array<double, 2>>& polygon, double x, double y) {
  double size = 0.0;
  for (const auto& v : polygon) size = std::max({size, std::abs(v[0]), std::abs(v[1])});
  const double tolerance = 1e-9 * std::max(size, 1.0);
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0, prev = n - 1; k < n; prev = k++) {
    const auto& a = polygon[prev];
    const auto& b = polygon[k];
    // On the edge a-b (within the tolerance): counts as inside; a wall reflection may leave
    // a particle exactly on the wall.
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double length2 = ex * ex + ey * ey;
    const double s =
        length2 > 0.0 ? std::clamp(((x - a[0]) * ex + (y - a[1]) * ey) / length2, 0.0, 1.0) : 0.0;
    if (std::hypot(x - (a[0] + s * ex), y - (a[1] + s * ey)) <= tolerance) return true;
    // Even-odd rule: crossings of a ray in +x.
    if ((a[1] > y) != (b[1] > y) && x < a[0] + (y - a[1]) / (b[1] - a[1]) * ex) inside = !inside;
  }
  return inside;
}

InvariantMonitor::InvariantMonitor(swe::Simulation& sim, InvariantBounds bounds)
    : bounds_(std::move(bounds)) {
  sim.refresh();
  const auto& p = sim.particles();
  datum_m_ = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.fluid_count(); ++i) datum_m_ = std::min(datum_m_, p.bed[i]);
  if (!std::isfinite(datum_m_)) datum_m_ = 0.0;
  initial_energy_ =
      water_energy(p, sim.settings().gravity_m_s2, datum_m_, bounds_.bed.get()).total();
  record_.min_depth_m = std::numeric_limits<double>::infinity();
  record_.min_time_step_s = std::numeric_limits<double>::infinity();
  record_.min_particles = record_.max_particles = p.fluid_count();
  record_.max_energy_growth = -std::numeric_limits<double>::infinity();
  lowest_energy_ = initial_energy_;
}

void InvariantMonitor::violate(const std::string& what) {
  if (record_.first_violation.empty()) record_.first_violation = what;
}

bool InvariantMonitor::check(swe::Simulation& sim) {
  sim.refresh();
  const auto& p = sim.particles();
  const std::size_t n = p.fluid_count();
  ++record_.steps_checked;
  record_.min_particles = std::min(record_.min_particles, n);
  record_.max_particles = std::max(record_.max_particles, n);
  const auto where = [&](std::size_t i) {
    std::ostringstream s;
    s << "step " << sim.steps() << ", t = " << sim.time() << " s, particle " << i << " at ("
      << p.x[i] << ", " << p.y[i] << ")";
    return s.str();
  };

  for (std::size_t i = 0; i < n; ++i) {
    if (const char* field = non_finite_field(p, i)) {
      ++record_.non_finite;
      violate(where(i) + ": " + field + " is not finite");
      continue;
    }
    record_.min_depth_m = std::min(record_.min_depth_m, p.depth[i]);
    if (!(p.depth[i] > 0.0)) violate(where(i) + ": depth " + std::to_string(p.depth[i]));
    record_.max_speed_m_s = std::max(record_.max_speed_m_s, std::hypot(p.u[i], p.v[i]));
    if (!bounds_.inside_polygon.empty() && !inside_or_on(bounds_.inside_polygon, p.x[i], p.y[i])) {
      ++record_.outside;
      violate(where(i) + ": behind a wall");
    }
  }

  const double volume_change = std::abs(sim.relative_volume_change());
  record_.max_volume_change = std::max(record_.max_volume_change, volume_change);
  if (!(volume_change <= bounds_.volume_change)) {
    std::ostringstream s;
    s << "step " << sim.steps() << ", t = " << sim.time() << " s: relative volume change "
      << volume_change << " exceeds " << bounds_.volume_change;
    violate(s.str());
  }

  const auto& ledger = sim.ledger();
  if (bounds_.closed && (ledger.removed_m3 != 0.0 || ledger.added_m3 != 0.0)) {
    std::ostringstream s;
    s << "step " << sim.steps() << ", t = " << sim.time() << " s: " << ledger.removed_m3
      << " m3 left and " << ledger.added_m3 << " m3 entered a closed scene";
    violate(s.str());
  }

  // The step the next advance takes; a collapse below the floor throws SimulationError here.
  record_.min_time_step_s = std::min(record_.min_time_step_s, sim.stable_time_step());

  if (!(initial_energy_ > 0.0)) return record_.first_violation.empty();
  const double energy =
      water_energy(p, sim.settings().gravity_m_s2, datum_m_, bounds_.bed.get()).total();
  lowest_energy_ = std::min(lowest_energy_, energy);
  record_.max_energy_rise =
      std::max(record_.max_energy_rise, (energy - lowest_energy_) / initial_energy_);
  const double growth = (energy - initial_energy_) / initial_energy_;
  record_.final_energy_change = growth;
  record_.max_energy_growth = std::max(record_.max_energy_growth, growth);
  if (bounds_.energy_growth >= 0.0 && !(growth <= bounds_.energy_growth)) {
    std::ostringstream s;
    s << "step " << sim.steps() << ", t = " << sim.time() << " s: energy grew by " << growth
      << " of its initial value (bound " << bounds_.energy_growth << ")";
    violate(s.str());
  }
  return record_.first_violation.empty();
}

}  // namespace swemps::verification

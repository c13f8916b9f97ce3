#pragma once
// What must hold after every step of any run, however hard the flow (docs/robustness.md):
// every value finite, every depth positive, volume conserved net of what entered and left,
// no particle behind a wall, and, in a closed scene without friction, total energy never
// growing. The hard-case suite checks these after every step; the monitor keeps the worst
// value of each so that the suite can report how close a run came to each bound.

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/bed.hpp"

namespace swemps::swe {
class Simulation;
}

namespace swemps::verification {

// Mechanical energy of the water per unit density (m^5 s^-2; times rho gives J):
//   E = sum_i V_i (|u_i|^2 / 2 + g (h_i / 2 + z_b,i - datum)).
// The potential part is the depth-integrated g z over the column, g V (z_b + h/2); the
// conservative scheme's force, and the seed scheme's summation gradient (for a fixed r_e), are
// exactly the force this potential gives, so without friction or dissipation the
// continuous-time motion keeps E constant. The datum
// only shifts E by g datum sum V, which is constant when volume is.
struct Energy {
  double kinetic = 0.0;    // m^5 s^-2
  double potential = 0.0;  // m^5 s^-2
  double total() const { return kinetic + potential; }
};
// The bed z_b,i is the particles' own field, sampled where each stood when the last step's
// forces were taken; with `bed` it is sampled where each stands now. The two differ by a
// step's travel up or down the slope, which on a steep bed is far above the round-off an
// energy check resolves.
Energy water_energy(const particles::SweParticles& p, double gravity_m_s2, double datum_m,
                    const swe::BedSource* bed = nullptr);

// Bounds a run must stay within. Each check is skipped when its bound is not set.
struct InvariantBounds {
  // |V - V_expected| / (V_0 + V_in) (Simulation::relative_volume_change).
  double volume_change = 1e-12;
  // Closed frictionless scenes: (E - E_0) / E_0 must stay at or below this; E measured from
  // the lowest bed of the start (datum). Negative: no energy check (open or rough scenes).
  double energy_growth = -1.0;
  // A closed scene: no water may leave (through the domain's edge or an outflow) nor enter.
  bool closed = false;
  // A closed wall polygon (counter-clockwise or clockwise): every particle must lie inside it
  // or on it. Empty: no check.
  std::vector<std::array<double, 2>> inside_polygon;
  // The scene's bed, for the energy (water_energy); null: the particles' sampled field, exact
  // only on a level bed.
  std::shared_ptr<const swe::BedSource> bed;
};

// The worst values met so far, and the first violation.
struct InvariantRecord {
  std::size_t steps_checked = 0;
  std::size_t non_finite = 0;       // particle fields that were NaN or infinite (summed)
  double min_depth_m = 0.0;         // smallest depth of any particle at any step
  double max_volume_change = 0.0;   // largest |relative volume change|
  double max_energy_growth = 0.0;   // largest (E - E_0) / E_0 (negative when E only fell)
  // Largest rise of E above its lowest value so far, / E_0: what E_0 as the only reference
  // would hide when energy first falls (a shock) and then creeps back up.
  double max_energy_rise = 0.0;
  double final_energy_change = 0.0; // (E - E_0) / E_0 at the last check
  double max_speed_m_s = 0.0;       // largest particle speed at any step
  double min_time_step_s = 0.0;     // smallest stable step (eq 13 and the effects' limits)
  std::size_t outside = 0;          // particles found outside the wall polygon (summed)
  std::size_t min_particles = 0, max_particles = 0;
  std::string first_violation;      // empty while every bound holds
};

class InvariantMonitor {
 public:
  // Takes E_0 and the datum from the simulation's state now (refreshed first). A scene that
  // starts dry (E_0 = 0) gets no energy check.
  InvariantMonitor(swe::Simulation& sim, InvariantBounds bounds);
  // Checks the state after a step (refreshes it: the sums the next step uses). Returns false
  // once any bound has been broken; the first break is described in record().first_violation.
  bool check(swe::Simulation& sim);
  const InvariantRecord& record() const { return record_; }
  double initial_energy() const { return initial_energy_; }

 private:
  void violate(const std::string& what);

  InvariantBounds bounds_;
  InvariantRecord record_;
  double datum_m_ = 0.0;
  double initial_energy_ = 0.0;
  double lowest_energy_ = 0.0;
};

// True if (x, y) lies inside the closed polygon or on its boundary (within 1e-9 of its
// size).
bool inside_or_on(const std::vector<std::array<double, 2>>& polygon, double x, double y);

}  // namespace swemps::verification
